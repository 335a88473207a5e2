#pragma once
/// \file image_bytes.h
/// Checks on PNG and JPEG bytes made before stb_image decodes them (issue 17's fuzzing): Debian's
/// stb_image writes past a Huffman table whose code counts sum beyond 256 (UBSan: index 257 of
/// stbi_uc[257]), and hands memcpy a null pointer for an empty IDAT chunk before any data.
#include <string>

namespace ctmap {

/// "PNG" or "JPEG" from the first bytes, or empty for anything else.
std::string image_format(const std::string& bytes);

/// The bytes stb_image may be given: a JPEG whose Huffman tables (DHT segments) are each
/// well-formed passes unchanged; a PNG loses its empty IDAT chunks (they carry no pixel data,
/// so the picture is the same). \throw BadInput naming `name` for a corrupt Huffman table.
std::string sanitized_image_bytes(const std::string& bytes, const std::string& name);

}  // namespace ctmap
