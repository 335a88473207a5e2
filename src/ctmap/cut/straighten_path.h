#pragma once
/// \file straighten_path.h
/// Straightening a path just inserted into the work mesh, inside each input face (beyond paper
/// §2.3). insert_path puts a vertex wherever the path crosses a mesh edge, also on the edges that
/// earlier insertions made inside an input face. A path that runs beside an earlier one crosses
/// every edge of the strip between them, so the strips' vertex counts add up path after path
/// (a Fibonacci-like growth: three_peaks with a twist of 8 grew to two million faces). An input
/// face is flat, and a path that crosses no other path inside it can go straight from where it
/// enters to where it leaves: then a face holds only the paths' entry and exit points, and a
/// path beside others crosses only the faces' diagonals.
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "ctmap/cut/work_mesh.h"

namespace ctmap {

/// What straightening did.
struct StraightenStats {
    int removed_vertices = 0;  ///< path vertices removed (left without faces)
    int kept_runs = 0;         ///< runs left as they were (going straight would cross, enclose or touch something)
};

/// Removes the vertices of `chain` that lie inside an input face (WorkMesh::site), were created
/// by its insertion (ids >= `first_new`) and can be skipped: each run of them inside an input
/// face F is replaced by the straight segment between the vertices before and after it, when
/// that segment crosses no other path, passes through no vertex and the region between it and
/// the run holds no blocked vertex (so the path keeps its side of every feature and path); the
/// run's cell (the faces of F around it up to the nearest paths and F's sides) is then
/// re-triangulated: CGAL's constrained Delaunay triangulation in F's affine frame, with the
/// cell's outline and the segment as constraints. Anything the exact predicates find amiss
/// keeps the run as it was. Removed vertices keep their ids and lose their faces.
/// \pre `chain` was just inserted (insert_path) and is not yet in `path_edges` or `blocked`;
/// `path_edges` holds the edges of every other path.
/// \return the chain without the removed vertices.
std::vector<int> straighten_path(WorkMesh& mesh, const std::vector<int>& chain, int first_new,
                                 const std::vector<char>& blocked, const std::unordered_set<std::uint64_t>& path_edges,
                                 StraightenStats* stats = nullptr);

}  // namespace ctmap
