#include "ctmap/cut/approximate_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace ctmap {
namespace {

/// The Steiner graph, implicit and local: nodes are vertices (their index) and the points of
/// edges (a tagged key of edge and index), the number of points on an edge computed when the
/// search meets it. Nothing is proportional to the mesh, so a search costs what it explores: the
/// cut runs hundreds of searches on meshes of millions of faces.
class SearchState;

/// The faces a search may use: all of them, or those of a corridor, marked by a stamp in arrays
/// that live as long as the thread (no cost proportional to the mesh per search).
class Corridor {
public:
    /// Marks the faces around the vertices within `rings` rings of `seeds`.
    void build(const WorkMesh& m, const std::vector<int>& seeds, int rings) {
        if (++stamp_ == 0) {
            std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0);
            std::fill(face_stamp_.begin(), face_stamp_.end(), 0);
            stamp_ = 1;
        }
        if (vertex_stamp_.size() < m.positions.size()) vertex_stamp_.resize(m.positions.size() * 5 / 4 + 1, 0);
        if (face_stamp_.size() < m.faces.size()) face_stamp_.resize(m.faces.size() * 5 / 4 + 1, 0);
        std::vector<int> layer;
        for (int v : seeds)
            if (vertex_stamp_[v] != stamp_) {
                vertex_stamp_[v] = stamp_;
                layer.push_back(v);
            }
        std::vector<int> next;
        for (int r = 0; r <= rings; ++r) {
            next.clear();
            for (int v : layer)
                for (int f : m.vertex_faces[v]) {
                    face_stamp_[f] = stamp_;
                    if (r == rings) continue;
                    for (int w : m.faces[f])
                        if (vertex_stamp_[w] != stamp_) {
                            vertex_stamp_[w] = stamp_;
                            next.push_back(w);
                        }
                }
            layer.swap(next);
        }
    }
    bool has(int f) const { return face_stamp_[f] == stamp_; }

private:
    std::uint32_t stamp_ = 0;
    std::vector<std::uint32_t> vertex_stamp_, face_stamp_;
};

class SteinerGraph {
public:
    using Node = std::uint64_t;
    SteinerGraph(const WorkMesh& m, const PathConstraints& c, double spacing, SearchState& state,
                 const Corridor* corridor)
        : m_(m), c_(c), spacing_(spacing), state_(state), corridor_(corridor) {}
    bool allowed(int f) const { return !corridor_ || corridor_->has(f); }
    /// Number of points on edge e, from the search's cache (computed once per search and edge).
    inline int count(int e) const;
    /// Number of points on edge e, computed.
    int compute_count(int e) const {
        if (!m_.is_live_edge(e) || m_.is_border_edge(e) || c_.path_edges->count(m_.edges[e])) return 0;
        const int a = key_lo(m_.edges[e]), b = key_hi(m_.edges[e]);
        const int n = int(std::min(double(kMaxPoints), (m_.positions[a] - m_.positions[b]).norm() / spacing_));
        // Keep a way between blocked ends, the path's own ends counted as blocked: a path that
        // goes round and passes its own end again must cross the short edges from that end to
        // the paths beside it (with no point there, three_peaks twist 8 stopped with "no valid
        // path" in a region the path's end sector does reach).
        auto held = [&](int v) { return (*c_.blocked)[v] || v == c_.source || v == c_.target; };
        return n == 0 && held(a) && held(b) ? 1 : n;
    }
    static Node node(int e, int j) { return kSteiner | (Node(e) << 20) | Node(j); }
    static bool is_vertex(Node x) { return !(x & kSteiner); }
    /// Edge and index of a Steiner node.
    static std::pair<int, int> locate(Node x) { return {int((x & ~kSteiner) >> 20), int(x & (kMaxPoints - 1))}; }
    double t_of(int e, int j) const { return double(j + 1) / double(count(e) + 1); }
    Vec3 position(Node x) const {
        if (is_vertex(x)) return m_.positions[x];
        auto [e, j] = locate(x);
        const Vec3& a = m_.positions[key_lo(m_.edges[e])];
        const Vec3& b = m_.positions[key_hi(m_.edges[e])];
        return a + t_of(e, j) * (b - a);
    }
    /// The node's point in the guide map. \pre c.guide is set.
    Vec2 guide_position(Node x) const {
        const std::vector<Vec2>& g = *c_.guide;
        if (is_vertex(x)) return g[x];
        auto [e, j] = locate(x);
        const Vec2& a = g[key_lo(m_.edges[e])];
        return a + t_of(e, j) * (g[key_hi(m_.edges[e])] - a);
    }
    bool blocked(int v) const { return (*c_.blocked)[v] && v != c_.source && v != c_.target; }
    bool path_edge(int a, int b) const { return c_.path_edges->count(edge_key(a, b)) > 0; }

    /// Calls fn(next_node, face) for every move out of `x` (face = -1 for a move along an edge).
    template <class Fn>
    void for_each_move(Node node_x, Fn&& fn) const {
        if (is_vertex(node_x)) {
            const int x = int(node_x);
            const bool src = x == c_.source;
            for (int f : m_.vertex_faces[x]) {
                if (!allowed(f) || (src && !contains(c_.source_sector.faces, f))) continue;
                const Tri& t = m_.faces[f];
                const int k = t[0] == x ? 0 : t[1] == x ? 1 : 2;
                const int p = t[(k + 1) % 3], q = t[(k + 2) % 3];
                const int e = m_.face_edges[f][(k + 1) % 3];
                for (int j = 0, n = count(e); j < n; ++j) fn(node(e, j), f);
                // Edge moves: each edge (x, q) is met once, as the `to` side of a face.
                if (!path_edge(x, q) && (!src || contains(c_.source_sector.edge_neighbours, q))) fn(Node(q), -1);
                if (m_.is_border_edge(m_.face_edges[f][k]) && !path_edge(x, p) &&
                    (!src || contains(c_.source_sector.edge_neighbours, p)))
                    fn(Node(p), -1);
            }
        } else {
            const int e = locate(node_x).first;
            for (int f : m_.edge_faces[e]) {
                if (f < 0 || !allowed(f)) continue;
                const Tri& t = m_.faces[f];
                for (int k = 0; k < 3; ++k) {
                    const int g = m_.face_edges[f][k];
                    if (g == e) {
                        fn(Node(t[(k + 2) % 3]), f);  // the opposite corner
                    } else {
                        for (int i = 0, n = count(g); i < n; ++i) fn(node(g, i), f);
                    }
                }
            }
        }
    }

    /// Whether a move from `from` into the vertex `v` through `face` may end there.
    bool may_enter_vertex(Node from, int v, int face) const {
        if (v == c_.source || blocked(v)) return false;
        if (v != c_.target) return true;
        if (face >= 0) return contains(c_.target_sector.faces, face);
        return is_vertex(from) && contains(c_.target_sector.edge_neighbours, int(from));
    }

private:
    static constexpr int kMaxPoints = 1 << 20;
    static constexpr Node kSteiner = Node(1) << 63;
    const WorkMesh& m_;
    const PathConstraints& c_;
    double spacing_;
    SearchState& state_;
    const Corridor* corridor_;
};

/// Search state of one node.
struct NodeState {
    double dist = std::numeric_limits<double>::infinity();
    SteinerGraph::Node pred = ~SteinerGraph::Node(0);
    int pred_face = -1;
    bool done = false;
};

/// The search state of every node met, in arrays that live as long as the thread and are
/// reset lazily by a stamp: no per-search cost proportional to the mesh, and no hashing. Edge
/// points get their slots when the search first meets their edge.
class SearchState {
public:
    void begin(const WorkMesh& m) {
        if (++stamp_ == 0) {  // wrapped: forget every old stamp
            std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0);
            std::fill(edge_stamp_.begin(), edge_stamp_.end(), 0);
            stamp_ = 1;
        }
        if (vertex_stamp_.size() < m.positions.size()) {
            vertex_stamp_.resize(m.positions.size() + m.positions.size() / 4, 0);
            vertex_state_.resize(vertex_stamp_.size());
        }
        if (edge_stamp_.size() < m.edges.size()) {
            edge_stamp_.resize(m.edges.size() + m.edges.size() / 4, 0);
            edge_base_.resize(edge_stamp_.size());
            edge_points_.resize(edge_stamp_.size());
        }
        points_used_ = 0;
    }
    NodeState& at(const SteinerGraph& g, SteinerGraph::Node x) {
        if (g.is_vertex(x)) {
            if (vertex_stamp_[x] != stamp_) {
                vertex_stamp_[x] = stamp_;
                vertex_state_[x] = NodeState();
            }
            return vertex_state_[x];
        }
        auto [e, j] = g.locate(x);
        edge_count(g, e);
        return point_state_[edge_base_[e] + j];
    }
    /// The points on edge e; the first call of a search computes them and reserves their slots.
    int edge_count(const SteinerGraph& g, int e) {
        if (edge_stamp_[e] != stamp_) {
            edge_stamp_[e] = stamp_;
            edge_base_[e] = points_used_;
            edge_points_[e] = g.compute_count(e);
            points_used_ += std::size_t(edge_points_[e]);
            if (point_state_.size() < points_used_) point_state_.resize(points_used_ * 2);
            std::fill(point_state_.begin() + edge_base_[e], point_state_.begin() + points_used_, NodeState());
        }
        return edge_points_[e];
    }

private:
    std::uint32_t stamp_ = 0;
    std::vector<std::uint32_t> vertex_stamp_, edge_stamp_;
    std::vector<NodeState> vertex_state_, point_state_;
    std::vector<std::size_t> edge_base_;
    std::vector<int> edge_points_;
    std::size_t points_used_ = 0;
};

int SteinerGraph::count(int e) const { return state_.edge_count(*this, e); }

/// A* in the Steiner graph of the given spacing, inside `corridor` if there is one.
std::optional<FoundPath> search(const WorkMesh& mesh, const PathConstraints& c, double spacing,
                                const Corridor* corridor) {
    using Node = SteinerGraph::Node;
    thread_local SearchState states;
    states.begin(mesh);
    const SteinerGraph g(mesh, c, spacing, states, corridor);
    const Vec3 goal = mesh.positions[c.target];
    const bool guided = c.guide != nullptr;
    const Vec2 guide_goal = guided ? (*c.guide)[c.target] : Vec2::Zero();
    auto guide_of = [&](Node x) { return guided ? g.guide_position(x) : Vec2::Zero(); };
    auto state = [&](Node x) -> NodeState& { return states.at(g, x); };
    using Item = std::pair<double, Node>;  // (distance + bound, node)
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    const Node source = Node(c.source), target = Node(c.target);
    state(source).dist = 0;
    open.push({(mesh.positions[c.source] - goal).norm() + c.guide_weight * (guide_of(source) - guide_goal).norm(), source});
    bool reached = false;
    while (!open.empty()) {
        const Node x = open.top().second;
        open.pop();
        NodeState& sx = state(x);
        if (sx.done) continue;
        sx.done = true;
        if (x == target) {
            reached = true;
            break;
        }
        if (x != source && g.is_vertex(x) && g.blocked(int(x))) continue;
        const Vec3 px = g.position(x);
        const Vec2 gx = guide_of(x);
        const double dx = sx.dist;
        g.for_each_move(x, [&](Node y, int face) {
            if (g.is_vertex(y) && !g.may_enter_vertex(x, int(y), face)) return;
            NodeState& sy = state(y);  // may grow the arrays: no reference to sx is used after this
            if (sy.done) return;
            const Vec3 py = g.position(y);
            const Vec2 gy = guide_of(y);
            const double d = dx + (py - px).norm() + c.guide_weight * (gy - gx).norm();
            if (d < sy.dist) {
                sy.dist = d;
                sy.pred = x;
                sy.pred_face = face;
                open.push({d + (py - goal).norm() + c.guide_weight * (gy - guide_goal).norm(), y});
            }
        });
    }
    if (!reached) return std::nullopt;
    FoundPath out;
    out.length = state(target).dist;
    for (Node x = target;; x = state(x).pred) {
        const NodeState& sx = state(x);
        PathNode node;
        if (g.is_vertex(x)) node.vertex = int(x);
        else {
            auto [e, j] = g.locate(x);
            node.a = key_lo(mesh.edges[e]);
            node.b = key_hi(mesh.edges[e]);
            node.t = g.t_of(e, j);
        }
        node.face = sx.pred_face;
        out.nodes.push_back(node);
        if (x == source) break;
    }
    std::reverse(out.nodes.begin(), out.nodes.end());
    return out;
}

}  // namespace

std::optional<FoundPath> find_path(const WorkMesh& mesh, const PathConstraints& c, const PathSearchOptions& opt) {
    const double reach = (mesh.positions[c.source] - mesh.positions[c.target]).norm();
    if (opt.corridor_rings <= 0 || reach < opt.corridor_min_distance * opt.spacing)
        return search(mesh, c, opt.spacing, nullptr);
    auto whole_graph = [&] {
        std::optional<FoundPath> p = search(mesh, c, opt.spacing, nullptr);
        if (p) p->search = FoundPath::Search::whole_graph_after_corridor;
        return p;
    };
    const std::optional<FoundPath> coarse = search(mesh, c, opt.spacing * opt.coarse_factor, nullptr);
    if (!coarse) return whole_graph();
    std::vector<int> seeds;
    for (const PathNode& n : coarse->nodes) {
        if (n.vertex >= 0) {
            seeds.push_back(n.vertex);
        } else {
            seeds.push_back(n.a);
            seeds.push_back(n.b);
        }
    }
    thread_local Corridor corridor;
    corridor.build(mesh, seeds, opt.corridor_rings);
    if (std::optional<FoundPath> fine = search(mesh, c, opt.spacing, &corridor)) {
        fine->search = FoundPath::Search::corridor;
        return fine;
    }
    return whole_graph();
}

}  // namespace ctmap
