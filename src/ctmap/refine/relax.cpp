#include "ctmap/refine/relax.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "ctmap/certify/certificate.h"
#include "ctmap/embed/mean_value_embedding.h"
#include "ctmap/errors.h"
#include "ctmap/face_jacobian.h"
#include "ctmap/refine/segment_grid.h"

namespace ctmap {
namespace {

/// The ordered one-ring of every vertex, from the faces' orientation: for face (v, a, b), b
/// follows a counter-clockwise around v. A border vertex's ring starts at the neighbour across
/// its outgoing border edge (v1) and ends at the one across its incoming border edge (vn).
struct Rings {
    std::vector<int> offset;  // CSR into nbr
    std::vector<int> nbr;
    std::vector<char> border;
    std::vector<int> face_offset;  // CSR into faces
    std::vector<int> faces;

    explicit Rings(const TriMesh& m) {
        const int nv = m.num_vertices();
        std::vector<int> deg(nv + 1, 0);
        for (const Tri& t : m.faces)
            for (int v : t) ++deg[v + 1];
        face_offset.assign(nv + 1, 0);
        for (int v = 0; v < nv; ++v) face_offset[v + 1] = face_offset[v] + deg[v + 1];
        faces.resize(face_offset[nv]);
        std::vector<int> fill(face_offset.begin(), face_offset.end() - 1);
        for (int f = 0; f < m.num_faces(); ++f)
            for (int v : m.faces[f]) faces[fill[v]++] = f;
        offset.assign(nv + 1, 0);
        border.assign(nv, 0);
        nbr.reserve(face_offset[nv] + nv);
        std::vector<std::pair<int, int>> pairs;  // (a, b) per face (v, a, b)
        for (int v = 0; v < nv; ++v) {
            pairs.clear();
            for (int i = face_offset[v]; i < face_offset[v + 1]; ++i) {
                const Tri& t = m.faces[faces[i]];
                const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
                pairs.push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
            }
            offset[v] = int(nbr.size());
            if (pairs.empty()) {
                offset[v + 1] = int(nbr.size());
                continue;
            }
            int start = pairs[0].first;
            for (const auto& [a, b] : pairs) {
                bool has_pred = false;
                for (const auto& q : pairs) has_pred |= q.second == a;
                if (!has_pred) {
                    start = a;
                    border[v] = 1;
                    break;
                }
            }
            int cur = start;
            for (std::size_t s = 0; s < pairs.size(); ++s) {
                nbr.push_back(cur);
                int next = -1, count = 0;
                for (const auto& [a, b] : pairs)
                    if (a == cur) next = b, ++count;
                if (count != 1) throw InternalError("relax: the mesh is not manifold at vertex " + std::to_string(v));
                cur = next;
            }
            if (border[v]) nbr.push_back(cur);
            else if (cur != start) throw InternalError("relax: the mesh is not manifold at vertex " + std::to_string(v));
            offset[v + 1] = int(nbr.size());
        }
    }
    int begin(int v) const { return offset[v]; }
    int end(int v) const { return offset[v + 1]; }
};

int sign_of(double x) { return (x > 0) - (x < 0); }

/// Segments [s, p] and [s, q] share the end s; they overlap beyond it iff collinear and
/// pointing the same way (exact: orientation predicate, signs of coordinate differences).
bool overlap_at_shared_end(const Vec2& s, const Vec2& p, const Vec2& q) {
    return orientation_2d(s, p, q) == 0 && sign_of(p.x() - s.x()) == sign_of(q.x() - s.x()) &&
           sign_of(p.y() - s.y()) == sign_of(q.y() - s.y());
}

}  // namespace

std::vector<double> border_mean_value_weights(const Vec3& center, const std::vector<Vec3>& fan) {
    const std::size_t n = fan.size();
    if (n < 3) return {};
    std::vector<Vec3> circuit(fan);
    for (std::size_t j = 1; j + 1 < n; ++j) circuit.push_back(2.0 * center - fan[j]);
    std::vector<double> lambda;
    try {
        lambda = mean_value_weights(center, circuit);
    } catch (const std::invalid_argument&) {
        return {};
    }
    double virtual_sum = 0;
    for (std::size_t j = n; j < circuit.size(); ++j) virtual_sum += lambda[j];
    // D = 1 - 2 sum(lambda') is positive when the real half of the circuit outweighs the
    // virtual one, and may be small or negative at a sharp or strongly reflex border vertex. The
    // form is exact either way; what matters is its conditioning: sum |mu| is the factor by which
    // the target amplifies errors in the neighbours' UVs (1 for a convex combination). Beyond 20
    // the vertex is better left where it is.
    const double D = 1.0 - 2.0 * virtual_sum;
    if (!(std::abs(D) > 1e-12)) return {};
    std::vector<double> mu(n);
    mu[0] = lambda[0] / D;
    mu[n - 1] = lambda[n - 1] / D;
    for (std::size_t j = 1; j + 1 < n; ++j) mu[j] = (lambda[j] - lambda[n + j - 1]) / D;
    double amplification = 0;
    for (double x : mu) amplification += std::abs(x);
    if (!(amplification <= 20)) return {};
    return mu;
}

RelaxStats relax(const TriMesh& mesh, std::vector<Vec2>& uv, const std::vector<int>& fixed,
                 const RelaxOptions& options) {
    const int nv = mesh.num_vertices();
    if (int(uv.size()) != nv)
        throw InternalError("relax: " + std::to_string(uv.size()) + " UVs for " + std::to_string(nv) + " vertices");
    RelaxStats stats;
    if (mesh.faces.empty()) return stats;
    const Rings rings(mesh);

    // The map's orientation, and the precondition that it is valid.
    int sigma = 0;
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const Tri& t = mesh.faces[f];
        const int s = orientation_2d(uv[t[0]], uv[t[1]], uv[t[2]]);
        if (sigma == 0) sigma = s;
        if (s == 0 || s != sigma)
            throw InternalError("relax: the map is not valid on entry (UV triangle " + std::to_string(f) + " is " +
                                (s == 0 ? "degenerate" : "flipped") + ")");
    }

    // Weights, fixed for the whole run: they depend on the 3D mesh only.
    std::vector<char> is_fixed(nv, 0);
    for (int v : fixed)
        if (v >= 0 && v < nv) is_fixed[v] = 1;
    std::vector<int> w_offset(nv + 1, 0);
    std::vector<int> w_nbr;
    std::vector<double> w_val;
    std::vector<char> is_free(nv, 0);
    std::vector<Vec3> ring;
    for (int v = 0; v < nv; ++v) {
        w_offset[v] = int(w_nbr.size());
        if (is_fixed[v] || rings.begin(v) == rings.end(v) || (rings.border[v] && !options.move_border)) {
            w_offset[v + 1] = int(w_nbr.size());
            continue;
        }
        ring.clear();
        for (int i = rings.begin(v); i < rings.end(v); ++i) ring.push_back(mesh.positions[rings.nbr[i]]);
        std::vector<double> w;
        if (rings.border[v]) {
            w = border_mean_value_weights(mesh.positions[v], ring);
        } else {
            try {
                w = mean_value_weights(mesh.positions[v], ring);
            } catch (const std::invalid_argument&) {
                w.clear();  // degenerate in 3D: no average to move towards; the vertex stays
            }
        }
        if (!w.empty()) {
            is_free[v] = 1;
            ++stats.free_vertices;
            for (int i = rings.begin(v); i < rings.end(v); ++i) {
                w_nbr.push_back(rings.nbr[i]);
                w_val.push_back(w[i - rings.begin(v)]);
            }
        }
        w_offset[v + 1] = int(w_nbr.size());
    }

    // Border edges, one per border vertex: v -> v1 (its outgoing edge in the face order).
    std::vector<std::array<int, 2>> border_edges;
    std::vector<int> out_edge(nv, -1);
    for (int v = 0; v < nv; ++v)
        if (rings.border[v]) {
            out_edge[v] = int(border_edges.size());
            border_edges.push_back({v, rings.nbr[rings.begin(v)]});
        }
    auto in_edge = [&](int v) { return out_edge[rings.nbr[rings.end(v) - 1]]; };
    double mean_len = 0, max_len = 0;
    for (const auto& e : border_edges) {
        const double l = (uv[e[0]] - uv[e[1]]).norm();
        mean_len += l;
        max_len = std::max(max_len, l);
    }
    if (!border_edges.empty()) mean_len /= double(border_edges.size());
    // Cells about one edge long keep a query to a few cells; a few much longer edges must not
    // make a query cover thousands of cells.
    const double cell = std::max({mean_len, max_len / 8, 1e-300});
    SegmentGrid grid(cell, uv, border_edges);

    // Per face, what the symmetric Dirichlet energy needs of the 3D triangle (face_jacobian.h).
    std::vector<FaceFrame> frame(mesh.faces.size());
    double area3 = 0;
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const Tri& t = mesh.faces[f];
        frame[f] = face_frame(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
        area3 += frame[f].area;
    }
    // The energy the certificate reports: with J the unscaled Jacobian of a face and s^2 =
    // A3 / A2 the scale that brings the UV area A2 to the 3D area A3,
    //   E = sum A_f |sJ|^2 (1 + 1/det(sJ)^2) = (A3/A2) X + (A2/A3) Y,
    //   X = sum A_f |J|^2, Y = sum A_f |J|^2 / det(J)^2.
    // A move of v changes X, Y and A2 only through v's faces, so the guard compares the true
    // normalized energy before and after in O(degree).
    struct Sums {
        double x = 0, y = 0, a2 = 0;
    };
    auto face_sums = [&](int f, int v, const Vec2& p, Sums& out) {
        const FaceFrame& F = frame[f];
        const Tri& t = mesh.faces[f];
        const Vec2& a = t[0] == v ? p : uv[t[0]];
        const Vec2& b = t[1] == v ? p : uv[t[1]];
        const Vec2& c = t[2] == v ? p : uv[t[2]];
        const Vec2 q1 = b - a, q2 = c - a;
        const double cross = q1.x() * q2.y() - q1.y() * q2.x();
        out.a2 += 0.5 * std::abs(cross);
        if (F.area == 0) return;
        const Mat2 J = face_jacobian(F, a, b, c);
        const double fro = J.squaredNorm(), det = J.determinant();
        out.x += F.area * fro;
        out.y += F.area * fro / (det * det);
    };
    auto local_sums = [&](int v, const Vec2& p) {
        Sums s;
        for (int i = rings.face_offset[v]; i < rings.face_offset[v + 1]; ++i) face_sums(rings.faces[i], v, p, s);
        return s;
    };
    auto energy_of = [&](const Sums& t) { return (area3 / t.a2 * t.x + t.a2 / area3 * t.y) / area3; };
    // E(base + delta) - E(base), written in the deltas so that a small change of one vertex is
    // not lost in the rounding of sums over the whole mesh.
    auto energy_change = [&](const Sums& base, const Sums& delta) {
        const double A2 = base.a2, A2n = base.a2 + delta.a2;
        return area3 * (delta.x * A2 - base.x * delta.a2) / (A2 * A2n) +
               (A2 * delta.y + delta.a2 * base.y + delta.a2 * delta.y) / area3;
    };
    // The sums over every face, in fixed chunks added in order: the same bits whatever the
    // number of threads.
    auto sum_all_faces = [&]() {
        constexpr int kChunk = 4096;
        const int chunks = (mesh.num_faces() + kChunk - 1) / kChunk;
        std::vector<Sums> part(chunks);
        auto run = [&](int c) {
            const int end = std::min(mesh.num_faces(), (c + 1) * kChunk);
            for (int f = c * kChunk; f < end; ++f) face_sums(f, -1, Vec2::Zero(), part[c]);
        };
        if (options.parallel) tbb::parallel_for(0, chunks, run);
        else for (int c = 0; c < chunks; ++c) run(c);
        Sums t;
        for (const Sums& p : part) t = {t.x + p.x, t.y + p.y, t.a2 + p.a2};
        return t;
    };

    auto triangles_ok = [&](int v, const Vec2& p) {
        for (int i = rings.face_offset[v]; i < rings.face_offset[v + 1]; ++i) {
            const Tri& t = mesh.faces[rings.faces[i]];
            const Vec2& a = t[0] == v ? p : uv[t[0]];
            const Vec2& b = t[1] == v ? p : uv[t[1]];
            const Vec2& c = t[2] == v ? p : uv[t[2]];
            if (orientation_2d(a, b, c) != sigma) return false;
        }
        return true;
    };
    auto border_ok = [&](int v, const Vec2& p) {
        const int e_out = out_edge[v], e_in = in_edge(v);
        const int x1 = border_edges[e_out][1], xn = border_edges[e_in][0];
        if (overlap_at_shared_end(p, uv[x1], uv[xn])) return false;
        bool ok = true;
        for (const int x : {x1, xn}) {
            grid.query(p, uv[x], [&](int e) {
                if (!ok || e == e_out || e == e_in) return;
                const int a = border_edges[e][0], b = border_edges[e][1];
                if (a == x || b == x) {
                    if (overlap_at_shared_end(uv[x], p, uv[a == x ? b : a])) ok = false;
                } else if (segments_intersect_2d(p, uv[x], uv[a], uv[b])) {
                    ok = false;
                }
            });
            if (!ok) return false;
        }
        return true;
    };

    // With keep_in_box: how far a point is inside the box (negative outside), and how far a border
    // vertex must stay (or, if it starts nearer, must not come nearer).
    const double wall_gap = 1e-3 * (options.box_hi - options.box_lo).maxCoeff();
    auto wall_distance = [&](const Vec2& p) {
        return std::min({p.x() - options.box_lo.x(), p.y() - options.box_lo.y(), options.box_hi.x() - p.x(),
                         options.box_hi.y() - p.y()});
    };

    // Over-relaxation only with the guard: without it nothing stops an overshooting sweep from
    // growing (the virtual-image rows are affine, not convex; nefertiti's energy went to 1e19).
    const double omega = options.energy_guard ? options.over_relaxation : 1.0;
    // Set by a vertex's neighbours, possibly by two threads at once (always to 1).
    std::vector<char> active(nv, 1);
    auto activate = [&](int v) { std::atomic_ref<char>(active[v]).store(1, std::memory_order_relaxed); };

    // What the moves of a group of vertices did; added up in a fixed order after each phase.
    struct Tally {
        long moves = 0, shortened = 0, rejected = 0, border_rejections = 0, energy_rejections = 0;
        double max_move = 0;
        Sums delta;
    };
    // One vertex's move, judged against the energy sums `base` (see the phases below).
    auto relax_vertex = [&](int v, const Sums& base, double negligible, Tally& tally) {
        // Only vertices whose neighbourhood changed since they were last looked at can have a
        // new target or a newly allowed move: near convergence most of the mesh is skipped.
        if (!active[v]) return;
        active[v] = 0;
        Vec2 target = Vec2::Zero();
        for (int i = w_offset[v]; i < w_offset[v + 1]; ++i) target += w_val[i] * uv[w_nbr[i]];
        const Vec2 d = target - uv[v];
        if (!(d.norm() > negligible)) return;
        double step = omega;
        bool accepted = false;
        const Sums old_local = options.energy_guard ? local_sums(v, uv[v]) : Sums();
        Sums delta;
        auto energy_ok = [&](const Vec2& p) {
            const Sums l = local_sums(v, p);
            delta = {l.x - old_local.x, l.y - old_local.y, l.a2 - old_local.a2};
            return energy_change(base, delta) <= 0;
        };
        for (int h = 0; h <= options.max_halvings; ++h, step *= 0.5) {
            const Vec2 p = uv[v] + step * d;
            if (p == uv[v]) break;
            if (!triangles_ok(v, p)) continue;
            if (options.energy_guard && !energy_ok(p)) {
                ++tally.energy_rejections;
                // If even the shortest step raises the energy, the direction climbs: stop here
                // instead of trying every length in between.
                if (h == 0 && !energy_ok(uv[v] + omega * std::ldexp(1.0, -options.max_halvings) * d)) break;
                continue;
            }
            if (rings.border[v] && options.keep_in_box && wall_distance(p) < std::min(wall_gap, wall_distance(uv[v]))) {
                ++tally.border_rejections;
                continue;
            }
            if (rings.border[v] && options.check_border && !border_ok(v, p)) {
                ++tally.border_rejections;
                continue;
            }
            if (rings.border[v]) {
                grid.remove(out_edge[v]);
                grid.remove(in_edge(v));
                uv[v] = p;
                grid.insert(out_edge[v]);
                grid.insert(in_edge(v));
            } else {
                uv[v] = p;
            }
            accepted = true;
            if (options.energy_guard)
                tally.delta = {tally.delta.x + delta.x, tally.delta.y + delta.y, tally.delta.a2 + delta.a2};
            if (step < 1) ++tally.shortened;  // short of the target (an over-relaxed step halved once is not)
            break;
        }
        if (accepted) {
            ++tally.moves;
            tally.max_move = std::max(tally.max_move, step * d.norm());
            activate(v);
            for (int i = rings.begin(v); i < rings.end(v); ++i) activate(rings.nbr[i]);
        } else {
            ++tally.rejected;
        }
    };

    // The sweep in phases. Interior free vertices are coloured so that no two of one colour
    // share a face: a vertex's move reads and checks only its own faces, whose other corners
    // then stay put while its colour is moved, so a colour is moved in parallel and every
    // orientation check is exactly the one a single thread would make. The energy guard judges
    // the moves of a colour against the sums at the colour's start (each move changes only its
    // own faces' terms; the changes are added up after the colour), not against running sums.
    // Border vertices check their border edges against every other border edge, which may be
    // moving too, so they move one by one, each against the running sums. Chunks are fixed and
    // tallies added in order, so the result does not depend on the number of threads.
    std::vector<int> colour(nv, -1);
    std::vector<std::vector<int>> colours;
    std::vector<int> border_free;
    for (int v = 0; v < nv; ++v) {
        if (!is_free[v]) continue;
        if (rings.border[v]) {
            border_free.push_back(v);
            continue;
        }
        std::uint64_t used = 0;  // colours of the neighbours (a vertex has < 64 of them in practice)
        std::vector<char> used_big;
        for (int i = rings.begin(v); i < rings.end(v); ++i) {
            const int c = colour[rings.nbr[i]];
            if (c < 0) continue;
            if (c < 64) used |= std::uint64_t(1) << c;
            else {
                if (int(used_big.size()) <= c) used_big.resize(c + 1, 0);
                used_big[c] = 1;
            }
        }
        int c = 0;
        while (c < 64 && (used >> c & 1)) ++c;
        while (c >= 64 && c < int(used_big.size()) && used_big[c]) ++c;
        colour[v] = c;
        if (int(colours.size()) <= c) colours.resize(c + 1);
        colours[c].push_back(v);
    }
    auto add = [&](const Tally& t, Sums& total) {
        stats.moves += t.moves;
        stats.moves_shortened += t.shortened;
        stats.moves_rejected += t.rejected;
        stats.border_rejections += t.border_rejections;
        stats.energy_rejections += t.energy_rejections;
        total = {total.x + t.delta.x, total.y + t.delta.y, total.a2 + t.delta.a2};
    };

    for (int it = 0; it < options.max_iterations; ++it) {
        Eigen::AlignedBox2d box;
        for (const Vec2& p : uv) box.extend(p);
        const double diag = box.diagonal().norm();
        if (!(diag > 0)) break;
        const double negligible = 1e-3 * options.tolerance * diag;
        Sums total;
        double sweep_start_energy = 0;
        if (options.energy_guard) {  // recomputed each sweep so that rounding does not drift
            total = sum_all_faces();
            sweep_start_energy = energy_of(total);
            if (it == 0) stats.energy_before = sweep_start_energy;
        }
        double max_move = 0;
        for (const std::vector<int>& members : colours) {
            constexpr int kChunk = 256;
            const int chunks = (int(members.size()) + kChunk - 1) / kChunk;
            std::vector<Tally> tallies(chunks);
            const Sums base = total;
            auto run = [&](int c) {
                const int end = std::min(int(members.size()), (c + 1) * kChunk);
                for (int i = c * kChunk; i < end; ++i) relax_vertex(members[i], base, negligible, tallies[c]);
            };
            if (options.parallel) tbb::parallel_for(0, chunks, run);
            else for (int c = 0; c < chunks; ++c) run(c);
            for (const Tally& t : tallies) {
                add(t, total);
                max_move = std::max(max_move, t.max_move);
            }
        }
        for (int v : border_free) {
            Tally t;
            relax_vertex(v, total, negligible, t);
            add(t, total);
            max_move = std::max(max_move, t.max_move);
        }
        stats.iterations = it + 1;
        stats.last_gain = max_move / diag;
        if (options.energy_guard) stats.energy_after = energy_of(total);
        if (stats.last_gain < options.tolerance ||
            (options.energy_guard && stats.energy_after > (1 - options.energy_tolerance) * sweep_start_energy)) {
            stats.converged = true;
            break;
        }
    }
    return stats;
}

}  // namespace ctmap
