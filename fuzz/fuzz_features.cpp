// libFuzzer target for ctmap::parse_features (the features JSON, parsed from memory), followed by
// what `ctmap map` does next with an accepted file: units to pixels, and writing it back.
#include "ctmap/io/features.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static constexpr const char* kTarget = "parse_features";
    const std::string text(reinterpret_cast<const char*>(data), size);
    ctmap::fuzz::expect_bad_input_only(kTarget, [&] {
        ctmap::FeatureSet fs = ctmap::parse_features(text, "/nonexistent/ctmap_fuzz/features.json");
        const std::string back = ctmap::features_to_json(fs);
        int w = 1024, h = 768;
        if (fs.image_size && (*fs.image_size)[0] > 0 && (*fs.image_size)[1] > 0) {
            w = (*fs.image_size)[0];
            h = (*fs.image_size)[1];
        }
        ctmap::resolve_units(fs, w, h);
    });
    return 0;
}
