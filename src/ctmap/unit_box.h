#pragma once
/// \file unit_box.h
/// A mesh's bounding box as the pipeline uses it: its diagonal (the scale of snapping and
/// tolerances) and the similarity into the unit box, where every stage works (map_texture) and the
/// map's input faces are found (input_faces.h), so nothing depends on the unit the mesh was saved in.
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "ctmap/errors.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// The length of the diagonal of `mesh`'s bounding box (0 for no vertices).
inline double diagonal(const TriMesh& mesh) {
    Eigen::AlignedBox3d box;
    for (const Vec3& p : mesh.positions) box.extend(p);
    return mesh.positions.empty() ? 0 : box.diagonal().norm();
}

/// The similarity that takes a mesh into the unit box [-1, 1]^3 (its largest side): the pipeline
/// works there, so a map does not depend on the unit the mesh was saved in (1e-300 or 1e300), and
/// every length and area the predicates and solvers see is of order 1.
struct UnitBox {
    Vec3 center = Vec3::Zero();
    double half = 1;  ///< half the largest side of the bounding box

    /// \throw BadInput if every vertex is at one point.
    static UnitBox of(const TriMesh& mesh) {
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
        for (const Vec3& p : mesh.positions) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        UnitBox b;
        b.center = 0.5 * lo + 0.5 * hi;  // halves first: no overflow near the largest doubles
        b.half = (0.5 * hi - 0.5 * lo).maxCoeff();
        if (!(b.half > 0) || !std::isfinite(b.half))
            throw BadInput("", "the mesh has no extent: all its vertices are at one point");
        return b;
    }
    Vec3 in(const Vec3& p) const { return (p - center) / half; }
    Vec3 out(const Vec3& q) const { return q * half + center; }
};

}  // namespace ctmap
