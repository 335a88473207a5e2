#include "ctmap/cut/insertion_order.h"

#include <algorithm>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <string>

#include "ctmap/errors.h"

namespace ctmap {

std::vector<std::array<int, 2>> nearest_first_order(const FeatureTriangulation& ft,
                                                    const std::function<double(int, int)>& distance) {
    const int n = int(ft.points.size());
    std::vector<std::array<int, 2>> order;
    std::vector<char> in_tree(n, 0);
    for (int b : ft.border) in_tree[b] = 1;
    std::set<std::array<int, 2>> pending;
    for (std::size_t e = 0; e < ft.edges.size(); ++e)
        if (!ft.edge_on_border[e]) pending.insert(ft.edges[e]);
    while (true) {
        double best = std::numeric_limits<double>::infinity();
        std::array<int, 2> pick{-1, -1};
        for (const auto& e : pending)
            if (in_tree[e[0]] != in_tree[e[1]] && distance(e[0], e[1]) < best) {
                best = distance(e[0], e[1]);
                pick = in_tree[e[0]] ? e : std::array<int, 2>{e[1], e[0]};
            }
        if (pick[0] < 0) break;
        order.push_back(pick);
        in_tree[pick[1]] = 1;
        pending.erase({std::min(pick[0], pick[1]), std::max(pick[0], pick[1])});
    }
    if (std::count(in_tree.begin(), in_tree.end(), 0))
        throw InternalError("cut: the feature triangulation does not connect every feature to the border");
    std::vector<std::array<int, 2>> closing(pending.begin(), pending.end());
    std::stable_sort(closing.begin(), closing.end(),
                     [&](const auto& a, const auto& b) { return distance(a[0], a[1]) < distance(b[0], b[1]); });
    order.insert(order.end(), closing.begin(), closing.end());
    return order;
}

namespace {

struct Candidate {
    double key;
    int u, w;
    int version;  // the network version `key` was searched at (-1: a lower bound)
    // Equal keys (two candidates with no path before refinement): the one searched last first,
    // so that stale ones are not searched again and again.
    bool operator>(const Candidate& o) const { return key > o.key || (key == o.key && version < o.version); }
};
using Queue = std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>>;

}  // namespace

InternalError no_path_error(int u, int w) {
    return InternalError("cut: no valid path between features " + std::to_string(u) + " and " + std::to_string(w) +
                         " after refinement");
}

namespace {

/// Runs one stage: pops candidates until the queue is empty. `wanted(u, w)`: whether the edge is
/// still to be inserted in this stage; `inserted(u, w)` after each insertion (may push more).
/// False when the network gave up.
template <class Wanted, class Inserted>
bool run_stage(Queue& queue, const PathNetworkAccess& net, int& version, Wanted&& wanted, Inserted&& inserted) {
    std::map<std::pair<int, int>, std::optional<FoundPath>> cache;  // the path behind a current key
    while (!queue.empty()) {
        const Candidate top = queue.top();
        queue.pop();
        if (!wanted(top.u, top.w)) continue;
        if (top.version == version) {
            // Searched in this network (its key): the path found then, or none, which refining
            // around the ends may give.
            std::optional<FoundPath> found = std::move(cache[{top.u, top.w}]);
            if (!found) found = net.find(top.u, top.w, true, true);
            if (!found) throw no_path_error(top.u, top.w);
            if (!net.insert(top.u, top.w, *found)) return false;
            ++version;
            cache.clear();  // every cached path was searched in an older network
            inserted(top.u, top.w);
            continue;
        }
        std::optional<FoundPath>& slot = cache[{top.u, top.w}];
        slot = net.find(top.u, top.w, false, false);
        queue.push({slot ? slot->length : std::numeric_limits<double>::max(), top.u, top.w, version});
    }
    return true;
}

}  // namespace

bool insert_shortest_path_first(const FeatureTriangulation& ft, const PathNetworkAccess& net) {
    const int n = int(ft.points.size());
    std::vector<std::vector<int>> nb(n);
    std::set<std::array<int, 2>> todo;  // interior edges not inserted, (lo, hi)
    for (std::size_t e = 0; e < ft.edges.size(); ++e)
        if (!ft.edge_on_border[e]) {
            const auto& ed = ft.edges[e];
            nb[ed[0]].push_back(ed[1]);
            nb[ed[1]].push_back(ed[0]);
            todo.insert({std::min(ed[0], ed[1]), std::max(ed[0], ed[1])});
        }
    auto done = [&](int u, int w) { todo.erase({std::min(u, w), std::max(u, w)}); };
    int version = 0;

    // The tree: candidates join a tree feature u to a feature w outside it.
    std::vector<char> in_tree(n, 0);
    for (int b : ft.border) in_tree[b] = 1;
    Queue queue;
    for (int b : ft.border)
        for (int x : nb[b])
            if (!in_tree[x]) queue.push({net.lower_bound(b, x), b, x, -1});
    const bool grown = run_stage(
        queue, net, version, [&](int, int w) { return !in_tree[w]; },
        [&](int u, int w) {
            done(u, w);
            in_tree[w] = 1;
            for (int x : nb[w])
                if (!in_tree[x]) queue.push({net.lower_bound(w, x), w, x, -1});
        });
    if (!grown) return false;
    if (std::count(in_tree.begin(), in_tree.end(), 0))
        throw InternalError("cut: the feature triangulation does not connect every feature to the border");

    // The closing edges.
    for (const auto& e : todo) queue.push({net.lower_bound(e[0], e[1]), e[0], e[1], -1});
    return run_stage(
        queue, net, version, [&](int u, int w) { return todo.count({std::min(u, w), std::max(u, w)}) > 0; },
        [&](int u, int w) { done(u, w); });
}

}  // namespace ctmap
