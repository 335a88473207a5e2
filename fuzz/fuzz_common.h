#pragma once
/// \file fuzz_common.h
/// What every ctmap fuzz target shares (README.md): the input file the path-taking readers read,
/// and the rule that bad input must come out as BadInput.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>

#include <unistd.h>

#include "ctmap/errors.h"
#include "ctmap/mesh.h"

namespace ctmap::fuzz {

/// A private folder for this process, `ctmap_fuzz_XXXXXX` (so that paths a file names relative to itself, glTF buffer
/// URIs and OBJ mtllibs, find nothing), removed at normal exit.
/// The folder is made in $TMPDIR (else /tmp); scripts/fuzz.sh points that into its run folder, as a
/// crash ends the process without the cleanup. (A plain char array: a std::string would be
/// destroyed before the atexit handler that reads it.)
inline const char* scratch_dir() {
    static char dir[4096];
    static const bool made = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::snprintf(dir, sizeof dir, "%s/ctmap_fuzz_XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(dir)) {
            std::perror("ctmap fuzz: mkdtemp");
            std::abort();
        }
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(dir, ec);
        });
        return true;
    }();
    (void)made;
    return dir;
}

/// Writes the fuzzer's bytes to `<scratch>/input<ext>` (the readers dispatch on the extension)
/// and returns that path. The same file is rewritten each iteration.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const char* ext) {
    const std::string path = std::string(scratch_dir()) + "/input" + ext;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) {
        std::perror("ctmap fuzz: cannot write the input file");
        std::abort();
    }
    return path;
}

/// Runs `read`: BadInput (and its children) is the expected answer to bad bytes; anything else
/// escaping (std::bad_alloc, InternalError, a CGAL assertion, a json or std::length_error, ...)
/// breaks the readers' contract and aborts, which libFuzzer reports as a crash.
template <class F>
void expect_bad_input_only(const char* target, F&& read) {
    // CTMAP_FUZZ_VERBOSE=1 says what each input came to (for checking seeds and triaging).
    static const bool verbose = std::getenv("CTMAP_FUZZ_VERBOSE") != nullptr;
    try {
        read();
        if (verbose) std::fprintf(stderr, "==ctmap-fuzz== %s: accepted\n", target);
    } catch (const BadInput& e) {
        if (verbose) std::fprintf(stderr, "==ctmap-fuzz== %s: BadInput: %s\n", target, e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\n==ctmap-fuzz== %s: an exception other than BadInput escaped: %s: %s\n", target,
                     typeid(e).name(), e.what());
        std::abort();
    } catch (...) {
        std::fprintf(stderr, "\n==ctmap-fuzz== %s: a non-std exception escaped\n", target);
        std::abort();
    }
}

[[noreturn]] inline void broken_promise(const char* target, const std::string& what) {
    std::fprintf(stderr, "\n==ctmap-fuzz== %s: %s\n", target, what.c_str());
    std::abort();
}

/// What every mesh reader promises of a mesh it returns: triangles on existing vertices; with UVs,
/// one UV triangle per face on existing UVs (TexturedMesh's invariant, which write_obj relies on).
/// Finite positions are promised by read_mesh only (`finite`).
inline void check_returned_mesh(const char* target, const TriMesh& mesh, bool finite = false) {
    if (finite)
        for (std::size_t i = 0; i < mesh.positions.size(); ++i)
            if (!mesh.positions[i].allFinite())
                broken_promise(target, "returned a non-finite position at vertex " + std::to_string(i));
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int v : mesh.faces[f])
            if (v < 0 || v >= mesh.num_vertices())
                broken_promise(target, "returned face " + std::to_string(f) + " on vertex " + std::to_string(v) +
                                           " of " + std::to_string(mesh.num_vertices()));
}

inline void check_returned_mesh(const char* target, const TexturedMesh& tm) {
    check_returned_mesh(target, tm.mesh);
    if (tm.uvs.empty()) return;
    if (tm.uv_faces.size() != tm.mesh.faces.size())
        broken_promise(target, "returned " + std::to_string(tm.uv_faces.size()) + " UV faces for " +
                                   std::to_string(tm.mesh.faces.size()) + " faces");
    for (std::size_t f = 0; f < tm.uv_faces.size(); ++f)
        for (int v : tm.uv_faces[f])
            if (v < 0 || v >= int(tm.uvs.size()))
                broken_promise(target, "returned UV face " + std::to_string(f) + " on UV " + std::to_string(v) +
                                           " of " + std::to_string(tm.uvs.size()));
}

}  // namespace ctmap::fuzz
