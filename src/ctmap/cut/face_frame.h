#pragma once
/// \file face_frame.h
/// The plane in which the cut re-triangulates a face: its affine frame with corners A(0,0),
/// B(1,0), C(1,1), and CGAL's constrained Delaunay triangulation there (exact predicates). Each
/// side is a line on which the coordinates of its points are exact (y = 0, x = 1, x = y), so
/// points on a side stay collinear in floating point and the triangulation makes no slivers
/// along sides.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

namespace ctmap::face_frame {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

/// The point at parameter `s` from corner k along side k (from corner k to corner k + 1).
inline K::Point_2 side_point(int k, double s) {
    if (k == 0) return {s, 0.0};
    if (k == 1) return {1.0, s};
    return {1.0 - s, 1.0 - s};
}

}  // namespace ctmap::face_frame
