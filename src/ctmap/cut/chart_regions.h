#pragma once
/// \file chart_regions.h
/// The first cut of a mesh with several charts (issue 13; paper §3, Figs. 5-7): each chart's
/// border features are joined by seams, and the mesh falls apart along them into one disc per
/// chart (and a remainder in no chart). Each disc then goes through the single-chart pipeline.
#include <string>
#include <vector>

#include "ctmap/cut/chart_outline.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// One chart's region: a disc of the mesh's faces.
struct ChartRegion {
    TriMesh mesh;             ///< the region's faces as a mesh of its own, vertices in the mesh's order
    std::vector<int> global;  ///< per vertex of `mesh`, its vertex in the whole mesh
    std::vector<int> faces;   ///< per face of `mesh`, its face in the whole mesh
};

/// The seams and the regions.
struct ChartRegions {
    std::vector<ChartRegion> charts;           ///< per chart, in the outlines' order
    std::vector<int> face_chart;               ///< per face of the mesh: its chart, or -1 (in no chart)
    std::vector<std::vector<int>> seams;       ///< the traced seam pieces, as vertex paths
    int rerouted = 0;                          ///< pieces traced again to keep features on their sides
};

/// Traces every chart's border on the mesh and splits the mesh along it. Consecutive border
/// features are joined by the mesh border where both lie on it with no other feature between
/// them, else by a shortest path along mesh edges that touches no other feature, seam or mesh
/// border; two charts that list the same consecutive pair share that piece. A chart's region is
/// the side of its border loop that holds its interior features (without any: the side on the
/// left of the loop when its image polygon runs counter-clockwise, so the map is not mirrored).
/// Where a shortest piece passes on the wrong side of an interior feature, the piece is traced
/// again round it (cut/seam_sides.h); on a closed mesh with handles, a loop that takes a
/// handle's short way gets the piece that did traced again in the other class
/// (cut/seam_homology.h); when that does not give discs, the pieces are traced again drawn to
/// where the charts' regions, grown from their features, meet (cut/seam_guide.h).
/// \pre `mesh` is a consistently oriented manifold; every vertex index in range; every chart
///      has at least 3 border features.
/// \throw BadInput naming the charts and features: two charts listing common border features
///        in different cyclic orders, no seam path, no seam route that keeps a feature on its
///        chart's side (the feature, its chart, the seam segment and the way round), a region that is not a disc bounded by its
///        chart's border, a region holding another chart's features or missing one of its own,
///        two charts on one region.
ChartRegions chart_regions(const TriMesh& mesh, const std::vector<ChartOutline>& charts);

}  // namespace ctmap
