#include "ctmap/cut/seam_guide.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

namespace ctmap {
namespace {

/// Distances along edges from every vertex of `sources`; with `nearest`, per vertex the index
/// into `sources` of the nearest one (-1 where none reaches).
std::vector<double> distances_from(const TriMesh& mesh, const SeamGraph& graph, const std::vector<int>& sources,
                                   std::vector<int>* nearest = nullptr) {
    std::vector<double> dist(mesh.num_vertices(), std::numeric_limits<double>::infinity());
    if (nearest) nearest->assign(mesh.num_vertices(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (std::size_t i = 0; i < sources.size(); ++i) {
        dist[sources[i]] = 0, queue.push({0, sources[i]});
        if (nearest) (*nearest)[sources[i]] = int(i);
    }
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[v]) continue;
        for (int w : graph.neighbours[v])
            if (const double nd = d + (mesh.positions[w] - mesh.positions[v]).norm(); nd < dist[w]) {
                dist[w] = nd, queue.push({nd, w});
                if (nearest) (*nearest)[w] = (*nearest)[v];
            }
    }
    return dist;
}

}  // namespace

std::vector<double> seam_guide_weights(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                                       double strength, double beyond_reach) {
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
    const int nv = mesh.num_vertices();
    if (sources.size() == 1) {  // one chart on a closed mesh: the rest grows from where it is far
        const std::vector<double> d = distances_from(mesh, graph, sources[0]);
        double reach = 0, far = 0;
        for (const ChartOutline& ch : charts)
            for (int v : ch.border) reach = std::max(reach, d[v]);
        for (int v = 0; v < nv; ++v)
            if (std::isfinite(d[v])) far = std::max(far, d[v]);
        const double beyond = std::min(beyond_reach * reach, 0.5 * (reach + far));  // past the chart's border features
        std::vector<int> rest_far;
        for (int v = 0; v < nv; ++v)
            if (std::isfinite(d[v]) && d[v] >= beyond && !feature[v]) rest_far.push_back(v);
        if (!rest_far.empty() && beyond > reach) sources.push_back(rest_far);
    }
    if (sources.size() < 2) return {};
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

std::vector<double> seam_level_weights(const TriMesh& mesh, const SeamGraph& graph, const ChartOutline& chart, double strength) {
    if (chart.interior.empty() || chart.border.empty()) return {};
    const std::vector<double> d = distances_from(mesh, graph, chart.interior);
    std::vector<int> nearest;
    distances_from(mesh, graph, chart.border, &nearest);
    std::vector<double> weight(mesh.num_vertices(), 1.0);
    for (int v = 0; v < mesh.num_vertices(); ++v) {
        if (nearest[v] < 0 || !std::isfinite(d[v])) continue;
        const double r = d[chart.border[nearest[v]]];
        if (d[v] + r > 0) weight[v] = 1 + strength * std::abs(d[v] - r) / (d[v] + r);
    }
    return weight;
}

}  // namespace ctmap
