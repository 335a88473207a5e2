#pragma once
/// \file surface_locator.h
/// The closest point of a triangle surface to a query point (CGAL's AABB tree), with the face it
/// lies on: the morph's distances, the map's record of which input face each of its faces lies in,
/// and the bake onto another tessellation of the same surface all ask this one question.
#include <memory>

#include "ctmap/mesh.h"

namespace ctmap {

/// Where a query point meets the surface.
struct SurfacePoint {
    int face = -1;                  ///< the face of the mesh the closest point lies on
    Vec3 point = Vec3::Zero();      ///< the closest point
    double squared_distance = 0;    ///< from the query point to `point`
};

/// Closest-point queries on one mesh. Faces of zero area are left out (they hold no point a
/// nonzero-area neighbour does not). Thread-safe for queries once constructed.
class SurfaceLocator {
public:
    /// \pre `mesh` has at least one face of nonzero area. \throw BadInput otherwise (naming no file).
    explicit SurfaceLocator(const TriMesh& mesh);
    ~SurfaceLocator();
    SurfaceLocator(const SurfaceLocator&) = delete;
    SurfaceLocator& operator=(const SurfaceLocator&) = delete;
    /// The closest point of the surface to `p`, and its face.
    SurfacePoint closest(const Vec3& p) const;
    /// The distance from `p` to the surface.
    double distance(const Vec3& p) const;

private:
    struct Tree;
    std::unique_ptr<Tree> tree_;
};

}  // namespace ctmap
