#pragma once
/// \file surface_distance.h
/// Distances from points to a triangle surface (CGAL's AABB tree): how far a morphed vertex is
/// from the target surface, and the one-sided Hausdorff distance between two surfaces.
#include <memory>
#include <vector>

#include "ctmap/mesh.h"
#include "ctmap/surface_locator.h"

namespace ctmap {

/// Distances to the surface of one mesh.
/// (SurfaceLocator, whose distance queries these are.)
using SurfaceDistance = SurfaceLocator;

/// The one-sided Hausdorff distance from `from` to `to`, sampled at `from`'s vertices, edge
/// midpoints and face centroids and at `samples_per_face` more points per face (a fixed pattern).
double hausdorff_from(const TriMesh& from, const TriMesh& to, int samples_per_face = 3);

/// The mean edge length of `mesh` (each edge once).
double mean_edge_length(const TriMesh& mesh);

}  // namespace ctmap
