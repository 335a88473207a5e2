#include "ctmap/cut/seam_paths.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>

#include "ctmap/edge_key.h"

namespace ctmap {
namespace {

std::uint64_t directed_edge(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

}  // namespace

SeamGraph::SeamGraph(const TriMesh& m) : neighbours(m.positions.size()), on_border(m.positions.size(), 0) {
    face_of.reserve(3 * m.faces.size());
    for (int f = 0; f < m.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
            face_of[directed_edge(a, b)] = f;
            neighbours[a].push_back(b);
        }
    for (int f = 0; f < m.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
            if (!face_of.count(directed_edge(b, a))) {
                on_border[a] = on_border[b] = 1;
                neighbours[b].push_back(a);  // a border edge is listed from one side only
            }
        }
}

int SeamGraph::left(int a, int b) const {
    const auto it = face_of.find(directed_edge(a, b));
    return it == face_of.end() ? -1 : it->second;
}

std::vector<int> border_arc(const TriMesh& mesh, const SeamGraph& graph, int a, int b, const std::vector<char>& blocked) {
    // The next border vertex after v (interior on the left): the b of the border edge v -> b.
    auto next = [&](int v, bool forward) {
        for (int w : graph.neighbours[v])
            if (forward ? (graph.left(v, w) >= 0 && graph.left(w, v) < 0) : (graph.left(w, v) >= 0 && graph.left(v, w) < 0))
                return w;
        return -1;
    };
    for (bool forward : {true, false}) {
        std::vector<int> path{a};
        for (int v = next(a, forward), steps = 0; v >= 0 && steps <= mesh.num_vertices(); v = next(v, forward), ++steps) {
            path.push_back(v);
            if (v == b) return path;
            if (blocked[v] || v == a) break;
        }
    }
    return {};
}

std::vector<int> seam_shortest_path(const TriMesh& mesh, const SeamGraph& graph, int a, int b,
                                    const std::vector<char>& blocked, const std::set<std::uint64_t>& seam_edges,
                                    const std::vector<double>* weight) {
    const int n = mesh.num_vertices();
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    std::vector<int> from(n, -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[a] = 0;
    queue.push({0, a});
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[v]) continue;
        if (v == b) break;
        if (v != a && (blocked[v] || graph.on_border[v])) continue;  // passes through free interior vertices only
        for (int w : graph.neighbours[v]) {
            if (w != b && (blocked[w] || graph.on_border[w])) continue;
            if (seam_edges.count(edge_key(v, w))) continue;
            const double scale = weight ? 0.5 * ((*weight)[v] + (*weight)[w]) : 1.0;
            const double nd = d + scale * (mesh.positions[w] - mesh.positions[v]).norm();
            if (nd < dist[w]) dist[w] = nd, from[w] = v, queue.push({nd, w});
        }
    }
    if (from[b] < 0) return {};
    std::vector<int> path;
    for (int v = b; v >= 0; v = from[v]) path.push_back(v);
    std::reverse(path.begin(), path.end());
    return path;
}

std::vector<int> free_border_loops(const TriMesh& mesh, const SeamGraph& graph, const std::vector<char>& features) {
    const int nv = mesh.num_vertices();
    std::vector<char> seen(nv, 0);
    std::vector<int> out;
    for (int v0 = 0; v0 < nv; ++v0) {
        if (!graph.on_border[v0] || seen[v0]) continue;
        bool free = true;
        std::vector<int> stack{v0};
        seen[v0] = 1;
        while (!stack.empty()) {  // the border vertices joined to v0 by border edges
            const int v = stack.back();
            stack.pop_back();
            free = free && !features[v];
            for (int w : graph.neighbours[v])
                if (graph.on_border[w] && !seen[w] && (graph.left(v, w) < 0 || graph.left(w, v) < 0))
                    seen[w] = 1, stack.push_back(w);
        }
        if (free) out.push_back(v0);
    }
    return out;
}

std::vector<int> seam_components(const TriMesh& mesh, const SeamGraph& graph, const std::set<std::uint64_t>& seam_edges,
                                 int& count) {
    const int nf = mesh.num_faces();
    std::vector<int> component(nf, -1);
    count = 0;
    for (int f0 = 0; f0 < nf; ++f0) {
        if (component[f0] >= 0) continue;
        std::vector<int> stack{f0};
        component[f0] = count;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
                if (seam_edges.count(edge_key(a, b))) continue;
                const int g = graph.left(b, a);
                if (g >= 0 && component[g] < 0) component[g] = count, stack.push_back(g);
            }
        }
        ++count;
    }
    return component;
}

}  // namespace ctmap
