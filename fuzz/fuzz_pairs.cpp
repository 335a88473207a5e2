// libFuzzer target for ctmap::parse_pairs (the `ctmap morph` pairs JSON, parsed from memory),
// followed by writing an accepted file back and parsing that again (it must be accepted).
#include "ctmap/errors.h"
#include "ctmap/morph/pairs.h"
#include "fuzz_common.h"

#include <cstdlib>
#include <cstdio>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static constexpr const char* kTarget = "parse_pairs";
    const std::string text(reinterpret_cast<const char*>(data), size);
    ctmap::fuzz::expect_bad_input_only(kTarget, [&] {
        const ctmap::PairSet set = ctmap::parse_pairs(text, "/nonexistent/ctmap_fuzz/pairs.json");
        const std::string back = ctmap::pairs_to_json(set);
        try {
            const ctmap::PairSet again = ctmap::parse_pairs(back, "/nonexistent/ctmap_fuzz/back.json");
            if (again.pairs.size() != set.pairs.size()) std::abort();
        } catch (const ctmap::BadInput& e) {
            std::fprintf(stderr, "parse_pairs: the written-back file is refused: %s\n", e.what());
            std::abort();
        }
    });
    return 0;
}
