#include "ctmap/cut/cut_to_disc.h"

#include <numeric>
#include <unordered_map>

#include "ctmap/cut/work_mesh.h"
#include "ctmap/errors.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/union_find.h"

namespace ctmap {

DiscCut cut_to_disc(const TriMesh& mesh) {
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    // Undirected edges with their faces (one for a border edge), and each face's edges.
    std::unordered_map<std::uint64_t, int> edge_of;
    std::vector<std::array<int, 2>> edge_faces, edge_ends;
    std::vector<std::array<int, 3>> face_edges(nf);
    for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
            auto [it, fresh] = edge_of.emplace(edge_key(a, b), int(edge_faces.size()));
            if (fresh) edge_faces.push_back({f, -1}), edge_ends.push_back({a, b});
            else edge_faces[it->second][1] = f;
            face_edges[f][k] = it->second;
        }
    const int ne = int(edge_faces.size());

    // A dual spanning tree (breadth first), then the edges it does not cross.
    std::vector<char> crossed(ne, 0), reached(nf, 0);
    std::vector<int> queue{0};
    reached[0] = 1;
    for (std::size_t i = 0; i < queue.size(); ++i) {
        const int f = queue[i];
        for (int e : face_edges[f]) {
            const int g = edge_faces[e][0] == f ? edge_faces[e][1] : edge_faces[e][0];
            if (g < 0 || reached[g]) continue;
            reached[g] = 1, crossed[e] = 1;
            queue.push_back(g);
        }
    }
    if (int(queue.size()) != nf) throw BadInput("", "the faces to cut open are not connected");
    // Prune: an edge of the graph at a vertex of degree 1 is a dangling tree's (gluing it back
    // keeps a disc). Border edges are never removed: a border vertex has two of them.
    std::vector<int> degree(nv, 0);
    std::vector<std::vector<int>> incident(nv);
    std::vector<char> in_graph(ne, 0);
    for (int e = 0; e < ne; ++e)
        if (!crossed[e]) {
            in_graph[e] = 1;
            for (int v : edge_ends[e]) ++degree[v], incident[v].push_back(e);
        }
    std::vector<int> leaves;
    for (int v = 0; v < nv; ++v)
        if (degree[v] == 1) leaves.push_back(v);
    while (!leaves.empty()) {
        const int v = leaves.back();
        leaves.pop_back();
        if (degree[v] != 1) continue;
        for (int e : incident[v]) {
            if (!in_graph[e]) continue;
            in_graph[e] = 0;
            --degree[v];
            const int w = edge_ends[e][0] == v ? edge_ends[e][1] : edge_ends[e][0];
            if (--degree[w] == 1) leaves.push_back(w);
            break;
        }
    }
    DiscCut out;
    bool any_edge = false;
    for (int e = 0; e < ne; ++e) {
        any_edge |= bool(in_graph[e]);
        if (in_graph[e] && edge_faces[e][1] >= 0) ++out.cut_edges;
    }
    if (!any_edge) {
        // A closed sphere (a piece in no chart with no border and no handle: an eyeball): a slit
        // of two edges a - b - c opens it into a disc whose border is a, b, c, b'.
        for (int b = 0; b < nv && !any_edge; ++b) {
            int first = -1;
            for (int e = 0; e < ne && !any_edge; ++e) {
                if (edge_ends[e][0] != b && edge_ends[e][1] != b) continue;
                if (first < 0) first = e;
                else in_graph[first] = in_graph[e] = 1, any_edge = true, out.cut_edges = 2;
            }
        }
        if (!any_edge) throw BadInput("", "a closed surface without two edges at a vertex cannot be cut open");
    }

    // Split: the corners of a vertex stay one vertex across every interior edge not cut.
    UnionFind corners(3 * nf);
    for (int e = 0; e < ne; ++e) {
        const int f = edge_faces[e][0], g = edge_faces[e][1];
        if (g < 0 || in_graph[e]) continue;
        for (int v : edge_ends[e]) {
            int cf = -1, cg = -1;
            for (int k = 0; k < 3; ++k) {
                if (mesh.faces[f][k] == v) cf = 3 * f + k;
                if (mesh.faces[g][k] == v) cg = 3 * g + k;
            }
            corners.unite(cf, cg);
        }
    }
    std::vector<int> vertex_of(3 * nf, -1);
    out.disc.faces.resize(nf);
    for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            const int root = corners.find(3 * f + k);
            if (vertex_of[root] < 0) {
                vertex_of[root] = out.disc.num_vertices();
                out.disc.positions.push_back(mesh.positions[mesh.faces[f][k]]);
                out.original.push_back(mesh.faces[f][k]);
            }
            out.disc.faces[f][k] = vertex_of[root];
        }
    const MeshTopology topo = compute_topology(out.disc);
    if (!topo.is_disc)
        throw InternalError("cut_to_disc: the cut surface is not a disc (" + std::to_string(topo.border_loops) +
                            " border loops, Euler characteristic " + std::to_string(topo.euler) + ")");
    return out;
}

}  // namespace ctmap
