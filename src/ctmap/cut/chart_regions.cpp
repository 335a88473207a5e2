#include "ctmap/cut/chart_regions.h"

#include <algorithm>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>

#include "ctmap/cut/work_mesh.h"
#include "ctmap/errors.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

std::uint64_t directed_key(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

/// The mesh's directed edges (a -> b inside face f) and vertex neighbours.
struct Adjacency {
    std::unordered_map<std::uint64_t, int> face_of;  ///< directed edge -> the face on its left
    std::vector<std::vector<int>> neighbours;
    std::vector<char> on_border;

    explicit Adjacency(const TriMesh& m) : neighbours(m.positions.size()), on_border(m.positions.size(), 0) {
        face_of.reserve(3 * m.faces.size());
        for (int f = 0; f < m.num_faces(); ++f)
            for (int k = 0; k < 3; ++k) {
                const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
                face_of[directed_key(a, b)] = f;
                neighbours[a].push_back(b);
            }
        for (int f = 0; f < m.num_faces(); ++f)
            for (int k = 0; k < 3; ++k) {
                const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
                if (!face_of.count(directed_key(b, a))) {
                    on_border[a] = on_border[b] = 1;
                    neighbours[b].push_back(a);  // a border edge is listed from one side only
                }
            }
    }
    int left(int a, int b) const {
        const auto it = face_of.find(directed_key(a, b));
        return it == face_of.end() ? -1 : it->second;
    }
};

/// The border arc from a to b (both on the mesh border) that meets no blocked vertex, or empty.
std::vector<int> border_arc(const TriMesh& mesh, const Adjacency& adj, int a, int b, const std::vector<char>& blocked) {
    // The next border vertex after v (interior on the left): the b of the border edge v -> b.
    auto next = [&](int v, bool forward) {
        for (int w : adj.neighbours[v])
            if (forward ? (adj.left(v, w) >= 0 && adj.left(w, v) < 0) : (adj.left(w, v) >= 0 && adj.left(v, w) < 0))
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

/// A shortest path a -> b along mesh edges through free interior vertices (Dijkstra), or empty.
std::vector<int> shortest_path(const TriMesh& mesh, const Adjacency& adj, int a, int b, const std::vector<char>& blocked,
                               const std::set<std::uint64_t>& seam_edges) {
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
        if (v != a && (blocked[v] || adj.on_border[v])) continue;  // passes through free interior vertices only
        for (int w : adj.neighbours[v]) {
            if (w != b && (blocked[w] || adj.on_border[w])) continue;
            if (seam_edges.count(edge_key(v, w))) continue;
            const double nd = d + (mesh.positions[w] - mesh.positions[v]).norm();
            if (nd < dist[w]) dist[w] = nd, from[w] = v, queue.push({nd, w});
        }
    }
    if (from[b] < 0) return {};
    std::vector<int> path;
    for (int v = b; v >= 0; v = from[v]) path.push_back(v);
    std::reverse(path.begin(), path.end());
    return path;
}

/// The cyclic order of `names` restricted to `common`, starting at its smallest name.
std::vector<std::string> cyclic(const std::vector<std::string>& names, const std::set<std::string>& common) {
    std::vector<std::string> out;
    for (const std::string& n : names)
        if (common.count(n)) out.push_back(n);
    if (!out.empty()) std::rotate(out.begin(), std::min_element(out.begin(), out.end()), out.end());
    return out;
}

}  // namespace

ChartRegions chart_regions(const TriMesh& mesh, const std::vector<ChartOutline>& charts) {
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    for (const ChartOutline& c : charts) {
        if (c.border.size() < 3)
            throw BadInput("", "chart " + quoted_name(c.name) + ": its border needs at least 3 features");
        for (int v : c.border)
            if (v < 0 || v >= nv) throw BadInput("", "chart " + quoted_name(c.name) + ": border vertex out of range");
        for (int v : c.interior)
            if (v < 0 || v >= nv) throw BadInput("", "chart " + quoted_name(c.name) + ": feature vertex out of range");
    }
    // Two charts with the same border features (two sides of a closed mesh) go round them in
    // one cyclic order, in either direction.
    for (std::size_t i = 0; i < charts.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) {
            std::set<std::string> a(charts[i].border_names.begin(), charts[i].border_names.end()), common;
            for (const std::string& n : charts[j].border_names)
                if (a.count(n)) common.insert(n);
            if (common.size() < 3) continue;
            const std::vector<std::string> x = cyclic(charts[i].border_names, common);
            std::vector<std::string> y = cyclic(charts[j].border_names, common), y_back(y.rbegin(), y.rend());
            std::rotate(y_back.begin(), std::min_element(y_back.begin(), y_back.end()), y_back.end());
            if (x != y && x != y_back) {
                std::string list_x, list_y;
                for (const auto& n : x) list_x += (list_x.empty() ? "" : ", ") + n;
                for (const auto& n : y) list_y += (list_y.empty() ? "" : ", ") + n;
                throw BadInput("", "charts " + quoted_name(charts[j].name) + " and " + quoted_name(charts[i].name) +
                                       " go round their common border features in different orders (" + list_y +
                                       " against " + list_x + "): a seam is one line on the mesh, so list them in "
                                       "one cyclic order (either direction)");
            }
        }

    // A chart's interior feature may not be another chart's border feature (it would lie on a
    // seam, on no one side).
    std::map<int, std::pair<std::string, std::string>> border_of;  // vertex -> (feature, chart)
    for (const ChartOutline& c : charts)
        for (std::size_t i = 0; i < c.border.size(); ++i) border_of.emplace(c.border[i], std::make_pair(c.border_names[i], c.name));
    for (const ChartOutline& c : charts)
        for (std::size_t i = 0; i < c.interior.size(); ++i)
            if (const auto it = border_of.find(c.interior[i]); it != border_of.end())
                throw BadInput("", "feature " + quoted_name(c.interior_names[i]) + " is inside chart " + quoted_name(c.name) +
                                       " but on the border of chart " + quoted_name(it->second.second) +
                                       ": a feature on a seam is a border feature of every chart it is in");
    const Adjacency adj(mesh);
    std::vector<char> blocked(nv, 0);
    std::map<int, std::string> feature_name;
    for (const ChartOutline& c : charts) {
        for (std::size_t i = 0; i < c.border.size(); ++i) blocked[c.border[i]] = 1, feature_name[c.border[i]] = c.border_names[i];
        for (std::size_t i = 0; i < c.interior.size(); ++i)
            blocked[c.interior[i]] = 1, feature_name[c.interior[i]] = c.interior_names[i];
    }

    // The seam pieces, each traced once (by the first chart that lists its pair).
    ChartRegions out;
    std::map<std::uint64_t, int> piece_of;  // undirected feature pair -> seam index
    std::set<std::uint64_t> seam_edges;
    std::vector<std::vector<int>> loops(charts.size());  // per chart, its border loop as vertices in its order
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const ChartOutline& ch = charts[c];
        for (std::size_t i = 0; i < ch.border.size(); ++i) {
            const int a = ch.border[i], b = ch.border[(i + 1) % ch.border.size()];
            auto it = piece_of.find(edge_key(a, b));
            if (it == piece_of.end()) {
                std::vector<int> path;
                if (adj.on_border[a] && adj.on_border[b]) path = border_arc(mesh, adj, a, b, blocked);
                if (path.empty()) path = shortest_path(mesh, adj, a, b, blocked, seam_edges);
                if (path.empty())
                    throw BadInput("", "chart " + quoted_name(ch.name) + ": no seam joins its border features " +
                                           quoted_name(ch.border_names[i]) + " and " +
                                           quoted_name(ch.border_names[(i + 1) % ch.border.size()]) +
                                           " without touching another feature or seam (move one, or list the border "
                                           "in another order)");
                for (std::size_t k = 1; k + 1 < path.size(); ++k) blocked[path[k]] = 1;
                for (std::size_t k = 0; k + 1 < path.size(); ++k) seam_edges.insert(edge_key(path[k], path[k + 1]));
                it = piece_of.emplace(edge_key(a, b), int(out.seams.size())).first;
                out.seams.push_back(std::move(path));
            }
            std::vector<int> piece = out.seams[it->second];
            if (piece.front() != a) std::reverse(piece.begin(), piece.end());
            loops[c].insert(loops[c].end(), piece.begin(), piece.end() - 1);
        }
    }

    // Faces fall apart along the seams (and the mesh border) into components.
    std::vector<int> component(nf, -1);
    int components = 0;
    for (int f0 = 0; f0 < nf; ++f0) {
        if (component[f0] >= 0) continue;
        std::vector<int> stack{f0};
        component[f0] = components;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
                if (seam_edges.count(edge_key(a, b))) continue;
                const int g = adj.left(b, a);
                if (g >= 0 && component[g] < 0) component[g] = components, stack.push_back(g);
            }
        }
        ++components;
    }

    // Each chart's side: where its interior features are, else by the image's orientation.
    std::vector<int> a_face(nv, 0);
    for (int f = 0; f < nf; ++f)
        for (int v : mesh.faces[f]) a_face[v] = f;
    std::vector<int> chart_of_component(components, -1);
    out.face_chart.assign(nf, -1);
    // Charts with interior features first: they decide their side; a chart without any then
    // takes the side its image's orientation says, or the other one if that is taken (a mirrored
    // chart of a closed mesh's second half).
    std::vector<std::size_t> order;
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t c = 0; c < charts.size(); ++c)
            if (charts[c].interior.empty() == (pass == 1)) order.push_back(c);
    for (std::size_t c : order) {
        const ChartOutline& ch = charts[c];
        const std::vector<int>& loop = loops[c];
        const int left = adj.left(loop[0], loop[1]), right = adj.left(loop[1], loop[0]);
        const int left_side = left >= 0 ? component[left] : -1, right_side = right >= 0 ? component[right] : -1;
        if (left_side >= 0 && left_side == right_side)
            throw BadInput("", "chart " + quoted_name(ch.name) + ": its border does not cut the mesh in two (a handle of the "
                                   "mesh passes through it), so its region is not a disc: put the border round a "
                                   "disc of the mesh");
        std::set<int> sides;
        for (int v : ch.interior) sides.insert(component[a_face[v]]);  // v is on no seam: its faces are one side
        if (sides.size() > 1)
            throw BadInput("", "chart " + quoted_name(ch.name) + ": its interior features lie on both sides of its border "
                                   "on the mesh; each chart's interior features must be inside its border");
        int side = -1;
        if (!sides.empty()) {
            side = *sides.begin();
            if (side != left_side && side != right_side)
                throw BadInput("", "chart " + quoted_name(ch.name) + ": its interior features are not beside its border on "
                                       "the mesh; each chart's interior features must be inside its border");
        } else {
            const int preferred = ch.image_ccw ? left_side : right_side, other = ch.image_ccw ? right_side : left_side;
            side = preferred >= 0 && chart_of_component[preferred] < 0 ? preferred : other >= 0 ? other : preferred;
        }
        if (side < 0) throw BadInput("", "chart " + quoted_name(ch.name) + ": its border has no face beside it");
        if (chart_of_component[side] >= 0)
            throw BadInput("", "charts " + quoted_name(charts[chart_of_component[side]].name) + " and " + quoted_name(ch.name) +
                                   " both take the same region of the mesh");
        chart_of_component[side] = int(c);
    }
    for (int f = 0; f < nf; ++f) out.face_chart[f] = chart_of_component[component[f]];

    // Each region as a mesh of its own; a disc bounded by its chart's loop, holding exactly the
    // chart's interior features.
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const ChartOutline& ch = charts[c];
        ChartRegion r;
        std::vector<int> local(nv, -1);
        for (int f = 0; f < nf; ++f)
            if (out.face_chart[f] == int(c))
                for (int v : mesh.faces[f]) local[v] = 0;
        for (int v = 0; v < nv; ++v)
            if (local[v] == 0) local[v] = int(r.global.size()), r.global.push_back(v), r.mesh.positions.push_back(mesh.positions[v]);
        for (int f = 0; f < nf; ++f)
            if (out.face_chart[f] == int(c)) {
                r.faces.push_back(f);
                r.mesh.faces.push_back({local[mesh.faces[f][0]], local[mesh.faces[f][1]], local[mesh.faces[f][2]]});
            }
        const MeshTopology topo = compute_topology(r.mesh);
        std::set<int> loop_vertices(loops[c].begin(), loops[c].end());
        const bool bounded = topo.is_disc && topo.border_edges == int(loops[c].size());
        if (!bounded)
            throw BadInput("", "chart " + quoted_name(ch.name) + ": its region of the mesh is not a disc bounded by its border (" +
                                   std::to_string(topo.border_loops) + " border loops, Euler characteristic " +
                                   std::to_string(topo.euler) +
                                   "): on a mesh with handles or holes, the border must go round a disc");
        std::set<int> own(ch.interior.begin(), ch.interior.end());
        std::vector<std::string> foreign;
        for (const auto& [v, name] : feature_name)
            if (local[v] >= 0 && !loop_vertices.count(v) && !own.count(v)) foreign.push_back(name);
        if (!foreign.empty()) {
            std::string list;
            for (const auto& n : foreign) list += (list.empty() ? "" : ", ") + quoted_name(n);
            throw BadInput("", "chart " + quoted_name(ch.name) + ": its region of the mesh holds features of other charts (" +
                                   list + "): list them in this chart too, or move the border");
        }
        out.charts.push_back(std::move(r));
    }
    return out;
}

}  // namespace ctmap
