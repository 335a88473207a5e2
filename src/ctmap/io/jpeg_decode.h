#pragma once
/// \file jpeg_decode.h
/// JPEG photographs (paper step 1: the image the features are picked on) decoded with
/// libjpeg-turbo (Debian's libjpeg62-turbo), whose bit reader and marker parser are hardened by
/// years of fuzzing. Debian's stb_image shifts by 32 bits on a corrupt entropy-coded stream
/// (issue 17, fuzz/regressions/fuzz_image/stb-jpeg-bit-reader-underflow): JPEG no longer goes
/// through stb_image; PNG still does.
#include <cstdint>
#include <string>
#include <vector>

namespace ctmap {

/// Width and height of a JPEG as stored (before any EXIF orientation), read from its header.
/// \pre `bytes` start with a JPEG signature (FF D8 FF).
/// \throw BadInput naming `name` if the header is truncated or corrupt.
void read_jpeg_size(const std::string& bytes, const std::string& name, int& width, int& height);

/// Decodes a JPEG (baseline or progressive; grey, YCbCr, RGB, CMYK or YCCK) as RGBA rows top to
/// bottom, as stored (EXIF orientation not applied). Refuses what libjpeg reports as corrupt,
/// including the warnings it would otherwise paper over (a truncated file filled with grey, a bad
/// Huffman code), except stray bytes between segments, and files of more than 500 scans (as
/// libjpeg-turbo's own TurboJPEG API does: a crafted progressive file can take minutes).
/// \pre `bytes` start with a JPEG signature; its size was checked by the caller (io/image).
/// \throw BadInput naming `name` with libjpeg's reason.
std::vector<std::uint8_t> decode_jpeg_rgba(const std::string& bytes, const std::string& name, int& width,
                                           int& height);

}  // namespace ctmap
