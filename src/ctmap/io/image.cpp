#include "ctmap/io/image.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <libexif/exif-data.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/image_bytes.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/jpeg_decode.h"

namespace ctmap {
namespace {

/// No texture ctmap maps has more pixels than this (16k x 16k); larger headers are broken files.
constexpr std::int64_t kMaxPixels = std::int64_t(1) << 28;
constexpr std::int64_t kMaxPixelsPerByte = 16384;

std::string reason() {
    const char* r = stbi_failure_reason();
    return r && *r ? std::string(" (") + r + ")" : std::string();
}

/// The bytes of an image file or buffer checked for what stb_image trusts (image_bytes.h), its
/// header read (a JPEG's by libjpeg-turbo: io/jpeg_decode), and sizes no real texture has
/// refused before any pixel is allocated.
struct CheckedImage {
    std::string format;  ///< "PNG" or "JPEG"
    std::string bytes;   ///< what the decoder may be given
    int width = 0, height = 0;  ///< as stored (before EXIF orientation)
};

CheckedImage check_image_bytes(const std::string& bytes, const std::string& name) {
    CheckedImage c;
    c.format = image_format(bytes);
    if (c.format.empty()) throw BadInput(name, "not a PNG or JPEG image (unrecognised file signature)");
    c.bytes = sanitized_image_bytes(bytes, name);
    if (c.bytes.size() > std::size_t(std::numeric_limits<int>::max()))
        throw BadInput(name, "the image file is too large (over 2 GB)");
    int n = 0;
    if (c.format == "JPEG") read_jpeg_size(c.bytes, name, c.width, c.height);
    else if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(c.bytes.data()), int(c.bytes.size()), &c.width,
                               &c.height, &n))
        throw BadInput(name, "the " + c.format + " header is truncated or corrupt" + reason());
    if (c.width <= 0 || c.height <= 0) throw BadInput(name, "the image has no pixels");
    // No real PNG or JPEG packs more pixels per byte than this (deflate's limit is ~1032 bytes
    // per byte, 8 pixels a byte at 1 bit; a flat JPEG block costs bits): a 1 KB file declaring
    // 64508 x 4113 pixels is a corrupt header, and decoding it took seconds.
    if (double(c.width) * c.height > double(kMaxPixelsPerByte) * double(bytes.size()))
        throw BadInput(name, "the " + c.format + " header declares " + std::to_string(c.width) + " x " +
                                 std::to_string(c.height) + " pixels, far more than its " + std::to_string(bytes.size()) +
                                 " bytes can hold (a corrupt header)");
    if (std::int64_t(c.width) * c.height > kMaxPixels)
        throw BadInput(name, "the image is too large (" + std::to_string(c.width) + " x " + std::to_string(c.height) +
                                 " pixels; at most " + std::to_string(kMaxPixels) + " are supported)");
    return c;
}

/// Orientations 5-8 swap width and height.
bool swaps_axes(int orientation) { return orientation >= 5 && orientation <= 8; }

/// The pixels of `src` (w x h, 4 channels) as shown for EXIF `orientation` (TIFF 6.0 tag 274).
std::vector<std::uint8_t> orient(const std::uint8_t* src, int w, int h, int orientation) {
    const int dw = swaps_axes(orientation) ? h : w, dh = swaps_axes(orientation) ? w : h;
    std::vector<std::uint8_t> out(std::size_t(w) * h * 4);
    for (int y = 0; y < dh; ++y)
        for (int x = 0; x < dw; ++x) {
            int sx = x, sy = y;  // the stored pixel shown at (x, y)
            switch (orientation) {
                case 2: sx = w - 1 - x; break;
                case 3: sx = w - 1 - x, sy = h - 1 - y; break;
                case 4: sy = h - 1 - y; break;
                case 5: sx = y, sy = x; break;
                case 6: sx = y, sy = h - 1 - x; break;
                case 7: sx = w - 1 - y, sy = h - 1 - x; break;
                case 8: sx = w - 1 - y, sy = x; break;
                default: break;
            }
            std::memcpy(&out[(std::size_t(y) * dw + x) * 4], src + (std::size_t(sy) * w + sx) * 4, 4);
        }
    return out;
}

}  // namespace

int exif_orientation(const std::string& bytes) {
    if (bytes.size() < 4 || (unsigned char)bytes[0] != 0xFF || (unsigned char)bytes[1] != 0xD8) return 1;
    ExifData* ed = exif_data_new_from_data(reinterpret_cast<const unsigned char*>(bytes.data()),
                                           unsigned(std::min<std::size_t>(bytes.size(), 1 << 16)));
    if (!ed) return 1;
    int o = 1;
    if (ExifEntry* e = exif_content_get_entry(ed->ifd[EXIF_IFD_0], EXIF_TAG_ORIENTATION);
        e && e->format == EXIF_FORMAT_SHORT && e->components >= 1 && e->data && e->size >= 2)
        o = exif_get_short(e->data, exif_data_get_byte_order(ed));
    exif_data_unref(ed);
    return o >= 1 && o <= 8 ? o : 1;
}

Image decode_image(const std::string& bytes, const std::string& name) {
    const CheckedImage c = check_image_bytes(bytes, name);
    int w = 0, h = 0, n = 0;
    // The stored pixels (RGBA, before EXIF orientation), from the decoder of the format.
    std::vector<std::uint8_t> stored;
    if (c.format == "JPEG") {
        stored = decode_jpeg_rgba(c.bytes, name, w, h);
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> data(
            stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(c.bytes.data()), int(c.bytes.size()), &w, &h, &n, 4),
            stbi_image_free);
        if (!data) throw BadInput(name, "the " + c.format + " image data is truncated or corrupt" + reason());
        stored.assign(data.get(), data.get() + std::size_t(w) * h * 4);
    }
    Image img;
    img.exif_orientation = c.format == "JPEG" ? exif_orientation(bytes) : 1;
    img.width = swaps_axes(img.exif_orientation) ? h : w;
    img.height = swaps_axes(img.exif_orientation) ? w : h;
    img.channels = 4;
    img.pixels = img.exif_orientation == 1 ? std::move(stored) : orient(stored.data(), w, h, img.exif_orientation);
    img.path = name;
    return img;
}

Image read_image(const std::string& path) { return decode_image(read_input_file(path, "image file"), path); }

void read_image_size(const std::string& path, int& width, int& height) {
    const std::string bytes = read_input_file(path, "image file");
    const CheckedImage c = check_image_bytes(bytes, path);
    const int o = c.format == "JPEG" ? exif_orientation(bytes) : 1;
    width = swaps_axes(o) ? c.height : c.width;
    height = swaps_axes(o) ? c.width : c.height;
}

std::string encode_png(const Image& image) {
    std::string out;
    const int ok = stbi_write_png_to_func(
        [](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<char*>(data), size); },
        &out, image.width, image.height, image.channels, image.pixels.data(), image.width * image.channels);
    if (!ok) throw InternalError("could not encode the image as PNG");
    return out;
}

void write_png(const Image& image, const std::string& path) {
    AtomicFile out(path);
    const int ok = stbi_write_png(out.temp_path().c_str(), image.width, image.height, image.channels,
                                  image.pixels.data(), image.width * image.channels);
    if (!ok) throw InternalError(path + ": could not write the PNG image");
    out.commit();
}

}  // namespace ctmap
