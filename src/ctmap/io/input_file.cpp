#include "ctmap/io/input_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ctmap/errors.h"

namespace ctmap {

void check_input_file(const std::string& path, const std::string& what) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) throw BadInput(path, "no such " + what);
    if (fs::is_directory(st)) throw BadInput(path, "is a directory, not a " + what);
    if (!fs::is_regular_file(st))
        throw BadInput(path, "is not a regular file (a pipe, a device or a socket): give a " + what + " on disc");
    if (fs::file_size(path, ec) == 0 && !ec) throw BadInput(path, "the " + what + " is empty");
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw BadInput(path, "cannot be opened for reading");
}

std::string read_input_file(const std::string& path, const std::string& what) {
    check_input_file(path, what);
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw BadInput(path, "could not be read to its end");
    return std::move(ss).str();
}

std::size_t utf8_bom_length(const std::string& text) {
    return text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
}

}  // namespace ctmap
