#pragma once
/// \file insertion_order.h
/// The order in which the cut inserts the feature triangulation's interior edges as paths (paper
/// §2.3). Both orders insert a spanning tree grown from the border features first, then the
/// closing edges: while the tree grows no region is split, and afterwards every feature of a
/// region lies on its boundary, so a path that respects the sectors at its ends separates exactly
/// the right features (DESIGN §2 condition 3 holds by construction, whatever tree is chosen).
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "ctmap/cut/approximate_path.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/errors.h"

namespace ctmap {

/// The paper's order: the tree by Prim on `distance` (the features' 3D distance), then the
/// closing edges shortest first. Each entry (u, w) is searched from u; in the tree, u is the end
/// already in the tree. \pre the triangulation connects every feature to the border features
/// (InternalError otherwise).
std::vector<std::array<int, 2>> nearest_first_order(const FeatureTriangulation& ft,
                                                    const std::function<double(int, int)>& distance);

/// The error both orders raise when the edge (u, w) has no valid path even after refinement.
InternalError no_path_error(int u, int w);

/// How `insert_shortest_path_first` reaches the network.
struct PathNetworkAccess {
    /// The path from u to w in the network as it stands; `refine`: refine around the ends when
    /// none is found (which changes the mesh) rather than return nothing; `missed`: a search
    /// without refinement found none in the network as it stands (it need not run again).
    std::function<std::optional<FoundPath>(int u, int w, bool refine, bool missed)> find;
    /// Inserts the path; false when the cut gives up (its growth limit).
    std::function<bool(int u, int w, const FoundPath& path)> insert;
    /// A lower bound of the search length from u to w (the features' 3D distance).
    std::function<double(int u, int w)> lower_bound;
};

/// Inserts every interior edge, tree first and then the closing edges, each time the edge whose
/// path, searched in the network as it stands, is the shortest. Lazy: a candidate's key is a lower
/// bound or a length searched earlier, and lengths roughly only grow as paths are inserted (paths
/// block and split the regions; the splits add Steiner points, so not strictly), so a candidate
/// searched since the last insertion that is still the smallest is taken: a heuristic order,
/// every path still checked by the search's rules. A path that would wind round others is thus put off, or left to the closing
/// stage where its region is fixed. About two searches per inserted path besides the one that
/// finds it. Returns false when `insert` gives up; InternalError when no path exists after
/// refinement. \pre as nearest_first_order.
bool insert_shortest_path_first(const FeatureTriangulation& ft, const PathNetworkAccess& net);

}  // namespace ctmap
