#include "ctmap/io/data_path.h"

#include <cstdlib>
#include <filesystem>

#include "ctmap/errors.h"

#ifndef CTMAP_SOURCE_DIR
#define CTMAP_SOURCE_DIR "."
#endif

namespace ctmap {
namespace {

std::vector<std::string> candidate_dirs() {
    namespace fs = std::filesystem;
    std::vector<std::string> dirs;
    if (const char* env = std::getenv("CTMAP_DATA"); env && *env) dirs.emplace_back(env);
    const fs::path src(CTMAP_SOURCE_DIR);
    dirs.push_back((src / "data").lexically_normal().string());  // the project's own features files
    dirs.push_back((src / ".." / "shared" / "data").lexically_normal().string());
    dirs.push_back((src / ".cache" / "data").lexically_normal().string());
    return dirs;
}

}  // namespace

std::vector<std::string> data_dirs() {
    std::vector<std::string> out;
    std::error_code ec;
    for (const std::string& d : candidate_dirs())
        if (std::filesystem::is_directory(d, ec)) out.push_back(d);
    return out;
}

std::string find_data_file(const std::string& relative) {
    namespace fs = std::filesystem;
    std::error_code ec;
    std::string searched;
    for (const std::string& d : candidate_dirs()) {
        const fs::path p = fs::path(d) / relative;
        if (fs::is_regular_file(p, ec)) return p.string();
        searched += "\n  " + d;
    }
    throw BadInput(relative, "example data not found; searched:" + searched +
                                 "\n(run scripts/setup.sh, or set CTMAP_DATA to a folder with meshes/ and images/)");
}

}  // namespace ctmap
