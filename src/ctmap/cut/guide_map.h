#pragma once
/// \file guide_map.h
/// A guide for the path search on twisted layouts (beyond paper §2.3): the biharmonic
/// interpolation of the features' image points over the mesh, the border on the border polygon. Where
/// the image twists the features against the surface (their image neighbours lie in other
/// directions on the mesh), shortest paths on the surface take routes the later paths cannot
/// follow, and the cut grows without bound; a path short in the guide runs near the preimage of
/// its straight image edge instead, which is where a valid map wants it.
#include <vector>

#include "ctmap/cut/work_mesh.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Per vertex of `mesh`, its place in the guide: border vertices on the straight image sides
/// between consecutive border features (by arc length), interior features at their image
/// points (`ft.points`), every other vertex where the square of the graph Laplacian vanishes
/// (smooth through the pins; a harmonic interpolation is flat around each pin with a spike at it).
/// The system is positive definite on a connected mesh with a pinned vertex. The guide may fold
/// where the layout twists; it is a metric for the search, not a map.
/// \pre `mesh` is a disc; `feature_vertex` holds distinct vertex ids, one per point of `ft`;
///      `ft.border` lists the border features in the mesh border's order.
/// \throw BadInput if no feature lies on the border; SolverError if the Laplacian cannot be factorised.
std::vector<Vec2> guide_map(const TriMesh& mesh, const std::vector<int>& feature_vertex, const FeatureTriangulation& ft);

/// Extends `guide` (one entry per vertex of the input `mesh.input_faces` refer to, then per
/// vertex added since) to every vertex of the work mesh: a vertex inside an input face takes
/// the guide interpolated at its barycentric coordinates. Vertices with no face (removed by
/// straightening) get zero.
void extend_guide(const WorkMesh& mesh, std::vector<Vec2>& guide);

}  // namespace ctmap
