// libFuzzer target for ctmap::read_mesh, built once per format (fuzz/CMakeLists.txt sets
// CTMAP_FUZZ_EXT to ".off", ".obj", ".ply" or ".stl"; read_mesh dispatches on it).
#include "ctmap/io/read_mesh.h"
#include "fuzz_common.h"

#ifndef CTMAP_FUZZ_EXT
#error "CTMAP_FUZZ_EXT must name the mesh extension, e.g. \".off\""
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static constexpr const char* kTarget = "read_mesh(" CTMAP_FUZZ_EXT ")";
    const std::string path = ctmap::fuzz::write_input(data, size, CTMAP_FUZZ_EXT);
    ctmap::fuzz::expect_bad_input_only(kTarget, [&] { ctmap::fuzz::check_returned_mesh(kTarget, ctmap::read_mesh(path), true); });
    return 0;
}
