// libFuzzer target for ctmap::read_image (PNG and JPEG through stb_image; the format comes from
// the file's signature, not its extension).
#include "ctmap/io/image.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static constexpr const char* kTarget = "read_image";
    const std::string path = ctmap::fuzz::write_input(data, size, ".png");
    ctmap::fuzz::expect_bad_input_only(kTarget, [&] {
        const ctmap::Image img = ctmap::read_image(path);
        if (img.width <= 0 || img.height <= 0 || img.channels != 4 ||
            img.pixels.size() != std::size_t(img.width) * img.height * 4)
            ctmap::fuzz::broken_promise(kTarget, "returned an image whose size and pixels disagree");
    });
    return 0;
}
