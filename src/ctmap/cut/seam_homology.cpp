#include "ctmap/cut/seam_homology.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>

#include "ctmap/edge_key.h"

namespace ctmap {
namespace {

constexpr int kMaxLoops = 4;  // genus 2: the search below keeps 2^count copies of the mesh
constexpr int kRetries = 40;  // searches for a simple path of a class

double length(const TriMesh& mesh, const std::vector<int>& path) {
    double l = 0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) l += (mesh.positions[path[i + 1]] - mesh.positions[path[i]]).norm();
    return l;
}

/// Takes piece `k` out of `layout`'s blocked vertices and seam edges (its ends stay features).
void free_piece(SeamLayout& layout, int k) {
    const std::vector<int>& old = layout.pieces[k];
    for (std::size_t j = 1; j + 1 < old.size(); ++j) layout.blocked[old[j]] = 0;
    for (std::size_t j = 0; j + 1 < old.size(); ++j) layout.seam_edges.erase(edge_key(old[j], old[j + 1]));
}

/// Makes `path` piece `k` of `layout`, blocking its inner vertices and adding its edges.
void place_piece(SeamLayout& layout, int k, const std::vector<int>& path) {
    for (std::size_t j = 1; j + 1 < path.size(); ++j) layout.blocked[path[j]] = 1;
    for (std::size_t j = 0; j + 1 < path.size(); ++j) layout.seam_edges.insert(edge_key(path[j], path[j + 1]));
    layout.pieces[k] = path;
}

/// The search of seam_path_of_parity, its path perhaps not simple.
std::vector<int> path_of_parity(const TriMesh& mesh, const SeamGraph& graph, const HandleLoops& loops, int a, int b,
                                     std::uint32_t parity, const std::vector<char>& blocked,
                                     const std::set<std::uint64_t>& seam_edges, const std::vector<double>* weight) {
    const int n = mesh.num_vertices(), copies = 1 << loops.count;
    auto state = [&](int v, std::uint32_t p) { return std::size_t(v) * copies + p; };
    std::vector<double> dist(std::size_t(n) * copies, std::numeric_limits<double>::infinity());
    std::vector<std::int64_t> from(dist.size(), -1);
    using Item = std::pair<double, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[state(a, 0)] = 0;
    queue.push({0, state(a, 0)});
    const std::size_t goal = state(b, parity);
    while (!queue.empty()) {
        const auto [d, s] = queue.top();
        queue.pop();
        if (d > dist[s]) continue;
        if (s == goal) break;
        const int v = int(s / copies);
        const std::uint32_t p = std::uint32_t(s % copies);
        if (v == b || (v != a && (blocked[v] || graph.on_border[v]))) continue;
        for (int w : graph.neighbours[v]) {
            if (w == a || (w != b && (blocked[w] || graph.on_border[w]))) continue;
            const std::uint64_t e = edge_key(v, w);
            if (seam_edges.count(e)) continue;
            const auto it = loops.crossing.find(e);
            const std::size_t t = state(w, p ^ (it == loops.crossing.end() ? 0u : it->second));
            const double scale = weight ? 0.5 * ((*weight)[v] + (*weight)[w]) : 1.0;
            const double nd = d + scale * (mesh.positions[w] - mesh.positions[v]).norm();
            if (nd < dist[t]) dist[t] = nd, from[t] = std::int64_t(s), queue.push({nd, t});
        }
    }
    if (from[goal] < 0) return {};
    std::vector<int> path;
    for (std::int64_t s = std::int64_t(goal); s >= 0; s = from[std::size_t(s)]) path.push_back(int(std::size_t(s) / copies));
    std::reverse(path.begin(), path.end());
    return path;
}

}  // namespace

std::uint32_t HandleLoops::parity(const std::vector<int>& path, bool closed) const {
    std::uint32_t p = 0;
    const std::size_t n = path.size();
    for (std::size_t i = 0; i + (closed ? 0 : 1) < n; ++i)
        if (const auto it = crossing.find(edge_key(path[i], path[(i + 1) % n])); it != crossing.end()) p ^= it->second;
    return p;
}

HandleLoops handle_loops(const TriMesh& mesh, const SeamGraph& graph) {
    HandleLoops out;
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    if (nv == 0 || std::any_of(graph.on_border.begin(), graph.on_border.end(), [](char b) { return b != 0; })) return out;
    if (nv - nf / 2 >= 2) return out;  // Euler characteristic 2 (closed: 3F = 2E): a sphere
    // A spanning tree of the vertices, then one of the faces across the other edges; the edges
    // in neither are the handles' (2g of them on a closed mesh).
    std::set<std::uint64_t> tree;
    std::vector<char> seen(nv, 0);
    std::queue<int> todo;
    seen[0] = 1, todo.push(0);
    while (!todo.empty()) {
        const int v = todo.front();
        todo.pop();
        for (int w : graph.neighbours[v])
            if (!seen[w]) seen[w] = 1, tree.insert(edge_key(v, w)), todo.push(w);
    }
    std::vector<int> parent(nf, -1), depth(nf, -1);
    std::vector<std::uint64_t> parent_edge(nf, 0);
    std::set<std::uint64_t> cotree;
    std::queue<int> faces;
    depth[0] = 0, faces.push(0);
    while (!faces.empty()) {
        const int f = faces.front();
        faces.pop();
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
            const int g = graph.left(b, a);
            if (g < 0 || depth[g] >= 0 || tree.count(edge_key(a, b))) continue;
            depth[g] = depth[f] + 1, parent[g] = f, parent_edge[g] = edge_key(a, b), cotree.insert(edge_key(a, b));
            faces.push(g);
        }
    }
    std::vector<std::pair<int, int>> handles;  // the leftover edges, as (a, b)
    for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
            if (a < b && !tree.count(edge_key(a, b)) && !cotree.count(edge_key(a, b))) handles.push_back({a, b});
        }
    if (handles.empty() || int(handles.size()) > kMaxLoops) return out;
    out.count = int(handles.size());
    for (int j = 0; j < out.count; ++j) {  // dual loop j: across handle edge j, back through the face tree
        const auto [a, b] = handles[j];
        const std::uint32_t bit = 1u << j;
        out.crossing[edge_key(a, b)] ^= bit;
        for (int f = graph.left(a, b), g = graph.left(b, a); f != g;) {
            int& deeper = depth[f] >= depth[g] ? f : g;
            out.crossing[parent_edge[deeper]] ^= bit;
            deeper = parent[deeper];
        }
    }
    return out;
}

std::vector<int> seam_path_of_parity(const TriMesh& mesh, const SeamGraph& graph, const HandleLoops& loops, int a, int b,
                                     std::uint32_t parity, const std::vector<char>& blocked,
                                     const std::set<std::uint64_t>& seam_edges, const std::vector<double>* weight) {
    // The shortest path of a class may come back to a vertex it passed (out round a handle and
    // back): the vertex it meets twice is blocked and the search run again.
    std::vector<char> avoid = blocked;
    for (int tries = 0; tries < kRetries; ++tries) {
        std::vector<int> path = path_of_parity(mesh, graph, loops, a, b, parity, avoid, seam_edges, weight);
        if (path.empty()) return {};
        std::vector<int> sorted = path;
        std::sort(sorted.begin(), sorted.end());
        const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
        if (twice == sorted.end()) return path;
        if (*twice == a || *twice == b) return {};
        avoid[*twice] = 1;
    }
    return {};
}

int keep_seams_off_handles(const TriMesh& mesh, const SeamGraph& graph, const HandleLoops& loops,
                           const std::vector<ChartOutline>& charts, SeamLayout& layout, const std::vector<double>* weight) {
    if (loops.count == 0) return 0;
    int moved = 0;
    for (std::size_t round = 0; round < 2 * charts.size() + 2; ++round) {
        int bad = -1;
        std::uint32_t total = 0;
        for (std::size_t c = 0; c < charts.size() && bad < 0; ++c)
            if ((total = loops.parity(chart_loop(layout, int(c)), true)) != 0) bad = int(c);
        if (bad < 0) return moved;
        // Of the chart's movable pieces, the one whose shortest simple path of the class that
        // closes the loop is shortest.
        double best = std::numeric_limits<double>::infinity();
        int best_piece = -1;
        std::vector<int> best_path;
        for (const auto& [k, forward] : layout.chart_pieces[bad]) {
            if (!layout.movable[k]) continue;
            SeamLayout trial = layout;
            free_piece(trial, k);
            const std::vector<int>& old = layout.pieces[k];
            std::vector<int> path = seam_path_of_parity(mesh, graph, loops, old.front(), old.back(),
                                                        loops.parity(old, false) ^ total, trial.blocked, trial.seam_edges, weight);
            if (!path.empty() && length(mesh, path) < best) best = length(mesh, path), best_piece = k, best_path = std::move(path);
        }
        if (best_piece < 0) return -1;
        free_piece(layout, best_piece);
        place_piece(layout, best_piece, best_path);
        layout.rerouted.insert(best_piece);
        ++moved;
    }
    return -1;
}

}  // namespace ctmap
