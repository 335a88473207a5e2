#pragma once
/// \file seam_guide.h
/// Where the seams should run when the shortest ones do not keep the features on their sides
/// (issue 40): each chart's region grown from its interior features (and the faces in no chart
/// from the mesh border loops that belong to no chart), as a multi-source front; a seam traced
/// with these weights is drawn to where two regions meet.
#include <vector>

#include "ctmap/cut/chart_outline.h"
#include "ctmap/cut/seam_paths.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Per vertex, a weight >= 1 for `seam_shortest_path`: 1 where the two nearest sources (3D
/// distance along edges) of different charts are equally far, up to 1 + `strength` at a source.
/// Empty when fewer than two kinds of source exist (nothing to run between).
/// \pre every feature vertex in range.
std::vector<double> seam_guide_weights(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                                       double strength = 8.0);

}  // namespace ctmap
