#pragma once
/// \file read_mesh.h
/// Mesh input (paper step 1): OFF, OBJ, PLY and STL through CGAL's polygon-soup readers.
#include <string>

#include "ctmap/mesh.h"

namespace ctmap {

/// Reads a polygon mesh and returns it as triangles.
/// Polygons with more than three corners are triangulated on read (CGAL's minimal-area polyline
/// triangulation, oriented like the polygon). The input vertex order is kept: vertex i of the
/// file is vertex i of the result, at the same position.
/// \pre `path` names a readable .off, .obj, .ply or .stl file (case-insensitive extension).
/// \throw BadInput if the file is missing, empty, unreadable, has an unknown extension, no faces,
///        a face index out of range, a face with fewer than 3 corners, or a non-finite coordinate.
///        The message names the file and the problem.
TriMesh read_mesh(const std::string& path);

}  // namespace ctmap
