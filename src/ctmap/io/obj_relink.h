#pragma once
/// \file obj_relink.h
/// A user's OBJ given a new material without touching its geometry (`ctmap bake --obj`, issue
/// 42): a rigged mesh keeps its vertex order, UVs, normals and faces byte for byte.
#include <string>

namespace ctmap {

/// `obj` (an OBJ file's text) with material `material` of the file `mtl_name`: a `mtllib` line
/// first, its own `mtllib` lines left out, each `usemtl` line replaced by `usemtl <material>`
/// and one added before the first face when it has none. Every other line, `v`, `vt`, `vn`,
/// `f`, `g`, `o`, `s` and comments, is kept byte for byte, in order, with its line ending.
/// \pre `mtl_name` and `material` hold no line break.
std::string relink_obj(const std::string& obj, const std::string& mtl_name, const std::string& material);

}  // namespace ctmap
