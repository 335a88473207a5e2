#include "ctmap/cut/seam_sides.h"

#include "ctmap/cut/seam_homology.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <functional>
#include <limits>
#include <queue>

#include "ctmap/edge_key.h"
#include "ctmap/errors.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

using Misplaced = ChartSides::Misplaced;

/// Per vertex, one face it is in (a vertex on no seam has all its faces on one side).
std::vector<int> some_face(const TriMesh& mesh) {
    std::vector<int> out(mesh.num_vertices(), -1);
    for (int f = 0; f < mesh.num_faces(); ++f)
        for (int v : mesh.faces[f]) out[v] = f;
    return out;
}

/// Per vertex, the piece it is an inner vertex of, or -1.
std::vector<int> inner_piece(const TriMesh& mesh, const SeamLayout& layout) {
    std::vector<int> out(mesh.num_vertices(), -1);
    for (std::size_t k = 0; k < layout.pieces.size(); ++k)
        for (std::size_t i = 1; i + 1 < layout.pieces[k].size(); ++i) out[layout.pieces[k][i]] = int(k);
    return out;
}

/// One vertex of each loop of the mesh border that holds no chart's border feature.
std::vector<int> border_loops_of_no_chart(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts) {
    std::vector<char> feature(mesh.num_vertices(), 0);
    for (const ChartOutline& ch : charts)
        for (int v : ch.border) feature[v] = 1;
    return free_border_loops(mesh, graph, feature);
}

std::string what(const std::vector<ChartOutline>& charts, const Misplaced& m) {
    return m.chart >= 0 ? "feature " + quoted_name(charts[m.chart].interior_names[m.index])
                        : "the mesh border loop through vertex " + std::to_string(m.vertex);
}

/// "the seam from 'x' to 'y' would have to pass ...", in the order of the chart whose side the
/// feature must be on when the piece is on its border, else of the first chart that has it.
std::string segment_text(const std::vector<ChartOutline>& charts, const SeamLayout& layout, const ChartSides& sides,
                         const Misplaced& m, int piece) {
    const int c = m.chart >= 0 ? m.chart : m.in_chart;
    for (int pass = 0; pass < 2; ++pass)
        for (int e = 0; e < int(charts.size()); ++e) {
            if (pass == 0 && e != c) continue;
            for (std::size_t i = 0; i < layout.chart_pieces[e].size(); ++i) {
                if (layout.chart_pieces[e][i].first != piece) continue;
                const ChartOutline& ch = charts[e];
                const std::string x = quoted_name(ch.border_names[i]);
                const std::string y = quoted_name(ch.border_names[(i + 1) % ch.border_names.size()]);
                std::string s = "the seam from " + x + " to " + y + " would have to pass " + what(charts, m);
                if (e == c && sides.side[c] >= 0) {
                    const bool left = m.chart >= 0 ? sides.on_left[c] : !sides.on_left[c];
                    s += std::string(" on its ") + (left ? "left" : "right") + " (going from " + x + " to " + y + ", " +
                         (m.chart >= 0 ? "on chart " + quoted_name(ch.name) + "'s side" : "outside chart " + quoted_name(ch.name)) +
                         ")";
                }
                return s;
            }
        }
    return "a seam would have to pass " + what(charts, m) + " on the other side";
}

/// The nearest piece to vertex p (3D distance to its vertices).
int nearest_piece(const TriMesh& mesh, const SeamLayout& layout, int p) {
    int best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < layout.pieces.size(); ++k)
        for (int v : layout.pieces[k])
            if (const double d = (mesh.positions[v] - mesh.positions[p]).squaredNorm(); d < best_d) best_d = d, best = int(k);
    return best;
}

[[noreturn]] void no_route(const TriMesh& mesh, const std::vector<ChartOutline>& charts, const SeamLayout& layout,
                           const ChartSides& sides, const Misplaced& m, int piece) {
    if (piece < 0) piece = nearest_piece(mesh, layout, m.vertex);
    const std::string where = m.in_chart >= 0 ? "on chart " + quoted_name(charts[m.in_chart].name) + "'s side"
                                              : "among the faces in no chart";
    const std::string seam = segment_text(charts, layout, sides, m, piece);
    if (m.chart >= 0) {
        const ChartOutline& ch = charts[m.chart];
        const std::string name = quoted_name(ch.interior_names[m.index]);
        throw BadInput("", "chart " + quoted_name(ch.name) + ": its feature " + name + " lies outside its border on the mesh (" +
                               where + "), and no seam keeps it inside: " + seam +
                               ", and every such route touches another feature or seam; move " + name +
                               " or the seam features around it");
    }
    throw BadInput("", "chart " + quoted_name(charts[m.in_chart].name) + ": its region of the mesh would hold " +
                           what(charts, m) + " and so not be a disc, and no seam keeps that loop outside: " + seam +
                           ", and every such route touches another feature or seam; move the seam features");
}

/// The shortest tether from m.vertex across the pieces `cross` into the piece m.side, ending
/// beside the rest of the border (a seam vertex of no piece in `cross`): a piece traced again
/// round it then has to pass m.vertex on that side, since it cannot pass the tether's other
/// end. The tether runs through free vertices of the two pieces of the mesh (never through
/// another owner's tether) and through inner vertices of the pieces in `cross`, each crossing
/// costing more than any detour.
std::vector<int> tether_path(const TriMesh& mesh, const SeamGraph& graph, const SeamLayout& layout, const ChartSides& sides,
                             const std::vector<int>& tether, const std::vector<int>& piece_of,
                             const std::vector<char>& cross, const Misplaced& m, int owner) {
    const int nv = mesh.num_vertices();
    const std::vector<int> face = some_face(mesh);
    auto component_of = [&](int v) { return face[v] >= 0 ? sides.component[face[v]] : -1; };
    const int side = m.side, here = component_of(m.vertex);
    // Seam vertices that stay: inner vertices and ends of the pieces not crossed.
    std::vector<char> stays(nv, 0);
    for (std::size_t k = 0; k < layout.pieces.size(); ++k)
        if (!cross[k])
            for (int v : layout.pieces[k]) stays[v] = 1;
    for (std::size_t k = 0; k < layout.pieces.size(); ++k)
        if (cross[k]) stays[layout.pieces[k].front()] = stays[layout.pieces[k].back()] = 0;
    auto target = [&](int v) {
        if (layout.blocked[v] || component_of(v) != side) return false;
        for (int w : graph.neighbours[v])
            if (stays[w]) return true;
        return false;
    };
    Eigen::AlignedBox3d box;
    for (const Vec3& x : mesh.positions) box.extend(x);
    const double crossing = 4 * box.diagonal().norm() + 1;
    std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
    std::vector<int> from(nv, -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[m.vertex] = 0;
    queue.push({0, m.vertex});
    int reached = -1;
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[v]) continue;
        if (v != m.vertex && target(v)) {
            reached = v;
            break;
        }
        for (int w : graph.neighbours[v]) {
            double step = (mesh.positions[w] - mesh.positions[v]).norm();
            if (layout.blocked[w]) {
                if (piece_of[w] < 0 || !cross[piece_of[w]]) continue;  // a feature, or a seam that stays
                step += crossing;
            } else {
                const int k = component_of(w);
                if ((k != side && k != here) || (tether[w] >= 0 && tether[w] != owner)) continue;
            }
            if (d + step < dist[w]) dist[w] = d + step, from[w] = v, queue.push({d + step, w});
        }
    }
    std::vector<int> path;
    for (int v = reached; v >= 0; v = from[v]) path.push_back(v);
    return path;
}

/// The movable pieces between the pieces of the mesh `a` and `b`, nearest to vertex p first.
std::vector<int> pieces_between(const TriMesh& mesh, const SeamGraph& graph, const SeamLayout& layout,
                                const ChartSides& sides, int a, int b, int p) {
    std::vector<std::pair<double, int>> found;
    for (std::size_t k = 0; k < layout.pieces.size(); ++k) {
        const std::vector<int>& path = layout.pieces[k];
        if (!layout.movable[k] || path.size() < 3) continue;
        const int l = graph.left(path[0], path[1]), r = graph.left(path[1], path[0]);
        const int cl = l >= 0 ? sides.component[l] : -1, cr = r >= 0 ? sides.component[r] : -1;
        if (!((cl == a && cr == b) || (cl == b && cr == a))) continue;
        double d = std::numeric_limits<double>::infinity();
        for (int v : path) d = std::min(d, (mesh.positions[v] - mesh.positions[p]).squaredNorm());
        found.push_back({d, int(k)});
    }
    std::sort(found.begin(), found.end());
    std::vector<int> out;
    for (const auto& [d, k] : found) out.push_back(k);
    return out;
}

/// Traces the pieces `redo` again, each a shortest path round every tether; false (and
/// `layout` as it was) if one has no route.
bool retrace(const TriMesh& mesh, const SeamGraph& graph, const std::vector<int>& tether, const std::set<int>& redo,
             SeamLayout& layout, const HandleLoops* handles) {
    const SeamLayout before = layout;
    for (int k : redo) {
        const std::vector<int>& old = layout.pieces[k];
        for (std::size_t j = 1; j + 1 < old.size(); ++j) layout.blocked[old[j]] = 0;
        for (std::size_t j = 0; j + 1 < old.size(); ++j) layout.seam_edges.erase(edge_key(old[j], old[j + 1]));
    }
    std::vector<char> avoid = layout.blocked;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (tether[v] >= 0) avoid[v] = 1;
    for (int k : redo) {
        const int a = layout.pieces[k].front(), b = layout.pieces[k].back();
        // On a mesh with handles, in the class the piece had (so the loop keeps splitting the mesh).
        std::vector<int> fresh = handles && handles->count > 0
                                     ? seam_path_of_parity(mesh, graph, *handles, a, b, handles->parity(before.pieces[k], false),
                                                           avoid, layout.seam_edges, nullptr)
                                     : seam_shortest_path(mesh, graph, a, b, avoid, layout.seam_edges);
        if (fresh.empty()) {
            layout = before;
            return false;
        }
        for (std::size_t j = 1; j + 1 < fresh.size(); ++j) layout.blocked[fresh[j]] = avoid[fresh[j]] = 1;
        for (std::size_t j = 0; j + 1 < fresh.size(); ++j) layout.seam_edges.insert(edge_key(fresh[j], fresh[j + 1]));
        layout.pieces[k] = std::move(fresh);
        layout.rerouted.insert(k);
    }
    return true;
}

/// One move for `m`: a tether across the nearest piece (or the nearest two: a feature wedged
/// between two pieces needs both to move) and those pieces traced again round it. False if no
/// attempt finds a route (`tethered`: false if not even a tether was found, as for a feature
/// walled in by other features); `tether` and `layout` are changed only by a move made.
bool move_across(const TriMesh& mesh, const SeamGraph& graph, const ChartSides& sides, const Misplaced& m, int owner,
                 std::vector<int>& tether, SeamLayout& layout, int& nearest, bool& tethered, const HandleLoops* handles) {
    const int nv = mesh.num_vertices();
    const std::vector<int> face = some_face(mesh);
    const std::vector<int> piece_of = inner_piece(mesh, layout);
    const std::vector<int> between =
        pieces_between(mesh, graph, layout, sides, sides.component[face[m.vertex]], m.side, m.vertex);
    nearest = between.empty() ? -1 : between.front();
    const std::size_t near = std::min<std::size_t>(between.size(), 6);
    std::vector<std::vector<int>> attempts;
    for (std::size_t a = 0; a < near; ++a) attempts.push_back({between[a]});
    for (std::size_t a = 0; a < near; ++a)
        for (std::size_t b = a + 1; b < near; ++b) attempts.push_back({between[a], between[b]});
    for (const std::vector<int>& attempt : attempts) {
        std::vector<char> cross(layout.pieces.size(), 0);
        for (int k : attempt) cross[k] = 1;
        const std::vector<int> path = tether_path(mesh, graph, layout, sides, tether, piece_of, cross, m, owner);
        bool crosses = false;
        for (int v : path) crosses = crosses || piece_of[v] >= 0;
        if (!crosses) continue;
        tethered = true;
        const std::set<int> redo(attempt.begin(), attempt.end());
        // Round every tether so far; where they leave no route, round the owner's own and this
        // one; then round this one alone (what the others hold is checked again next round, and
        // tethered again if the new pieces left it on the wrong side).
        for (int keep = 0; keep < 3; ++keep) {
            std::vector<int> with(nv, -1);
            for (int v = 0; v < nv; ++v)
                if (tether[v] >= 0 && (keep == 0 || (keep == 1 && tether[v] == owner))) with[v] = tether[v];
            for (int v : path) with[v] = owner;
            if (retrace(mesh, graph, with, redo, layout, handles)) {
                tether = std::move(with);
                return true;
            }
        }
    }
    return false;
}

}  // namespace

std::vector<int> chart_loop(const SeamLayout& layout, int c) {
    std::vector<int> loop;
    for (const auto& [piece, forward] : layout.chart_pieces[c]) {
        const std::vector<int>& path = layout.pieces[piece];
        if (forward)
            loop.insert(loop.end(), path.begin(), path.end() - 1);
        else
            loop.insert(loop.end(), path.rbegin(), path.rend() - 1);
    }
    return loop;
}

ChartSides chart_sides(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                       const SeamLayout& layout) {
    ChartSides out;
    out.component = seam_components(mesh, graph, layout.seam_edges, out.components);
    const std::vector<int> face = some_face(mesh);
    auto component_of = [&](int v) { return face[v] >= 0 ? out.component[face[v]] : -1; };
    const std::size_t nc = charts.size();
    out.side.assign(nc, -1);
    out.on_left.assign(nc, 0);
    std::vector<int> taken(out.components, -1), other_side(nc, -1);
    // On a closed mesh with handles, the side a chart's features choose may hold a handle while
    // the other side is a disc: then the disc is the chart's, and its features are misplaced.
    const bool closed = std::none_of(graph.on_border.begin(), graph.on_border.end(), [](char b) { return b != 0; });
    const bool has_handles = closed && mesh.num_vertices() - mesh.num_faces() / 2 < 2;
    auto is_disc = [&](int piece) {
        std::set<std::uint64_t> edges;
        std::set<int> vertices;
        int faces = 0;
        for (int f = 0; f < mesh.num_faces(); ++f)
            if (out.component[f] == piece) {
                ++faces;
                for (int k = 0; k < 3; ++k) vertices.insert(mesh.faces[f][k]), edges.insert(edge_key(mesh.faces[f][k], mesh.faces[f][(k + 1) % 3]));
            }
        return int(vertices.size()) - int(edges.size()) + faces == 1;
    };
    // Charts with interior features first: they decide their side; a chart without any then
    // takes the side its image's orientation says, or the other one if that is taken (a mirrored
    // chart of a closed mesh's second half).
    std::vector<std::size_t> order;
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t c = 0; c < nc; ++c)
            if (charts[c].interior.empty() == (pass == 1)) order.push_back(c);
    for (std::size_t c : order) {
        const ChartOutline& ch = charts[c];
        const std::vector<int> loop = chart_loop(layout, int(c));
        const int left = graph.left(loop[0], loop[1]), right = graph.left(loop[1], loop[0]);
        const int l = left >= 0 ? out.component[left] : -1, r = right >= 0 ? out.component[right] : -1;
        if (l >= 0 && l == r) {
            if (out.error.empty())
                out.error = "chart " + quoted_name(ch.name) + ": its border does not cut the mesh in two (a handle of the "
                            "mesh passes through it), so its region is not a disc: put the border round a disc of the mesh";
            continue;
        }
        int nl = 0, nr = 0;
        for (int v : ch.interior) nl += component_of(v) == l, nr += component_of(v) == r;
        const int preferred = ch.image_ccw ? l : r;
        int first = nl > nr ? l : nr > nl ? r : preferred, second = first == l ? r : l;
        if (has_handles && first >= 0 && second >= 0 && taken[second] < 0 && !is_disc(first) && is_disc(second))
            std::swap(first, second);
        int side = -1;
        for (int s : {first, second})
            if (s >= 0 && taken[s] < 0) {
                side = s;
                break;
            }
        if (side < 0) {
            if (out.error.empty()) {
                const int s = first >= 0 ? first : second;
                out.error = s < 0 ? "chart " + quoted_name(ch.name) + ": its border has no face beside it"
                                  : "charts " + quoted_name(charts[taken[s]].name) + " and " + quoted_name(ch.name) +
                                        " both take the same region of the mesh";
            }
            continue;
        }
        taken[side] = int(c);
        out.side[c] = side;
        out.on_left[c] = side == l;
        other_side[c] = side == l ? r : l;
    }
    auto chart_in = [&](int v) { return component_of(v) >= 0 ? taken[component_of(v)] : -1; };
    for (std::size_t c = 0; c < nc; ++c)
        for (std::size_t i = 0; i < charts[c].interior.size(); ++i) {
            const int v = charts[c].interior[i];
            if (out.side[c] >= 0 && component_of(v) != out.side[c])
                out.misplaced.push_back({v, int(c), int(i), chart_in(v), out.side[c]});
        }
    for (int v : border_loops_of_no_chart(mesh, graph, charts))
        if (const int c = chart_in(v); c >= 0 && other_side[c] >= 0) out.misplaced.push_back({v, -1, -1, c, other_side[c]});
    return out;
}

void keep_features_on_their_sides(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                                  SeamLayout& layout, const HandleLoops* handles) {
    int features = 0;
    for (const ChartOutline& ch : charts) features += int(ch.interior.size());
    const int rounds = 8 + 4 * (features + 4);
    std::vector<int> tether(mesh.num_vertices(), -1);  // per vertex: the owner whose tether passes through it, or -1
    for (int round = 0;; ++round) {
        const ChartSides sides = chart_sides(mesh, graph, charts, layout);
        if (!sides.error.empty() || sides.misplaced.empty()) return;
        if (round == rounds) no_route(mesh, charts, layout, sides, sides.misplaced.front(), -1);
        // The first misplaced thing that can be moved. If none can, the one reported is the
        // first that not even a tether reaches (walled in by features), else the first.
        bool moved = false;
        int walled = -1, first_piece = -1;
        for (std::size_t j = 0; j < sides.misplaced.size() && !moved; ++j) {
            const Misplaced& m = sides.misplaced[j];
            const int owner = m.chart >= 0 ? m.chart : int(charts.size());  // border loops: the rest's
            int nearest = -1;
            bool tethered = false;
            moved = move_across(mesh, graph, sides, m, owner, tether, layout, nearest, tethered, handles);
            if (j == 0) first_piece = nearest;
            if (!moved && !tethered && walled < 0) walled = int(j);
        }
        if (!moved) no_route(mesh, charts, layout, sides, sides.misplaced[std::max(walled, 0)], walled >= 0 ? -1 : first_piece);
    }
}

}  // namespace ctmap
