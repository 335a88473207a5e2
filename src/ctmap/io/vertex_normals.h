#pragma once
/// \file vertex_normals.h
/// Per-vertex normals for the written maps (OBJ `vn`, glTF NORMAL), so viewers shade them smooth.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Area-weighted vertex normals (the sum of the incident faces' cross products, normalised).
/// A vertex on no face, or whose faces cancel out, gets (0, 0, 1). Computed in the mesh's unit
/// box, so meshes in units near 1e±300 neither overflow nor underflow.
std::vector<Vec3> vertex_normals(const TriMesh& mesh);

}  // namespace ctmap
