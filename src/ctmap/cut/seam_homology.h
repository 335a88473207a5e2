#pragma once
/// \file seam_homology.h
/// Seams that do not go round a handle (paper §3: each chart is a disc). On a closed mesh of
/// genus g a simple loop splits the mesh in two exactly when it is null in Z/2 homology, which
/// its crossings with 2g dual loops tell (tree-cotree: Eppstein 2003, Erickson & Whittlesey
/// 2005). A chart's border loop made of shortest pieces can take a short way round a handle;
/// the piece that did is traced again as the shortest path of the other class.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "ctmap/cut/chart_outline.h"
#include "ctmap/cut/seam_paths.h"
#include "ctmap/cut/seam_sides.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// The dual loops of a closed mesh's handles: per edge, which of them cross it.
struct HandleLoops {
    int count = 0;  ///< 2g; 0 for a sphere, a mesh with a border or a genus above 2 (not handled)
    std::unordered_map<std::uint64_t, std::uint32_t> crossing;  ///< edge_key -> bit j set if dual loop j crosses it

    /// The crossings of the path (closed: with its last vertex joined to its first), mod 2 per loop.
    std::uint32_t parity(const std::vector<int>& path, bool closed) const;
};

/// The handle loops of `mesh`. \pre `mesh` is a consistently oriented connected manifold.
HandleLoops handle_loops(const TriMesh& mesh, const SeamGraph& graph);

/// A shortest path a -> b under seam_shortest_path's rules (and `weight`) whose crossings with
/// the handle loops are `parity`, or empty if there is no simple one. \pre as seam_shortest_path.
std::vector<int> seam_path_of_parity(const TriMesh& mesh, const SeamGraph& graph, const HandleLoops& loops, int a, int b,
                                     std::uint32_t parity, const std::vector<char>& blocked,
                                     const std::set<std::uint64_t>& seam_edges, const std::vector<double>* weight);

/// Re-traces pieces of `layout` until every chart's border loop splits the mesh in two: for a
/// loop that goes round a handle, of its movable pieces the one whose shortest path of the class
/// that closes the loop is shortest. Adds the pieces traced again to `layout.rerouted`; returns
/// how many were traced again, or -1 if some loop still goes round a handle (`layout` stays valid).
int keep_seams_off_handles(const TriMesh& mesh, const SeamGraph& graph, const HandleLoops& loops,
                           const std::vector<ChartOutline>& charts, SeamLayout& layout,
                           const std::vector<double>* weight = nullptr);

}  // namespace ctmap
