#include "ctmap/io/image.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"

namespace ctmap {
namespace {

/// No texture ctmap maps has more pixels than this (16k x 16k); larger headers are broken files.
constexpr std::int64_t kMaxPixels = std::int64_t(1) << 28;

void check_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec)) throw BadInput(path, "no such image file");
    if (fs::is_directory(path, ec)) throw BadInput(path, "is a directory, not an image");
    if (fs::file_size(path, ec) == 0) throw BadInput(path, "the image file is empty");
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

}  // namespace

Image read_image(const std::string& path) {
    check_file(path);
    const std::string format = check_header(path);
    int w = 0, h = 0, n = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &n, 4), stbi_image_free);
    if (!data) throw BadInput(path, "the " + format + " image data is truncated or corrupt" + reason());
    Image img;
    img.width = w;
    img.height = h;
    img.channels = 4;
    img.pixels.assign(data.get(), data.get() + std::size_t(w) * h * 4);
    img.path = path;
    return img;
}

void write_png(const Image& image, const std::string& path) {
    AtomicFile out(path);
    const int ok = stbi_write_png(out.temp_path().c_str(), image.width, image.height, image.channels,
                                  image.pixels.data(), image.width * image.channels);
    if (!ok) throw InternalError(path + ": could not write the PNG image");
    out.commit();
}

}  // namespace ctmap
