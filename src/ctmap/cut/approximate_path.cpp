#include "ctmap/cut/approximate_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace ctmap {
namespace {

bool contains(const std::vector<int>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

/// The Steiner graph, implicit: nodes are vertices, then the points of each edge in turn.
class SteinerGraph {
public:
    SteinerGraph(const WorkMesh& m, const PathConstraints& c, double spacing) : m_(m), c_(c) {
        const int ne = int(m.edges.size());
        offset_.resize(ne + 1);
        offset_[0] = 0;
        for (int e = 0; e < ne; ++e) {
            const int a = key_lo(m.edges[e]), b = key_hi(m.edges[e]);
            int n = 0;
            if (!m.is_border_edge(e) && !c.path_edges->count(m.edges[e])) {
                n = int((m.positions[a] - m.positions[b]).norm() / spacing);
                if (n == 0 && blocked(a) && blocked(b)) n = 1;  // keep a way between blocked ends
            }
            offset_[e + 1] = offset_[e] + n;
        }
    }
    int nv() const { return m_.num_vertices(); }
    int size() const { return nv() + offset_.back(); }
    int count(int e) const { return offset_[e + 1] - offset_[e]; }
    int node(int e, int j) const { return nv() + offset_[e] + j; }
    bool is_vertex(int x) const { return x < nv(); }
    /// Edge and index of a Steiner node.
    std::pair<int, int> locate(int x) const {
        const int k = x - nv();
        const int e = int(std::upper_bound(offset_.begin(), offset_.end(), k) - offset_.begin()) - 1;
        return {e, k - offset_[e]};
    }
    double t_of(int e, int j) const { return double(j + 1) / double(count(e) + 1); }
    Vec3 position(int x) const {
        if (is_vertex(x)) return m_.positions[x];
        auto [e, j] = locate(x);
        const Vec3& a = m_.positions[key_lo(m_.edges[e])];
        const Vec3& b = m_.positions[key_hi(m_.edges[e])];
        return a + t_of(e, j) * (b - a);
    }
    bool blocked(int v) const { return (*c_.blocked)[v] && v != c_.source && v != c_.target; }
    bool path_edge(int a, int b) const { return c_.path_edges->count(edge_key(a, b)) > 0; }

    /// Calls fn(next_node, face) for every move out of `x` (face = -1 for a move along an edge).
    template <class Fn>
    void for_each_move(int x, Fn&& fn) const {
        if (is_vertex(x)) {
            const bool src = x == c_.source;
            for (int f : m_.vertex_faces[x]) {
                if (src && !contains(c_.source_sector.faces, f)) continue;
                const Tri& t = m_.faces[f];
                const int k = t[0] == x ? 0 : t[1] == x ? 1 : 2;
                const int p = t[(k + 1) % 3], q = t[(k + 2) % 3];
                const int e = m_.find_edge(p, q);
                for (int j = 0; j < count(e); ++j) fn(node(e, j), f);
                // Edge moves: each edge (x, q) is met once, as the `to` side of a face.
                if (!path_edge(x, q) && (!src || contains(c_.source_sector.edge_neighbours, q))) fn(q, -1);
                if (m_.is_border_edge(m_.find_edge(x, p)) && !path_edge(x, p) &&
                    (!src || contains(c_.source_sector.edge_neighbours, p)))
                    fn(p, -1);
            }
        } else {
            auto [e, j] = locate(x);
            for (int f : m_.edge_faces[e]) {
                if (f < 0) continue;
                const Tri& t = m_.faces[f];
                for (int k = 0; k < 3; ++k) {
                    const int a = t[k], b = t[(k + 1) % 3];
                    const int g = m_.find_edge(a, b);
                    if (g == e) {
                        fn(t[(k + 2) % 3], f);  // the opposite corner
                    } else {
                        for (int i = 0; i < count(g); ++i) fn(node(g, i), f);
                    }
                }
            }
        }
    }

    /// Whether a move from `from` into the vertex `v` through `face` may end there.
    bool may_enter_vertex(int from, int v, int face) const {
        if (v == c_.source || blocked(v)) return false;
        if (v != c_.target) return true;
        if (face >= 0) return contains(c_.target_sector.faces, face);
        return contains(c_.target_sector.edge_neighbours, from);
    }

private:
    const WorkMesh& m_;
    const PathConstraints& c_;
    std::vector<int> offset_;
};

}  // namespace

std::optional<FoundPath> find_path(const WorkMesh& mesh, const PathConstraints& c, const PathSearchOptions& opt) {
    const SteinerGraph g(mesh, c, opt.spacing);
    const int n = g.size();
    const Vec3 goal = mesh.positions[c.target];
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    std::vector<int> pred(n, -1), pred_face(n, -1);
    std::vector<char> done(n, 0);
    using Item = std::pair<double, int>;  // (distance + bound, node)
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    dist[c.source] = 0;
    open.push({(mesh.positions[c.source] - goal).norm(), c.source});
    while (!open.empty()) {
        const int x = open.top().second;
        open.pop();
        if (done[x]) continue;
        done[x] = 1;
        if (x == c.target) break;
        if (x != c.source && g.is_vertex(x) && g.blocked(x)) continue;
        const Vec3 px = g.position(x);
        g.for_each_move(x, [&](int y, int face) {
            if (done[y]) return;
            if (g.is_vertex(y) && !g.may_enter_vertex(x, y, face)) return;
            const Vec3 py = g.position(y);
            const double d = dist[x] + (py - px).norm();
            if (d < dist[y]) {
                dist[y] = d;
                pred[y] = x;
                pred_face[y] = face;
                open.push({d + (py - goal).norm(), y});
            }
        });
    }
    if (!done[c.target]) return std::nullopt;
    FoundPath out;
    out.length = dist[c.target];
    for (int x = c.target; x >= 0; x = pred[x]) {
        PathNode node;
        if (g.is_vertex(x)) node.vertex = x;
        else {
            auto [e, j] = g.locate(x);
            node.a = key_lo(mesh.edges[e]);
            node.b = key_hi(mesh.edges[e]);
            node.t = g.t_of(e, j);
        }
        node.face = pred_face[x];
        out.nodes.push_back(node);
        if (x == c.source) break;
    }
    std::reverse(out.nodes.begin(), out.nodes.end());
    return out;
}

}  // namespace ctmap
