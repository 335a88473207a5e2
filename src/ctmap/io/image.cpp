#include "ctmap/io/image.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <filesystem>
#include <memory>

#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"

namespace ctmap {
namespace {

void check_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec)) throw BadInput(path, "no such image file");
    if (fs::is_directory(path, ec)) throw BadInput(path, "is a directory, not an image");
    if (fs::file_size(path, ec) == 0) throw BadInput(path, "the image file is empty");
}

std::string reason() {
    const char* r = stbi_failure_reason();
    return r ? std::string(" (") + r + ")" : std::string();
}

}  // namespace

Image read_image(const std::string& path) {
    check_file(path);
    int w = 0, h = 0, n = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &n, 4), stbi_image_free);
    if (!data) throw BadInput(path, "not a readable PNG or JPEG image" + reason());
    if (w <= 0 || h <= 0) throw BadInput(path, "the image has no pixels");
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
