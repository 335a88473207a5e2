#include "ctmap/io/glb_container.h"

#include <cstdint>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

/// The little-endian 32-bit word at `at` (the caller checked that 4 bytes are there).
std::uint64_t word(const std::string& bytes, std::size_t at) {
    std::uint64_t v = 0;
    for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    return v;
}

}  // namespace

void check_glb_container(const std::string& bytes, const std::string& path) {
    const std::uint64_t size = bytes.size();
    if (size > 0xFFFFFFFFull)
        throw BadInput(path, "a binary glTF file of " + std::to_string(size) + " bytes (the format's limit is 4 GiB)");
    if (size < 20 || bytes.compare(0, 4, "glTF") != 0)
        throw BadInput(path, "not a binary glTF file (it does not start with a 'glTF' header and a chunk)");
    if (word(bytes, 4) != 2)
        throw BadInput(path, "binary glTF version " + std::to_string(word(bytes, 4)) + " (ctmap reads version 2)");
    const std::uint64_t length = word(bytes, 8);
    if (length > size)
        throw BadInput(path, "the GLB header gives a length of " + std::to_string(length) + " bytes, the file has " +
                                 std::to_string(size));
    const std::uint64_t json_end = 20 + word(bytes, 12);
    if (json_end > length)
        throw BadInput(path, "the GLB's JSON chunk runs past the file's stated length (" + std::to_string(json_end) +
                                 " > " + std::to_string(length) + " bytes)");
    if (json_end == length) return;  // no BIN chunk
    if (json_end + 8 > length)
        throw BadInput(path, "the GLB's BIN chunk header runs past the file's stated length (" +
                                 std::to_string(json_end + 8) + " > " + std::to_string(length) + " bytes)");
    const std::uint64_t bin_end = json_end + 8 + word(bytes, json_end);
    if (bin_end > length)
        throw BadInput(path, "the GLB's BIN chunk runs past the file's stated length (" + std::to_string(bin_end) +
                                 " > " + std::to_string(length) + " bytes)");
}

}  // namespace ctmap
