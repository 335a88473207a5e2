#pragma once
/// \file seam_paths.h
/// The paths a seam is made of (paper §3): along the mesh border where two border features lie
/// on it, else shortest paths along mesh edges through free interior vertices; and the pieces of
/// the mesh the seams leave.
#include <cstdint>
#include <set>
#include <unordered_map>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// The mesh's directed edges (a -> b inside face f) and vertex neighbours.
struct SeamGraph {
    std::unordered_map<std::uint64_t, int> face_of;  ///< directed edge -> the face on its left
    std::vector<std::vector<int>> neighbours;        ///< per vertex, its neighbours
    std::vector<char> on_border;                     ///< per vertex: on the mesh border

    /// \pre `mesh` is a consistently oriented manifold.
    explicit SeamGraph(const TriMesh& mesh);
    /// The face on the left of the directed edge a -> b, or -1 (a border edge seen from outside).
    int left(int a, int b) const;
};

/// The mesh border's arc from `a` to `b` (both on the mesh border) that meets no `blocked`
/// vertex between them, or empty. \pre a != b, both in range.
std::vector<int> border_arc(const TriMesh& mesh, const SeamGraph& graph, int a, int b, const std::vector<char>& blocked);

/// A shortest path a -> b along mesh edges (3D length, Dijkstra) whose inner vertices are free
/// (not `blocked`, not on the mesh border) and whose edges are not in `seam_edges` (edge_key),
/// or empty if there is none. With `weight` (per vertex, >= 1), an edge's length is scaled by
/// the mean of its two ends' weights. \pre a, b in range; blocked.size() == mesh.num_vertices().
std::vector<int> seam_shortest_path(const TriMesh& mesh, const SeamGraph& graph, int a, int b,
                                    const std::vector<char>& blocked, const std::set<std::uint64_t>& seam_edges,
                                    const std::vector<double>* weight = nullptr);

/// One vertex of each loop of the mesh border that holds none of the vertices `features`.
std::vector<int> free_border_loops(const TriMesh& mesh, const SeamGraph& graph, const std::vector<char>& features);

/// The pieces the mesh's faces fall into along `seam_edges` (and the mesh border): per face, its
/// piece, numbered from 0 in face order; `count` is set to the number of pieces.
std::vector<int> seam_components(const TriMesh& mesh, const SeamGraph& graph, const std::set<std::uint64_t>& seam_edges,
                                 int& count);

}  // namespace ctmap
