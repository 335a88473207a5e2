#include "ctmap/io/output_paths.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

namespace fs = std::filesystem;

/// The path with links and `..` resolved as far as it exists (weakly_canonical), made absolute.
fs::path resolved(const std::string& p) {
    std::error_code ec;
    fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
    if (ec) r = fs::absolute(p, ec).lexically_normal();
    return r;
}

/// Creates and removes a probe file in the folder of `target`.
void probe_writable(const std::string& target, const std::string& role) {
    const fs::path t(target);
    const fs::path dir = t.has_parent_path() ? t.parent_path() : fs::path(".");
    const std::string probe = (dir / ("." + t.filename().string() + ".probe" + std::to_string(::getpid()))).string();
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        const int err = errno;
        throw BadInput(target, role + ": cannot create a file in the folder '" + dir.string() + "' (" +
                                   std::strerror(err) + ")");
    }
    ::close(fd);
    ::unlink(probe.c_str());
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec) return true;
    return resolved(a) == resolved(b);
}

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const NamedPath& o = outputs[i];
        if (o.path.empty()) continue;
        for (const NamedPath& in : inputs)
            if (!in.path.empty() && same_file(o.path, in.path))
                throw BadInput(o.path, o.role + " is the same file as " + in.role + " (" + in.path +
                                           "): it would be overwritten; choose another output name");
        for (std::size_t j = 0; j < i; ++j)
            if (!outputs[j].path.empty() && same_file(o.path, outputs[j].path))
                throw BadInput(o.path, o.role + " is the same file as " + outputs[j].role + " (" + outputs[j].path +
                                           "): each output needs its own name");
    }
    for (const NamedPath& o : outputs) {
        if (o.path.empty()) continue;
        const fs::path t(o.path);
        if (t.filename().empty() || t.filename() == "." || t.filename() == "..")
            throw BadInput(o.path, o.role + ": an output path must name a file");
        std::error_code ec;
        if (fs::is_directory(t, ec)) throw BadInput(o.path, o.role + " is a folder; name a file");
        if (fs::exists(t, ec) && !fs::is_regular_file(t, ec))
            throw BadInput(o.path, o.role + " exists and is not a regular file (a device, a pipe or a socket)");
        const fs::path dir = t.has_parent_path() ? t.parent_path() : fs::path(".");
        if (!fs::exists(dir, ec)) throw BadInput(o.path, o.role + ": the output folder '" + dir.string() + "' does not exist");
        if (!fs::is_directory(dir, ec)) throw BadInput(o.path, o.role + ": '" + dir.string() + "' is not a folder");
        probe_writable(o.path, o.role);
    }
}

}  // namespace ctmap
