#pragma once
/// \file starter_features.h
/// A starter features file for a mesh and an image (paper step 1 made easier): landmarks spread
/// over the mesh, placed in the image by a one-to-one map of the disc (Tutte's embedding onto an
/// ellipse inscribed in the image), so the set is always feasible. Users then move the image
/// points onto what they see in the photo; tests and benchmarks use such sets as real inputs.
#include <vector>

#include "ctmap/io/features.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Tutte's barycentric embedding with uniform weights, the border on the unit circle by 3D arc
/// length (counter-clockwise in the faces' orientation): one-to-one for a disc (Tutte 1963).
/// \pre `mesh` is a manifold disc. \throw SolverError if the sparse factorization fails.
std::vector<Vec2> tutte_map(const TriMesh& mesh);

/// `disc` (Tutte's map of `mesh`) with every interior vertex moved along its ray so that the disc
/// within radius r holds the share r^2 of the mesh's 3D area: still one-to-one (a monotone radial
/// map), the border still on the unit circle, and the interior no longer crowded in the middle.
/// \pre disc.size() == mesh.num_vertices(), every point in the closed unit disc.
std::vector<Vec2> spread_radially(const TriMesh& mesh, std::vector<Vec2> disc);

/// Options of `starter_features`.
struct StarterOptions {
    int border = 8;     ///< features on the mesh border, equally spaced by arc length (0: landmarks only)
    int interior = 12;  ///< interior features, spread by farthest-point sampling in 3D
    double margin = 0.05;  ///< the ellipse stays this fraction of the image size inside it
};

/// A feasible features set for `mesh` on a `width` x `height` image (pixels, DESIGN §4). With
/// `border_vertices`, those (on the mesh border) are the border features, named
/// border0, border1, ... in that order, instead of `options.border` equally spaced ones.
/// \pre `mesh` is a manifold disc; width, height > 0.
FeatureSet starter_features(const TriMesh& mesh, int width, int height, const StarterOptions& options = {},
                            const std::vector<int>* border_vertices = nullptr);

}  // namespace ctmap
