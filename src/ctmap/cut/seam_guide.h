#pragma once
/// \file seam_guide.h
/// Where the seams should run when the shortest ones do not keep the features on their sides
/// (issue 40): each chart's region grown from its interior features (and the faces in no chart
/// from the mesh border loops that belong to no chart, or on a closed mesh with one chart, from
/// the vertices beyond its border features), as a multi-source front; a seam traced
/// with these weights is drawn to where two regions meet.
#include <vector>

#include "ctmap/cut/chart_outline.h"
#include "ctmap/cut/seam_paths.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Per vertex, a weight >= 1 for `seam_shortest_path`: 1 where the two nearest sources (3D
/// distance along edges) of different charts are equally far, up to 1 + `strength` at a source.
/// Empty when fewer than two kinds of source exist (nothing to run between). With one chart on
/// a closed mesh, the rest grows from the vertices `beyond_reach` times as far from the chart's
/// interior features as its farthest border feature (or half way to the farthest vertex).
/// \pre every feature vertex in range.
std::vector<double> seam_guide_weights(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                                       double strength = 8.0, double beyond_reach = 2.0);

/// Per vertex, a weight >= 1 for `seam_shortest_path` that draws a seam of `chart` to the level
/// of its border features: 1 where the vertex is as far from the chart's interior features as the
/// border feature nearest to it, up to 1 + `strength` at an interior feature. Empty without
/// interior features. \pre every feature vertex in range.
std::vector<double> seam_level_weights(const TriMesh& mesh, const SeamGraph& graph, const ChartOutline& chart,
                                       double strength = 8.0);

}  // namespace ctmap
