#pragma once
/// \file image_bytes.h
/// Checks on PNG bytes made before stb_image decodes them (issue 17's fuzzing): Debian's stb_image
/// hands memcpy a null pointer for an empty IDAT chunk before any data, and grows its buffer to an
/// IDAT chunk's declared length before reading it. (JPEG goes to libjpeg-turbo: io/jpeg_decode.)
#include <string>

namespace ctmap {

/// "PNG" or "JPEG" from the first bytes, or empty for anything else.
std::string image_format(const std::string& bytes);

/// The bytes a decoder may be given: a PNG loses its empty IDAT chunks (they carry no pixel data,
/// so the picture is the same); anything else passes unchanged.
/// \throw BadInput naming `name` for an IDAT chunk longer than the bytes that follow it.
std::string sanitized_image_bytes(const std::string& bytes, const std::string& name);

}  // namespace ctmap
