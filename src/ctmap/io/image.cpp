#include "ctmap/io/image.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <libexif/exif-data.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/input_file.h"

namespace ctmap {
namespace {

/// No texture ctmap maps has more pixels than this (16k x 16k); larger headers are broken files.
constexpr std::int64_t kMaxPixels = std::int64_t(1) << 28;

void check_file(const std::string& path) {
    check_input_file(path, "image file");
}

std::string reason() {
    const char* r = stbi_failure_reason();
    return r && *r ? std::string(" (") + r + ")" : std::string();
}

/// "PNG" or "JPEG" from the file's first bytes, or empty for anything else.
std::string format_of(const std::string& path) {
    unsigned char head[8] = {};
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(head), sizeof head);
    if (in.gcount() >= 8 && std::memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0) return "PNG";
    if (in.gcount() >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) return "JPEG";
    return {};
}

/// Reads the header (size only) and refuses sizes no real texture has, before any pixel is
/// allocated. Returns the format's name.
std::string check_header(const std::string& path) {
    const std::string format = format_of(path);
    if (format.empty()) throw BadInput(path, "not a PNG or JPEG image (unrecognised file signature)");
    int w = 0, h = 0, n = 0;
    if (!stbi_info(path.c_str(), &w, &h, &n))
        throw BadInput(path, "the " + format + " header is truncated or corrupt" + reason());
    if (w <= 0 || h <= 0) throw BadInput(path, "the image has no pixels");
    if (std::int64_t(w) * h > kMaxPixels)
        throw BadInput(path, "the image is too large (" + std::to_string(w) + " x " + std::to_string(h) +
                                 " pixels; at most " + std::to_string(kMaxPixels) + " are supported)");
    return format;
}

/// The first bytes of a file (enough for a JPEG's EXIF block, which must sit in its first 64 KiB).
std::string head_bytes(const std::string& path, std::size_t n = 1 << 16) {
    std::ifstream in(path, std::ios::binary);
    std::string s(n, '\0');
    in.read(s.data(), std::streamsize(n));
    s.resize(std::size_t(in.gcount()));
    return s;
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

Image read_image(const std::string& path) {
    check_file(path);
    const std::string format = check_header(path);
    int w = 0, h = 0, n = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &n, 4), stbi_image_free);
    if (!data) throw BadInput(path, "the " + format + " image data is truncated or corrupt" + reason());
    Image img;
    img.exif_orientation = format == "JPEG" ? exif_orientation(head_bytes(path)) : 1;
    img.width = swaps_axes(img.exif_orientation) ? h : w;
    img.height = swaps_axes(img.exif_orientation) ? w : h;
    img.channels = 4;
    if (img.exif_orientation == 1) img.pixels.assign(data.get(), data.get() + std::size_t(w) * h * 4);
    else img.pixels = orient(data.get(), w, h, img.exif_orientation);
    img.path = path;
    return img;
}

Image decode_image(const std::string& bytes, const std::string& name) {
    const auto* b = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int len = int(std::min<std::size_t>(bytes.size(), std::size_t(1) << 30));
    int w = 0, h = 0, n = 0;
    if (!stbi_info_from_memory(b, len, &w, &h, &n) || w <= 0 || h <= 0)
        throw BadInput(name, "the embedded texture is not a readable PNG or JPEG" + reason());
    if (std::int64_t(w) * h > kMaxPixels) throw BadInput(name, "the embedded texture is too large");
    std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load_from_memory(b, len, &w, &h, &n, 4), stbi_image_free);
    if (!data) throw BadInput(name, "the embedded texture is truncated or corrupt" + reason());
    Image img;
    img.exif_orientation = exif_orientation(bytes);
    img.width = swaps_axes(img.exif_orientation) ? h : w;
    img.height = swaps_axes(img.exif_orientation) ? w : h;
    img.channels = 4;
    if (img.exif_orientation == 1) img.pixels.assign(data.get(), data.get() + std::size_t(w) * h * 4);
    else img.pixels = orient(data.get(), w, h, img.exif_orientation);
    img.path = name;
    return img;
}

void read_image_size(const std::string& path, int& width, int& height) {
    check_file(path);
    const std::string format = check_header(path);
    int w = 0, h = 0, n = 0;
    stbi_info(path.c_str(), &w, &h, &n);
    const int o = format == "JPEG" ? exif_orientation(head_bytes(path)) : 1;
    width = swaps_axes(o) ? h : w;
    height = swaps_axes(o) ? w : h;
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
