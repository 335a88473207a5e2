#pragma once
/// \file glb_container.h
/// The binary glTF container's layout, checked before tinygltf parses it: Debian's tinygltf
/// (2.7.0) bounds the BIN chunk's length by the file's length without its own 8-byte header, so a
/// chunk that claims up to 8 bytes past the end of the file was read past the end of the buffer
/// (ASan, heap-buffer-overflow in tinygltf::ParseBuffer: a fuzz finding of 2026-12-06,
/// fuzz/regressions/fuzz_glb/).
#include <string>

namespace ctmap {

/// Checks the GLB layout of `bytes` (the file `path`, under 4 GiB): a 12-byte header ("glTF",
/// version 2, a total length no larger than the file), a JSON chunk, and, where the total length
/// leaves room for one, a BIN chunk whose header and data both end within that length.
/// \throw BadInput naming `path` and what is wrong.
void check_glb_container(const std::string& bytes, const std::string& path);

}  // namespace ctmap
