#pragma once
/// \file triangulate_polygon.h
/// Polygons of a mesh file split into triangles on read (paper step 1: ctmap maps triangle meshes).
#include <cstddef>
#include <string>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Polygons with more corners than this are triangulated in their plane (a constrained Delaunay
/// triangulation, O(n log n)) instead of by CGAL's minimal-area hole filling, whose fallback is
/// cubic in the corners (a 3,000-corner face of a mutated file took minutes and gigabytes).
constexpr std::size_t kMaxHoleFillingCorners = 100;

/// Appends the triangles of polygon `poly` (vertex indices into `positions`) to `out`, oriented
/// like the polygon (its Newell normal). A triangle is kept as it is. Up to
/// kMaxHoleFillingCorners corners: CGAL's minimal-area polyline triangulation; larger polygons
/// must be simple when projected on their Newell plane.
/// \pre every index of `poly` is below positions.size(); poly.size() >= 3.
/// \throw BadInput naming `path` and face `face_index` if the polygon cannot be triangulated.
void triangulate_polygon(const std::string& path, std::size_t face_index, const std::vector<std::size_t>& poly,
                         const std::vector<Vec3>& positions, std::vector<Tri>& out);

}  // namespace ctmap
