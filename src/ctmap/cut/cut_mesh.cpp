#include "ctmap/cut/cut_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

#include "ctmap/border_loop.h"
#include "ctmap/cut/approximate_path.h"
#include "ctmap/cut/exact_geodesic.h"
#include "ctmap/cut/guide_map.h"
#include "ctmap/cut/insert_path.h"
#include "ctmap/cut/insertion_order.h"
#include "ctmap/cut/straighten_path.h"
#include "ctmap/cut/work_mesh.h"
#include "ctmap/errors.h"
#include "ctmap/subdivide.h"

namespace ctmap {
namespace {

/// The path network as it grows: paths as vertex chains, what they block.
struct Network {
    WorkMesh mesh;
    const FeatureTriangulation& ft;
    std::vector<int> fv;  // feature -> vertex
    std::vector<char> blocked;
    std::unordered_set<std::uint64_t> path_edges;
    std::map<std::pair<int, int>, std::vector<int>> chains;  // (a, b) -> vertex chain from a to b
    std::vector<Vec2> guide;  // per vertex (guided cut only)

    Network(const TriMesh& m, const std::vector<int>& feature_vertex, const FeatureTriangulation& t)
        : mesh(m), ft(t), fv(feature_vertex), blocked(m.positions.size(), 0) {
        for (int v : fv) blocked[v] = 1;
    }

    bool embedded(int a, int b) const { return chains.count({a, b}) > 0; }

    void add_chain(int a, int b, const std::vector<int>& chain) {
        chains[{a, b}] = chain;
        chains[{b, a}] = std::vector<int>(chain.rbegin(), chain.rend());
        blocked.resize(mesh.positions.size(), 0);
        for (int v : chain) blocked[v] = 1;
        for (std::size_t i = 0; i + 1 < chain.size(); ++i) path_edges.insert(edge_key(chain[i], chain[i + 1]));
    }

    /// Sector at feature `u` for a new path towards neighbour `w` (DESIGN §2 condition 2).
    EndSector sector(int u, int w) const {
        const std::vector<int>& nb = ft.neighbours[u];
        const int d = int(nb.size());
        const int k = int(std::find(nb.begin(), nb.end(), w) - nb.begin());
        int prev = -1, next = -1;
        for (int s = 1; s < d && prev < 0; ++s)
            if (embedded(u, nb[(k - s + d) % d])) prev = nb[(k - s + d) % d];
        for (int s = 1; s < d && next < 0; ++s)
            if (embedded(u, nb[(k + s) % d])) next = nb[(k + s) % d];
        const auto fan = mesh.fan(fv[u]);
        EndSector out;
        if (prev < 0) {  // nothing embedded at u yet: every direction is allowed
            for (const auto& e : fan) {
                out.faces.push_back(e.face);
                out.edge_neighbours.push_back(e.to);
                out.edge_neighbours.push_back(e.from);
            }
            return out;
        }
        const int xp = chains.at({u, prev})[1], xq = chains.at({u, next})[1];
        const int n = int(fan.size());
        int i = 0;
        while (i < n && fan[i].from != xp) ++i;
        if (i == n) throw InternalError("cut: a path does not leave its feature along a mesh edge");
        for (int s = 0; s < n; ++s) {
            const auto& e = fan[(i + s) % n];
            out.faces.push_back(e.face);
            if (e.to == xq) break;
            out.edge_neighbours.push_back(e.to);
        }
        return out;
    }

    /// Inserts a Steiner vertex at the centre of every face in the sectors (condition 4).
    int refine_sector(const EndSector& s) {
        int added = 0;
        std::vector<Vec3> centres;
        std::vector<std::array<int, 3>> corners;
        for (int f : s.faces) corners.push_back(mesh.faces[f]);
        for (const auto& t : corners) {
            // Faces are renumbered by each insertion: find the face again by its corners.
            int f = -1;
            for (int g : mesh.vertex_faces[t[0]])
                if (mesh.faces[g] == t) f = g;
            if (f < 0) continue;
            insert_point(mesh, f, Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3));
            ++added;
        }
        blocked.resize(mesh.positions.size(), 0);
        return added;
    }
};

/// Area of the surface over the area of the image triangles: the square root scales the guide.
double area_ratio(const TriMesh& m, const FeatureTriangulation& ft) {
    double surface = 0, image = 0;
    for (const Tri& t : m.faces)
        surface += 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
    for (const Tri& t : ft.triangles) {
        const Vec2 a = ft.points[t[1]] - ft.points[t[0]], b = ft.points[t[2]] - ft.points[t[0]];
        image += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    }
    return image > 0 ? surface / image : 1.0;
}

double mean_edge_length(const TriMesh& m) {
    double sum = 0;
    for (const Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) sum += (m.positions[t[k]] - m.positions[t[(k + 1) % 3]]).norm();
    return sum / (3.0 * m.faces.size());
}

}  // namespace

double steiner_spacing(const TriMesh& mesh, const CutOptions& options) {
    return options.spacing_factor * mean_edge_length(mesh);
}

std::vector<int> border_features(const TriMesh& mesh, const std::vector<int>& feature_vertex) {
    std::unordered_map<int, int> feature_of;
    for (int i = 0; i < int(feature_vertex.size()); ++i) feature_of[feature_vertex[i]] = i;
    std::vector<int> out;
    for (int v : border_loop(mesh))
        if (feature_of.count(v)) out.push_back(feature_of[v]);
    return out;
}

namespace {

/// Barycentric coordinates of P in face f of `mesh`, by areas in the face's plane (P lies in it).
Vec3 barycentric(const TriMesh& mesh, int f, const Vec3& P) {
    const Tri& t = mesh.faces[f];
    const Vec3 &A = mesh.positions[t[0]], &B = mesh.positions[t[1]], &C = mesh.positions[t[2]];
    const Vec3 n = (B - A).cross(C - A);
    const double l1 = (P - A).cross(C - A).dot(n) / n.squaredNorm();
    const double l2 = (B - A).cross(P - A).dot(n) / n.squaredNorm();
    return Vec3(1 - l1 - l2, l1, l2);
}

/// The cut with the paths searched on the surface (`guided` false) or with the guide map; gives
/// up (nothing) when the work mesh gets more than `face_limit` faces. `stage` names its progress
/// lines (CutOptions::progress).
std::optional<CutMesh> cut_with(const TriMesh& input, const std::vector<int>& feature_vertex,
                                const FeatureTriangulation& ft, const CutOptions& opt, CutOptions::Order order, bool guided,
                                std::size_t face_limit, CutStats& stats, const std::string& stage) {
    Network net(input, feature_vertex, ft);
    const int nfeat = int(feature_vertex.size());
    double guide_weight = 0;
    if (guided) {
        net.guide = guide_map(input, feature_vertex, ft);
        guide_weight = opt.guide_weight * std::sqrt(area_ratio(input, ft));
        stats.guided = true;
    }

    // Border edges of the triangulation follow the mesh border (Table 1, first branch).
    std::vector<int> loop = net.mesh.border_loop();
    {
        const auto it = std::find_if(loop.begin(), loop.end(), [&](int v) {
            return std::find(feature_vertex.begin(), feature_vertex.end(), v) != feature_vertex.end();
        });
        std::rotate(loop.begin(), it, loop.end());
        loop.push_back(loop.front());
        std::unordered_map<int, int> feature_of;
        for (int i = 0; i < nfeat; ++i) feature_of[feature_vertex[i]] = i;
        std::vector<int> arc{loop[0]};
        for (std::size_t i = 1; i < loop.size(); ++i) {
            arc.push_back(loop[i]);
            if (feature_of.count(loop[i])) {
                net.add_chain(feature_of[arc.front()], feature_of[arc.back()], arc);
                arc = {loop[i]};
            }
        }
    }

    auto dist3 = [&](int a, int b) { return (input.positions[feature_vertex[a]] - input.positions[feature_vertex[b]]).norm(); };
    const bool shortest_path_first = order == CutOptions::Order::shortest_path && !opt.exact_geodesics;
    stats.shortest_path_first = shortest_path_first;
    const std::vector<std::array<int, 2>> nearest =
        shortest_path_first ? std::vector<std::array<int, 2>>() : nearest_first_order(ft, dist3);

    PathSearchOptions search;
    search.spacing = steiner_spacing(input, opt);
    search.corridor_rings = opt.corridor_rings;
    search.corridor_min_distance = opt.corridor_min_distance;
    int total = 0;
    for (std::size_t e = 0; e < ft.edges.size(); ++e) total += !ft.edge_on_border[e];

    // The path from u to w in the network as it stands, refining around its ends up to
    // `max_refinements` times when none is found (each refinement changes the mesh).
    // `missed`: a search without refinement already found nothing in the network as it stands
    // (insert_shortest_path_first's lazy candidates), so the first search is not run again.
    auto find = [&](int u, int w, int max_refinements, bool missed) {
        std::optional<FoundPath> found;
        for (int attempt = 0;; ++attempt) {
            PathConstraints c;
            c.source = feature_vertex[u];
            c.target = feature_vertex[w];
            c.blocked = &net.blocked;
            c.path_edges = &net.path_edges;
            c.source_sector = net.sector(u, w);
            c.target_sector = net.sector(w, u);
            if (guided) {
                extend_guide(net.mesh, net.guide);
                c.guide = &net.guide;
                c.guide_weight = guide_weight;
            }
            if (!(missed && attempt == 0)) {
                if (opt.exact_geodesics && attempt == 0 && !guided) {  // a geodesic ignores the guide
                    found = find_exact_path(net.mesh, c);
                    if (found) {
                        ++stats.exact_paths;
                        break;
                    }
                    ++stats.exact_rejected;
                }
                PathSearchOptions s = search;
                // Closer features get finer points (dense layouts), but at most 64 times finer: two
                // features a hair apart would otherwise put a million points on every edge met.
                s.spacing = search.spacing;
                if (opt.reach_spacing_factor > 0)
                    s.spacing = std::max(search.spacing / 64,
                                         std::min(search.spacing, opt.reach_spacing_factor * dist3(u, w)));
                s.spacing /= double(1 << std::min(attempt, 4));
                found = find_path(net.mesh, c, s);
            }
            if (found || attempt >= max_refinements) break;
            if (attempt == 0) ++stats.fallback_fired;
            const int added = net.refine_sector(c.source_sector) + net.refine_sector(net.sector(w, u));
            stats.steiner_vertices += added;
        }
        return found;
    };
    // Inserts the path `found` from u to w; false when the mesh outgrew the face limit.
    int inserted = 0;
    auto insert = [&](int u, int w, const FoundPath& found) {
        if (found.search == FoundPath::Search::corridor) ++stats.corridor_paths;
        if (found.search == FoundPath::Search::whole_graph_after_corridor) ++stats.corridor_misses;
        const int first_new = net.mesh.num_vertices();
        std::vector<int> chain = insert_path(net.mesh, found.nodes);
        if (opt.straighten) {
            StraightenStats st;
            chain = straighten_path(net.mesh, chain, first_new, net.blocked, net.path_edges, &st);
            stats.straightened_vertices += st.removed_vertices;
            stats.kept_runs += st.kept_runs;
        }
        // The length on the surface (a guided search's own lengths include the guide's).
        for (std::size_t k = 0; k + 1 < chain.size(); ++k)
            stats.path_length += (net.mesh.positions[chain[k + 1]] - net.mesh.positions[chain[k]]).norm();
        net.add_chain(u, w, chain);
        ++stats.paths;
        ++inserted;
        if (opt.progress) opt.progress(stage, inserted, total);
        if (net.mesh.faces.size() > face_limit) {
            stats.guide_restart_faces = int(net.mesh.faces.size());
            return false;
        }
        return true;
    };

    if (!shortest_path_first) {
        for (const auto& [u, w] : nearest) {
            const std::optional<FoundPath> found = find(u, w, opt.max_refinements, false);
            if (!found) throw no_path_error(u, w);
            if (!insert(u, w, *found)) return std::nullopt;
        }
    } else {
        PathNetworkAccess access;
        access.find = [&](int u, int w, bool refine, bool missed) {
            return find(u, w, refine ? opt.max_refinements : 0, refine && missed);
        };
        access.insert = insert;
        access.lower_bound = dist3;
        if (!insert_shortest_path_first(ft, access)) return std::nullopt;
    }

    // Patches: faces joined across non-path edges; each image triangle (a, b, c) owns the region
    // just counter-clockwise of the path a->b at a.
    const WorkMesh& m = net.mesh;
    const int nf = int(m.faces.size());
    // Path edges by edge id: the flood below crosses every face's edges, and a hash lookup each
    // was a tenth of the cut on a million triangles.
    std::vector<char> on_path(m.edges.size(), 0);
    for (const auto& [ends, chain] : net.chains) {
        if (ends.first > ends.second) continue;  // the same chain reversed: already marked
        for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
            const int e = m.find_edge(chain[i], chain[i + 1]);
            if (e < 0) throw InternalError("cut: a path runs along an edge the mesh does not have");
            on_path[e] = 1;
        }
    }
    std::vector<int> comp(nf, -1);
    int ncomp = 0;
    for (int f0 = 0; f0 < nf; ++f0) {
        if (comp[f0] >= 0) continue;
        std::vector<int> stack{f0};
        comp[f0] = ncomp;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const int e = m.face_edges[f][k];
                if (on_path[e]) continue;
                for (int g : m.edge_faces[e])
                    if (g >= 0 && comp[g] < 0) {
                        comp[g] = ncomp;
                        stack.push_back(g);
                    }
            }
        }
        ++ncomp;
    }
    CutMesh out;
    out.patches.resize(ft.triangles.size());
    std::vector<int> patch_of_comp(ncomp, -1);
    for (int t = 0; t < int(ft.triangles.size()); ++t) {
        const Tri& tri = ft.triangles[t];
        Patch& p = out.patches[t];
        p.corners = tri;
        for (int k = 0; k < 3; ++k) p.sides[k] = net.chains.at({tri[k], tri[(k + 1) % 3]});
        const int a = feature_vertex[tri[0]], xb = p.sides[0][1];
        int face = -1;
        for (const auto& e : m.fan(a))
            if (e.from == xb) face = e.face;
        if (face < 0 || patch_of_comp[comp[face]] >= 0)
            throw InternalError("cut: image triangle " + std::to_string(t) + " has no region of its own");
        patch_of_comp[comp[face]] = t;
    }
    if (std::count(patch_of_comp.begin(), patch_of_comp.end(), -1))
        throw InternalError("cut: a region of the mesh matches no image triangle");

    // Vertices straightening removed have no faces: the output numbers the others in order
    // (the input's keep their ids: none of them is ever removed).
    std::vector<int> id(m.positions.size(), -1);
    for (int v = 0; v < m.num_vertices(); ++v)
        if (!m.vertex_faces[v].empty()) {
            id[v] = int(out.mesh.positions.size());
            out.mesh.positions.push_back(m.positions[v]);
            if (v >= input.num_vertices()) ++(m.site[v][0] >= 0 ? stats.vertices_on_input_edges : stats.vertices_inside_faces);
        }
    out.num_input_vertices = input.num_vertices();
    for (const Tri& t : m.faces) out.mesh.faces.push_back({id[t[0]], id[t[1]], id[t[2]]});
    for (int v : feature_vertex) out.feature_vertex.push_back(id[v]);
    for (Patch& p : out.patches)
        for (auto& side : p.sides)
            for (int& v : side) v = id[v];
    out.face_patch.resize(nf);
    for (int f = 0; f < nf; ++f) out.face_patch[f] = patch_of_comp[comp[f]];
    out.vertex_face.assign(out.mesh.positions.size(), -1);
    out.vertex_bary.assign(out.mesh.positions.size(), Vec3::Zero());
    for (int v = 0; v < m.num_vertices(); ++v) {
        if (id[v] < 0) continue;
        const int f = m.origin[m.vertex_faces[v][0]];
        out.vertex_face[id[v]] = f;
        out.vertex_bary[id[v]] = barycentric(input, f, m.positions[v]);
    }
    stats.inserted_vertices = int(out.mesh.positions.size()) - input.num_vertices();
    out.steiner_vertices = stats.steiner_vertices;
    return out;
}

/// Re-expresses a cut of `input` subdivided `levels` times in terms of `input`: each vertex's
/// face becomes the input face its subdivided face lies in, with barycentric coordinates there;
/// the subdivision's midpoints count as inserted vertices (on input edges or inside faces).
void to_input_faces(const TriMesh& input, int levels, CutMesh& out, CutStats& stats) {
    const int shift = 2 * levels;
    stats.vertices_on_input_edges = stats.vertices_inside_faces = 0;
    for (std::size_t v = 0; v < out.mesh.positions.size(); ++v) {
        const int f = out.vertex_face[v] >> shift;
        out.vertex_face[v] = f;
        out.vertex_bary[v] = barycentric(input, f, out.mesh.positions[v]);
        if (int(v) < input.num_vertices()) continue;
        // On an input edge when a coordinate is zero to rounding (midpoints and path crossings
        // of input edges lie on them exactly in exact arithmetic).
        const double lo = out.vertex_bary[v].minCoeff();
        ++(std::abs(lo) < 1e-9 ? stats.vertices_on_input_edges : stats.vertices_inside_faces);
    }
    out.num_input_vertices = input.num_vertices();
    stats.inserted_vertices = int(out.mesh.positions.size()) - input.num_vertices();
}

}  // namespace

CutMesh cut_mesh(const TriMesh& input, const std::vector<int>& feature_vertex, const FeatureTriangulation& ft,
                 const CutOptions& opt, CutStats* stats_out) {
    CutStats stats;
    std::optional<CutMesh> out;
    const std::size_t unlimited = std::numeric_limits<std::size_t>::max();
    const bool automatic = opt.guide == CutOptions::Guide::automatic;
    CutOptions::Order order = opt.order;
    if (automatic) {
        // The paper's cut first; where the layout twists the features against the surface and
        // the mesh outgrows the limit, the same surface with the paths shortest first, then (with
        // a limit three times as large) the guide as well.
        const double limit = opt.growth_limit * (double(input.faces.size()) + 20.0 * double(feature_vertex.size()));
        auto capped = [](double x) { return std::size_t(std::min(x, 1e18)); };
        // (Asked for shortest first from the start: that cut alone, up to three times the limit.)
        int first_restart = 0, second_restart = 0;
        if (order != CutOptions::Order::shortest_path || opt.exact_geodesics) {
            out = cut_with(input, feature_vertex, ft, opt, order, false, capped(limit), stats, "paths");
            if (!out) first_restart = stats.guide_restart_faces;
        }
        if (!out && !opt.exact_geodesics) {
            order = CutOptions::Order::shortest_path;
            stats = CutStats();
            out = cut_with(input, feature_vertex, ft, opt, order, false, capped(3 * limit), stats,
                           first_restart > 0 ? "paths (again, shortest first)" : "paths");
            if (!out) second_restart = stats.guide_restart_faces;
        }
        if (!out) stats = CutStats();
        stats.guide_restart_faces = first_restart;
        stats.shortest_path_restart_faces = second_restart;
    }
    if (!out) {
        const bool guided = opt.guide != CutOptions::Guide::off;
        const int levels = guided ? opt.guide_subdivisions : 0;
        const int first_restart = stats.guide_restart_faces, second_restart = stats.shortest_path_restart_faces;
        const std::string stage = first_restart > 0 || second_restart > 0 ? "paths (again, guided)" : "paths";
        if (levels == 0) {
            out = cut_with(input, feature_vertex, ft, opt, order, guided, unlimited, stats, stage);
        } else {
            // The same surface with smaller faces: the input's vertices keep their ids, so the
            // features do; each input face f becomes faces f * 4^levels ... (f + 1) * 4^levels - 1.
            const TriMesh fine = subdivide_midpoint(input, levels);
            out = cut_with(fine, feature_vertex, ft, opt, order, guided, unlimited, stats, stage);
            if (out) to_input_faces(input, levels, *out, stats);
        }
        stats.guide_subdivisions = levels;
        stats.guide_restart_faces = first_restart;
        stats.shortest_path_restart_faces = second_restart;
    }
    if (!out) throw InternalError("cut: the cut gave up with no limit on its growth");
    if (stats_out) *stats_out = stats;
    return std::move(*out);
}

}  // namespace ctmap
