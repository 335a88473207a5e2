#pragma once
/// \file image.h
/// Texture images (paper step 1): PNG and JPEG through stb_image.
#include <cstdint>
#include <string>
#include <vector>

namespace ctmap {

/// An 8-bit image, rows top to bottom (pixel (x, y) at `pixels[(y * width + x) * channels + c]`).
struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<std::uint8_t> pixels;
    std::string path;  ///< where it was read from (empty if made in memory)
};

/// Reads a PNG or JPEG file with all its pixels, as RGBA (4 channels).
/// \pre `path` names a PNG or JPEG file.
/// \throw BadInput naming the file if it is missing, a folder, empty, not a PNG/JPEG (by its
///        signature), truncated or corrupt, or larger than 2^28 pixels (checked from the header,
///        before any pixel is allocated).
Image read_image(const std::string& path);

/// Writes `image` as PNG to `path` (atomically: a temporary renamed into place).
/// \throw InternalError if the file cannot be written.
void write_png(const Image& image, const std::string& path);

}  // namespace ctmap
