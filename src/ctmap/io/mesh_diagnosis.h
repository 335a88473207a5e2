#pragma once
/// \file mesh_diagnosis.h
/// Why a mesh file is broken, in words. CGAL's readers only report *that* they failed, and the OFF
/// reader allocates whatever its header declares before reading a single vertex. These functions
/// look at the file itself: before the reader, whether the declared counts can fit in the file at
/// all; after a failed read, the first specific problem (a NaN coordinate, an index out of range,
/// a truncated file, binary garbage). They do not read meshes: CGAL does that.
#include <string>

namespace ctmap {

/// Checks what a reader would trust blindly, before it runs: the vertex and face counts that an
/// OFF header (text or BINARY) declares must fit in the file (CGAL's OFF reader allocates them
/// first); a binary STL must have the size its header declares and only finite coordinates
/// (CGAL's STL reader merges a NaN corner into another vertex without a word). Other formats,
/// and headers too broken to read, pass: the reader and diagnose_mesh_file() report them.
/// \pre `ext` is the lower-case extension with its dot (".off", ".stl", ...).
/// \throw BadInput naming `path` and the problem (truncated, NaN).
/// `bytes` are the file's, as the reader will parse them (read once by read_mesh).
void check_before_reading(const std::string& path, const std::string& ext, const std::string& bytes);

/// The first specific problem in a mesh file that a reader rejected, as a sentence naming the line
/// and the element ("line 5: vertex 1 has a non-finite coordinate 'nan' (NaN or infinity)"), or an
/// empty string when no specific problem is found.
/// \pre `ext` is the lower-case extension with its dot: ".off", ".obj", ".ply" or ".stl".
std::string diagnose_mesh_file(const std::string& path, const std::string& ext);

}  // namespace ctmap
