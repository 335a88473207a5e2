#include "ctmap/io/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <fstream>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

/// Removes the temporaries `.<name>.tmp<pid>_<n>` of `name` in `dir` whose process is gone: what
/// a run killed by a signal (SIGKILL, the OOM killer) left behind; a live run's are kept.
void remove_stale_temporaries(const std::filesystem::path& dir, const std::string& name) {
    namespace fs = std::filesystem;
    const std::string prefix = "." + name + ".tmp";
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string entry = it->path().filename().string();
        if (entry.rfind(prefix, 0) != 0) continue;
        const std::string rest = entry.substr(prefix.size());
        const std::size_t us = rest.find('_');
        if (us == 0 || us == std::string::npos || us > 9 || rest.find_first_not_of("0123456789_") != std::string::npos) continue;
        const long pid = std::stol(rest.substr(0, us));
        if (pid <= 0 || pid == long(::getpid())) continue;
        if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
        std::error_code rm;
        fs::remove(it->path(), rm);
    }
}

}  // namespace

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
    static std::atomic<int> counter{0};
    namespace fs = std::filesystem;
    const fs::path t(target_);
    if (t.filename().empty()) throw BadInput(target_, "an output path must name a file");
    const fs::path dir = t.has_parent_path() ? t.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw BadInput(target_, "the output folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(t, ec)) throw BadInput(target_, "the output path is a folder; name a file");
    remove_stale_temporaries(dir, t.filename().string());
    temp_ = (dir / ("." + t.filename().string() + ".tmp" + std::to_string(::getpid()) + "_" +
                    std::to_string(counter++)))
                .string();
}

AtomicFile::AtomicFile(AtomicFile&& o) noexcept
    : target_(std::move(o.target_)), temp_(std::move(o.temp_)), committed_(o.committed_) {
    o.committed_ = true;  // the moved-from object owns nothing
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        std::error_code ec;
        std::filesystem::remove(temp_, ec);
    }
}

void AtomicFile::commit() {
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);
    if (ec) throw InternalError(target_ + ": could not write the output (" + ec.message() + ")");
    committed_ = true;
}

std::string OutputSet::add(const std::string& target) {
    files_.emplace_back(target);
    return files_.back().temp_path();
}

void OutputSet::commit_all() {
    std::size_t done = 0;
    try {
        for (; done < files_.size(); ++done) files_[done].commit();
    } catch (...) {
        std::error_code ec;  // all or nothing: take back the outputs already renamed into place
        for (std::size_t i = 0; i < done; ++i) std::filesystem::remove(files_[i].target(), ec);
        throw;
    }
}

void write_text_file(const std::string& path, const std::string& content) {
    AtomicFile out(path);
    {
        std::ofstream os(out.temp_path(), std::ios::binary);
        os << content;
        if (!os.flush()) throw InternalError(path + ": could not write the file");
    }
    out.commit();
}

}  // namespace ctmap
