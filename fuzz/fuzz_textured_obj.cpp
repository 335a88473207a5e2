// libFuzzer target for ctmap::read_textured_obj (ctmap's own OBJ reader, with UVs and mtllib).
#include "ctmap/io/obj_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static constexpr const char* kTarget = "read_textured_obj";
    const std::string path = ctmap::fuzz::write_input(data, size, ".obj");
    ctmap::fuzz::expect_bad_input_only(kTarget, [&] {
        std::string image;
        ctmap::fuzz::check_returned_mesh(kTarget, ctmap::read_textured_obj(path, &image));
    });
    return 0;
}
