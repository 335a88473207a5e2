#pragma once
/// \file obj_io.h
/// Textured OBJ + MTL output and input (DESIGN §2, io/). UVs are written per face corner
/// (`f v/vt`), in OBJ's convention UV = (x / W, 1 - y / H), with the shortest decimal form that
/// reads back to the same double, so a write-read round trip is bitwise exact.
#include <string>
#include <vector>

#include "ctmap/io/atomic_file.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Writes `mesh` as OBJ to `obj_path` and a material file beside it (same stem, `.mtl`) whose
/// `map_Kd` points at `image` (a path written relative to the OBJ's folder; no map when empty).
/// The two files are registered in `outputs` and appear only when the caller commits it.
/// \pre uv_faces has one entry per face when uvs is non-empty.
/// \throw InternalError if a file cannot be written.
void write_obj(const TexturedMesh& mesh, const std::string& obj_path, const std::string& image, OutputSet& outputs);

/// Same with one material per chart (issue 13): faces of chart c (TexturedMesh::chart) use
/// `materials[c]`, each with its own `map_Kd`.
/// \throw BadInput if a chart id does not index `materials`; InternalError if a file cannot be written.
void write_obj(const TexturedMesh& mesh, const std::string& obj_path, const std::vector<ChartMaterial>& materials,
               OutputSet& outputs);

/// Same, committed at once.
void write_obj(const TexturedMesh& mesh, const std::string& obj_path, const std::string& image = "");
/// The MTL file `write_obj` writes beside `obj_path` for `materials`: each with its `map_Kd`
/// image, named relative to the OBJ's folder.
std::string mtl_text(const std::vector<ChartMaterial>& materials, const std::string& obj_path);

/// Reads an OBJ with optional texture coordinates (`v`, `vt`, `f v`, `f v/vt`, `f v/vt/vn`,
/// `f v//vn`, negative indices). Polygons are split into fans. CGAL's readers drop `vt`, so this
/// one is ctmap's own; it parses numbers with std::from_chars, which is correctly rounded.
/// `mtllib`/`usemtl` are read only to return the material's `map_Kd` image path in `image`.
/// \throw BadInput naming the file and line for malformed content or indices out of range.
/// `usemtl` names a chart (issue 13): faces after the n-th distinct material are chart n (all
/// chart 0 without any); `materials`, if given, receives per chart its material name and the
/// `map_Kd` image of the MTL file (empty when the MTL has none).
TexturedMesh read_textured_obj(const std::string& path, std::string* image = nullptr,
                               std::vector<ChartMaterial>* materials = nullptr);

}  // namespace ctmap
