#pragma once
/// \file image.h
/// Texture images (paper step 1): PNG through stb_image, JPEG through libjpeg-turbo (io/jpeg_decode).
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
    /// The EXIF orientation of the file (1-8; 1 = stored upright), already applied to `pixels`:
    /// width, height and pixels are the image as viewers show it.
    int exif_orientation = 1;
};

/// The EXIF orientation tag (1-8) of a JPEG file's bytes, or 1 when it has none (PNG, no EXIF,
/// an unreadable EXIF block).
int exif_orientation(const std::string& bytes);

/// Reads a PNG or JPEG file with all its pixels, as RGBA (4 channels), turned upright as viewers
/// show it when a JPEG's EXIF orientation says so (issue 17: pixel coordinates picked in a
/// viewer are in the upright image).
/// \pre `path` names a PNG or JPEG file.
/// \throw BadInput naming the file if it is missing, a folder, empty, not a PNG/JPEG (by its
///        signature), truncated or corrupt, or larger than 2^28 pixels (checked from the header,
///        before any pixel is allocated).
Image read_image(const std::string& path);

/// Decodes PNG or JPEG bytes held in memory (a texture embedded in a glTF file) as RGBA, with
/// `read_image`'s checks and EXIF rule; `name` names the bytes' source in messages.
/// \throw BadInput naming `name` if the bytes are not a readable PNG or JPEG.
Image decode_image(const std::string& bytes, const std::string& name);

/// The size of the image as `read_image` would return it (EXIF orientation applied), from the
/// header alone. \throw BadInput as read_image.
void read_image_size(const std::string& path, int& width, int& height);

/// `image` as PNG bytes in memory. \throw InternalError if encoding fails.
std::string encode_png(const Image& image);

/// Writes `image` as PNG to `path` (atomically: a temporary renamed into place).
/// \throw InternalError if the file cannot be written.
void write_png(const Image& image, const std::string& path);

}  // namespace ctmap
