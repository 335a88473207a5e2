#include "ctmap/cut/seam_guide.h"

#include <cmath>
#include <functional>
#include <limits>
#include <queue>

namespace ctmap {
namespace {

/// Distances along edges from every vertex of `sources`.
std::vector<double> distances_from(const TriMesh& mesh, const SeamGraph& graph, const std::vector<int>& sources) {
    std::vector<double> dist(mesh.num_vertices(), std::numeric_limits<double>::infinity());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (int s : sources) dist[s] = 0, queue.push({0, s});
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[v]) continue;
        for (int w : graph.neighbours[v])
            if (const double nd = d + (mesh.positions[w] - mesh.positions[v]).norm(); nd < dist[w]) dist[w] = nd, queue.push({nd, w});
    }
    return dist;
}

}  // namespace

std::vector<double> seam_guide_weights(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                                       double strength) {
    std::vector<std::vector<int>> sources;
    for (const ChartOutline& ch : charts)
        if (!ch.interior.empty()) sources.push_back(ch.interior);
    std::vector<char> feature(mesh.num_vertices(), 0);
    for (const ChartOutline& ch : charts)
        for (int v : ch.border) feature[v] = 1;
    std::vector<int> rest;  // the faces in no chart: every vertex of the free border loops
    const std::vector<int> loops = free_border_loops(mesh, graph, feature);
    if (!loops.empty()) {
        std::vector<char> mark(mesh.num_vertices(), 0);
        for (int v : loops) mark[v] = 1;
        for (bool grew = true; grew;) {  // spread along border edges
            grew = false;
            for (int v = 0; v < mesh.num_vertices(); ++v)
                if (mark[v])
                    for (int w : graph.neighbours[v])
                        if (graph.on_border[w] && !mark[w] && (graph.left(v, w) < 0 || graph.left(w, v) < 0)) mark[w] = 1, grew = true;
        }
        for (int v = 0; v < mesh.num_vertices(); ++v)
            if (mark[v]) rest.push_back(v);
        sources.push_back(rest);
    }
    if (sources.size() < 2) return {};
    const int nv = mesh.num_vertices();
    std::vector<double> first(nv, std::numeric_limits<double>::infinity()), second = first;
    for (const std::vector<int>& s : sources) {
        const std::vector<double> d = distances_from(mesh, graph, s);
        for (int v = 0; v < nv; ++v) {
            if (d[v] < first[v])
                second[v] = first[v], first[v] = d[v];
            else if (d[v] < second[v])
                second[v] = d[v];
        }
    }
    std::vector<double> weight(nv, 1.0);
    for (int v = 0; v < nv; ++v)
        if (std::isfinite(second[v]) && second[v] > 0) weight[v] = 1 + strength * (second[v] - first[v]) / (second[v] + first[v]);
    return weight;
}

}  // namespace ctmap
