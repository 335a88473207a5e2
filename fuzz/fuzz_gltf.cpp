// libFuzzer target for ctmap::read_glb (tinygltf), built twice: CTMAP_FUZZ_EXT ".glb" (binary
// glTF) and ".gltf" (JSON glTF); read_glb picks the loader by the extension.
#include "ctmap/io/glb_io.h"
#include "fuzz_common.h"

#ifndef CTMAP_FUZZ_EXT
#error "CTMAP_FUZZ_EXT must be \".glb\" or \".gltf\""
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static constexpr const char* kTarget = "read_glb(" CTMAP_FUZZ_EXT ")";
    const std::string path = ctmap::fuzz::write_input(data, size, CTMAP_FUZZ_EXT);
    ctmap::fuzz::expect_bad_input_only(kTarget, [&] {
        ctmap::GlbTexture texture;
        ctmap::fuzz::check_returned_mesh(kTarget, ctmap::read_glb(path, &texture));
    });
    return 0;
}
