#pragma once
/// \file approximate_path.h
/// Approximate shortest paths on the surface (paper §2.3, after Zhang & Wu): Steiner points on
/// every edge, as many as the edge's length over a spacing, a graph joining the points that share
/// a face, and A* (Dijkstra with the straight-line distance as its admissible bound).
#include <algorithm>
#include <optional>
#include <unordered_set>
#include <vector>

#include "ctmap/cut/insert_path.h"
#include "ctmap/cut/work_mesh.h"

namespace ctmap {

/// Whether the short list `v` (a sector's faces or neighbours) holds `x`.
inline bool contains(const std::vector<int>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

/// Where a path may start or end: the faces around the end vertex it may cross first, and the
/// neighbours it may step to along an edge (the sector of DESIGN §2 condition 2).
struct EndSector {
    std::vector<int> faces;
    std::vector<int> edge_neighbours;
};

/// What the search must respect (DESIGN §2 conditions 1-2).
struct PathConstraints {
    int source = -1, target = -1;
    const std::vector<char>* blocked = nullptr;                 ///< per vertex: on a path or a feature
    const std::unordered_set<std::uint64_t>* path_edges = nullptr;  ///< edges of embedded paths
    EndSector source_sector, target_sector;
    /// A guide map (guide_map.h), one point per vertex, or none: a move then costs its length on
    /// the surface plus `guide_weight` times its length in the guide (both in world units: the
    /// weight includes the guide's scale), and the search looks for a path short in both.
    const std::vector<Vec2>* guide = nullptr;
    double guide_weight = 0;
};

/// Options of the search.
struct PathSearchOptions {
    double spacing = 0;  ///< Steiner point spacing (world units); > 0
    /// Coarse to fine: search first with `coarse_factor` times the spacing (most edges then hold
    /// no Steiner point or one), then at the spacing only inside the faces within
    /// `corridor_rings` vertex rings of the coarse path. A* with the straight-line bound
    /// explores a wide region wherever the surface curves away from the straight line (around a
    /// head, a limb), which was most of the cut's time on a million triangles; the corridor keeps
    /// the fine search to a band. 0 rings searches the whole fine graph at once, and so does a
    /// path whose ends are closer than `corridor_min_distance` spacings (there the two searches
    /// cost more than one). The rules are the same in both graphs, but the coarse one has other
    /// crossing points and the corridor a border (a move whose face lies outside is not offered),
    /// so either search may find nothing where the whole fine graph has a path: then the whole
    /// graph is searched. A coarser graph (factor 6) strays too far: worst paths 6.7% longer than
    /// the geodesic on lion-head against 2.3% (GeodesicAccuracy).
    int corridor_rings = 2;
    double coarse_factor = 4;
    double corridor_min_distance = 100;
};

/// A path found by `find_path`.
struct FoundPath {
    std::vector<PathNode> nodes;
    double length = 0;
    /// Which search found it: the whole fine graph at once, the corridor, or the whole fine graph
    /// after the coarse search or the corridor found nothing.
    enum class Search { whole_graph, corridor, whole_graph_after_corridor };
    Search search = Search::whole_graph;
};

/// A short path in the Steiner graph from `c.source` to `c.target` that avoids blocked vertices
/// and path edges (Steiner points are never put on path edges, so it cannot cross a path), leaves
/// the source through its sector and enters the target through its sector. Points on a free edge
/// stay usable even when both its ends are blocked or are the path's own ends (an edge with no
/// Steiner point then gets one), which lets a path squeeze between two others and pass by its own
/// ends (PathSearch.APathMayPassByItsOwnEnd). Ends closer than `opt.corridor_min_distance`
/// spacings, or `opt.corridor_rings == 0`: the shortest such path of the whole graph (A*).
/// Otherwise the shortest inside the corridor of a coarse path (`FoundPath::search` says which
/// search found it), which is at most a little longer (GeodesicAccuracy and
/// Cut.CorridorPathsAreNearlyAsShortAsWholeGraphPaths measure how much).
/// \pre spacing > 0, source != target.
/// \return nothing when the target cannot be reached in the whole fine graph.
std::optional<FoundPath> find_path(const WorkMesh& mesh, const PathConstraints& c, const PathSearchOptions& opt);

}  // namespace ctmap
