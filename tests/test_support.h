#pragma once
// Helpers shared by the tests: data lookup, scratch folders, running the ctmap program.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "ctmap/io/data_path.h"
#include "support_paths.h"

namespace ctmap::test {

/// A real data file (meshes/..., images/..., features/...); the test fails if it is missing.
inline std::string data(const std::string& rel) { return ctmap::find_data_file(rel); }

/// A fresh scratch folder, removed when the object dies.
class TempDir {
public:
    TempDir() {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() / ("ctmap_test_" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    std::string operator/(const std::string& name) const { return (path_ / name).string(); }
    const std::filesystem::path& path() const { return path_; }
    /// Number of entries in the folder (to prove that no output was left behind).
    int count() const {
        int n = 0;
        for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(path_)) ++n;
        return n;
    }

private:
    std::filesystem::path path_;
};

inline void write_file(const std::string& path, const std::string& content) {
    std::ofstream os(path, std::ios::binary);
    os << content;
}

inline std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct RunResult {
    int code = -1;
    std::string out;  ///< stdout and stderr together
};

/// Runs the ctmap program with `args` (already quoted as needed) after the shell words `prefix`
/// (e.g. "timeout 60"), capturing its output.
inline RunResult run_ctmap_with_prefix(const std::string& prefix, const std::string& args) {
    RunResult r;
    const std::string cmd = prefix + " '" + ctmap_test::ctmap_binary() + "' " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

/// Runs the ctmap program with `args` (already quoted as needed), capturing its output.
inline RunResult run_ctmap(const std::string& args) { return run_ctmap_with_prefix("", args); }

inline std::string q(const std::string& s) { return "'" + s + "'"; }

}  // namespace ctmap::test
