#pragma once
/// \file locate_2d.h
/// Point location in a planar triangulation (a valid UV map): a uniform grid of the triangles'
/// bounding boxes, exact orientation tests inside a cell (issue 14: not a brute-force scan).
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Where a point lies in the triangulation.
struct Location {
    int face = -1;            ///< the triangle holding the point (-1: the triangulation is empty)
    Vec3 bary = Vec3::Zero(); ///< barycentric coordinates in that triangle, each in [0, 1], summing to 1
    int corner = -1;          ///< k if the point is exactly the triangle's corner k (then bary is e_k)
    bool inside = true;       ///< false: outside every triangle (rounding at the border); `face` is the nearest
};

/// Locates points in the triangles `faces` over the planar points `uv`.
class TriangleLocator {
public:
    /// \pre `uv` and `faces` form a valid map: triangles of one orientation, no overlaps
    ///      (certify's conditions); indices in range.
    TriangleLocator(const std::vector<Vec2>& uv, const std::vector<Tri>& faces);

    /// The triangle holding `p`, decided by exact orientation tests (a point on a shared edge
    /// gets one of its triangles). A point outside every triangle gets the nearest one, with its
    /// barycentric coordinates clamped to the triangle (`inside` false).
    Location locate(const Vec2& p) const;

private:
    int cell_index(int i, int j) const { return j * nx_ + i; }
    const std::vector<Vec2>& uv_;
    const std::vector<Tri>& faces_;
    Vec2 lo_, cell_;
    int nx_ = 1, ny_ = 1;
    std::vector<int> start_, items_;  ///< CSR lists of the triangles overlapping each cell
};

}  // namespace ctmap
