#pragma once
/// \file seam_sides.h
/// Seams that keep every chart's features on its side (paper §3, issue 40). The seams are the
/// user's intent only at the border features; between two of them a shortest path may pass on the
/// wrong side of a chart's interior feature, so that the loop it closes leaves the feature
/// outside its chart. Such a piece is re-routed: a tether joins the feature to its chart's
/// side (to a feature of the chart there, or to its faces), the pieces the tether crosses are
/// traced again as shortest paths that avoid every tether, and this repeats until every feature
/// is on its chart's side. A seam that avoids a tether leaves its two ends on one side.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "ctmap/cut/chart_outline.h"
#include "ctmap/cut/seam_paths.h"
#include "ctmap/mesh.h"

namespace ctmap {

struct HandleLoops;  // cut/seam_homology.h

/// The seams traced so far: pieces between consecutive border features, shared by the charts
/// that list the same pair.
struct SeamLayout {
    std::vector<std::vector<int>> pieces;  ///< vertex paths from one border feature to the next
    std::vector<char> movable;             ///< per piece: through the interior (a mesh border arc is not re-routed)
    /// Per chart, per side i of its border polygon: the piece, and whether it runs from
    /// border[i] to border[i + 1] (else the other way).
    std::vector<std::vector<std::pair<int, bool>>> chart_pieces;
    std::vector<char> blocked;              ///< per vertex: a feature, or an inner vertex of a piece
    std::set<std::uint64_t> seam_edges;     ///< the pieces' edges (edge_key)
    std::set<int> rerouted;                 ///< the pieces traced again to keep features on their sides
};

/// Chart `c`'s border loop on the mesh: its pieces in its order, each piece's last vertex left
/// out (it starts the next piece).
std::vector<int> chart_loop(const SeamLayout& layout, int c);

/// Where each chart lies: per chart, the piece of the mesh (`seam_components`) on the side of its
/// loop that holds most of its interior features (on a tie, or without any: the left side when
/// its image runs counter-clockwise, so the map is not mirrored; the other side if that one is
/// another chart's).
struct ChartSides {
    std::vector<int> component;  ///< per face: its piece of the mesh
    int components = 0;
    std::vector<int> side;       ///< per chart: its piece, or -1 (then `error` says why)
    std::vector<char> on_left;   ///< per chart: its piece is on the left of its loop
    std::string error;           ///< the first chart whose loop gives it no piece of its own, or ""
    /// What lies on the wrong side: an interior feature outside its chart's piece, or a loop of
    /// the mesh border (with no border feature on it) inside a chart's piece, which would then
    /// not be a disc.
    struct Misplaced {
        int vertex = -1;  ///< the feature's vertex, or a vertex of the border loop
        int chart = -1;   ///< the feature's chart, or -1 for a border loop
        int index = -1;   ///< into the chart's `interior`
        int in_chart = -1;  ///< the chart whose piece it is in, or -1 (in no chart)
        int side = -1;    ///< the piece it must be in (for a border loop: beside, not in, `in_chart`'s)
    };
    std::vector<Misplaced> misplaced;
};

/// The charts' sides for the seams of `layout`. \pre every chart's loop has at least 3 vertices.
ChartSides chart_sides(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                       const SeamLayout& layout);

/// Re-routes pieces of `layout` until every chart's interior features lie on its side (above)
/// and no chart's side holds a loop of the mesh border;
/// adds the pieces it traced again to `layout.rerouted`. Returns when no feature is misplaced or
/// when a chart's loop gives it no piece of its own (`chart_sides`' error: the caller reports it).
/// The pieces keep the validity conditions of their first tracing: simple, through free interior
/// vertices, no two sharing an inner vertex or an edge.
/// \throw BadInput naming the feature, its chart and the seam segment (the two border features),
///        and which way round the seam would have to pass it, when no route keeps it inside.
/// With `handles` (a closed mesh with handles), each piece traced again keeps its class, so a
/// loop that splits the mesh keeps splitting it.
void keep_features_on_their_sides(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                                  SeamLayout& layout, const HandleLoops* handles = nullptr);

}  // namespace ctmap
