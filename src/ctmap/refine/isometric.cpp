#include "ctmap/refine/isometric.h"

#include <Eigen/SparseCore>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "ctmap/border_loop.h"
#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/face_jacobian.h"
#include "ctmap/refine/border_guard.h"
#include "ctmap/refine/box_barrier.h"
#include "ctmap/refine/face_newton.h"
#include "ctmap/refine/flip_free_step.h"
#include "ctmap/refine/newton_system.h"
#include "ctmap/refine/sparse_cholesky.h"

namespace ctmap {
namespace {

/// Sums over the faces in fixed chunks added in order: the same bits whatever the threads.
template <class F>
double chunked_sum(int n, bool parallel, F&& term) {
    constexpr int kChunk = 4096;
    const int chunks = (n + kChunk - 1) / kChunk;
    std::vector<double> part(chunks, 0.0);
    auto run = [&](int c) {
        double s = 0;
        const int end = std::min(n, (c + 1) * kChunk);
        for (int i = c * kChunk; i < end; ++i) s += term(i);
        part[c] = s;
    };
    if (parallel) tbb::parallel_for(0, chunks, run);
    else for (int c = 0; c < chunks; ++c) run(c);
    double s = 0;
    for (double p : part) s += p;
    return s;
}

template <class F>
void for_faces(int n, bool parallel, F&& f) {
    if (parallel) tbb::parallel_for(0, n, [&](int i) { f(i); });
    else for (int i = 0; i < n; ++i) f(i);
}

}  // namespace

IsometricStats optimise_isometric(const TriMesh& mesh, std::vector<Vec2>& uv, const std::vector<int>& fixed,
                                  const IsometricOptions& o) {
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    if (int(uv.size()) != nv)
        throw BadInput("", "optimise_isometric: " + std::to_string(uv.size()) + " UVs for " + std::to_string(nv) +
                               " vertices");
    if (!(o.scale >= 0) || !std::isfinite(o.scale))
        throw BadInput("", "optimise_isometric: the scale must be a finite number >= 0");
    IsometricStats stats;
    if (nf == 0) {
        stats.stop = "no free vertex";
        return stats;
    }
    std::vector<char> is_fixed(nv, 0);
    for (int v : fixed) {
        if (v < 0 || v >= nv)
            throw BadInput("", "optimise_isometric: fixed vertex " + std::to_string(v) + " is out of range");
        is_fixed[v] = 1;
    }
    const bool local_only = !o.movable.empty();
    if (local_only) {
        std::vector<char> may_move(nv, 0);
        for (int v : o.movable) {
            if (v < 0 || v >= nv)
                throw BadInput("", "optimise_isometric: movable vertex " + std::to_string(v) + " is out of range");
            may_move[v] = 1;
        }
        for (int v = 0; v < nv; ++v)
            if (!may_move[v]) is_fixed[v] = 1;
    }
    // The faces whose energy can change: those with a vertex that is not held (all of them unless
    // `movable` restricts the moving vertices). Only these are visited in the iterations.
    std::vector<int> active;
    std::vector<Tri> active_tris;
    for (int f = 0; f < nf; ++f) {
        const Tri& t = mesh.faces[f];
        if (!local_only || !is_fixed[t[0]] || !is_fixed[t[1]] || !is_fixed[t[2]]) active.push_back(f);
    }
    const int na = int(active.size());
    // The map's orientation, and the precondition that it is valid.
    int sigma = 0;
    for (int f = 0; f < nf; ++f) {
        const Tri& t = mesh.faces[f];
        const int s = orientation_2d(uv[t[0]], uv[t[1]], uv[t[2]]);
        if (sigma == 0) sigma = s;
        if (s == 0 || s != sigma)
            throw BadInput("", "optimise_isometric: the map is not valid on entry (UV triangle " + std::to_string(f) +
                                   " is " + (s == 0 ? "degenerate" : "flipped") + ")");
    }

    // Frames of the mesh scaled to the map's UV area (mirrored for a clockwise map, so that
    // every Jacobian has a positive determinant).
    double area3 = 0, area2 = 0;
    for (const Tri& t : mesh.faces) {
        area3 += face_frame(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]).area;
        const Vec2 q1 = uv[t[1]] - uv[t[0]], q2 = uv[t[2]] - uv[t[0]];
        area2 += 0.5 * std::abs(q1.x() * q2.y() - q1.y() * q2.x());
    }
    if (!(area3 > 0) || !(area2 > 0) || !std::isfinite(area3)) {
        stats.stop = "no free vertex";
        return stats;
    }
    // (Measured and rejected: the scale at which the entry map's energy is least, or the area
    // median of the faces' scales. They halve the iterations on some sets, but a relaxed map that
    // squeezes most faces gets a tiny scale there and converges to a far more distorted map.)
    const double k = o.scale > 0 ? o.scale : std::sqrt(area2 / area3);
    stats.scale = k;
    std::vector<FaceFrame> frame(nf);
    double area_sum = 0;
    for (int f = 0; f < nf; ++f) {
        const Tri& t = mesh.faces[f];
        frame[f] = face_frame(k * mesh.positions[t[0]], k * mesh.positions[t[1]], k * mesh.positions[t[2]], sigma < 0);
        area_sum += frame[f].area;
    }
    // A face's term of the energy (before the division by the total area).
    auto face_term = [](const FaceFrame& F, const Tri& t, const std::vector<Vec2>& x) {
        if (F.area == 0) return 0.0;
        return F.area * symmetric_dirichlet_density(face_jacobian(F, x[t[0]], x[t[1]], x[t[2]]));
    };
    auto face_energy = [&](int f, const std::vector<Vec2>& x) { return face_term(frame[f], mesh.faces[f], x); };
    // The held faces' share, once (0 when every face is active: the same bits as a plain sum).
    double held_energy = 0;
    if (local_only) {
        std::vector<char> is_active(nf, 0);
        for (int f : active) is_active[f] = 1;
        held_energy = chunked_sum(nf, o.parallel, [&](int f) { return is_active[f] ? 0.0 : face_energy(f, uv); });
    }
    // The active faces' frames and corners in the order of `active` (set below, with the unknowns).
    std::vector<FaceFrame> active_frame;
    auto energy_of = [&](const std::vector<Vec2>& x) {
        return (held_energy +
                chunked_sum(na, o.parallel, [&](int i) { return face_term(active_frame[i], active_tris[i], x); })) /
               area_sum;
    };

    // Unknowns per vertex.
    const std::vector<int> loop = border_loop(mesh);
    std::vector<char> used(nv, 0), on_border(nv, 0);
    for (const Tri& t : mesh.faces)
        for (int v : t) used[v] = 1;
    for (int v : loop) on_border[v] = 1;
    // The image rectangle (widened to hold the starting map).
    const double inf = std::numeric_limits<double>::infinity();
    Vec2 box_lo = o.keep_in_box ? o.box_lo : Vec2(-inf, -inf), box_hi = o.keep_in_box ? o.box_hi : Vec2(inf, inf);
    for (int v : loop) box_lo = box_lo.cwiseMin(uv[v]), box_hi = box_hi.cwiseMax(uv[v]);
    auto on_wall = [&](const Vec2& p) {
        return p.x() <= box_lo.x() || p.x() >= box_hi.x() || p.y() <= box_lo.y() || p.y() >= box_hi.y();
    };
    std::vector<Dof> dof(nv);
    for (int v = 0; v < nv; ++v) {
        if (!used[v] || is_fixed[v]) continue;
        if (on_border[v] && o.border == BorderMode::fixed) continue;  // set below
        // A free border vertex already on the rectangle's edge (a side of the image's own
        // border) stays there: the barrier below would be infinite for it.
        if (on_border[v] && on_wall(uv[v])) continue;
        dof[v].n = 2;
    }
    if (o.border == BorderMode::fixed) {
        // Each side runs from one fixed border vertex to the next along the loop.
        const int n = int(loop.size());
        int start = -1;
        for (int i = 0; i < n && start < 0; ++i)
            if (is_fixed[loop[i]]) start = i;
        if (start >= 0)
            for (int s = 0; s < n;) {
                const int a = loop[(start + s) % n];
                int e = s + 1;
                while (e < n && !is_fixed[loop[(start + e) % n]]) ++e;
                const int b = loop[(start + e) % n];
                const Vec2 dir = uv[b] - uv[a];
                for (int i = s + 1; i < e; ++i) {
                    Dof& d = dof[loop[(start + i) % n]];
                    if (!(dir.squaredNorm() > 0)) continue;  // stays fixed
                    d.n = 1;
                    d.dir = dir;
                }
                s = e;
            }
    }
    // Numbered vertex by vertex in a fill-reducing order (sparse_cholesky.h); a local
    // optimisation's small system is ordered by its simplicial factorisation.
    std::vector<int> order;
    if (local_only) {
        for (int v = 0; v < nv; ++v)
            if (dof[v].n > 0) order.push_back(v);
    } else {
        std::vector<char> has_unknowns(nv, 0);
        for (int v = 0; v < nv; ++v) has_unknowns[v] = dof[v].n > 0;
        order = fill_reducing_order(mesh.faces, has_unknowns);
    }
    int unknowns = 0;
    for (int v : order) {
        dof[v].first = unknowns;
        unknowns += dof[v].n;
        if (dof[v].n == 2) ++stats.free_vertices;
        else ++stats.sliding_vertices;
    }
    // The active faces in the unknowns' order (each face by its vertex that comes first in it),
    // so that the faces whose shares a vertex's columns gather sit together in memory: the
    // assembly was bound by cache misses on them (17% of the optimiser's samples on
    // mannequin-devil with 50 features, faces in the mesh's order).
    {
        std::vector<int> rank(nv, std::numeric_limits<int>::max());
        for (int r = 0; r < int(order.size()); ++r) rank[order[r]] = r;
        std::vector<std::pair<int, int>> key(na);
        for (int i = 0; i < na; ++i) {
            const Tri& t = mesh.faces[active[i]];
            key[i] = {std::min({rank[t[0]], rank[t[1]], rank[t[2]]}), active[i]};
        }
        std::sort(key.begin(), key.end());
        for (int i = 0; i < na; ++i) active[i] = key[i].second;
    }
    active_tris.reserve(na);
    active_frame.reserve(na);
    for (int f : active) active_tris.push_back(mesh.faces[f]), active_frame.push_back(frame[f]);
    const std::vector<Tri>& step_faces = active_tris;
    // The free border's barrier (box_barrier.h), with eps a tenth of the mean UV border edge and
    // each free border vertex's weight its share of the energy (4 x its third of the area of its
    // faces, over the whole area).
    std::vector<double> barrier_weight(nv, 0.0);
    double eps = 0;
    for (std::size_t i = 0; i < loop.size(); ++i) eps += (uv[loop[i]] - uv[loop[(i + 1) % loop.size()]]).norm();
    if (!loop.empty()) eps /= 10.0 * double(loop.size());
    if (o.border == BorderMode::free)
        for (int f = 0; f < nf; ++f)
            for (int v : mesh.faces[f])
                if (on_border[v] && dof[v].n == 2) barrier_weight[v] += 4 * frame[f].area / 3 / area_sum;
    std::vector<int> barrier_vertices;
    for (int v : loop)
        if (barrier_weight[v] > 0) barrier_vertices.push_back(v);
    const BoxBarrier barrier(std::move(barrier_vertices), std::move(barrier_weight), box_lo, box_hi, eps);
    stats.energy.push_back(energy_of(uv));
    double objective = stats.energy.back() + barrier.value(uv);
    if (unknowns == 0) {
        stats.stop = "no free vertex";
        stats.converged = true;
        return stats;
    }

    if (o.max_iterations <= 0) {
        stats.stop = "iterations";
        return stats;
    }
    // The system's pattern, once (newton_system.h).
    NewtonSystem system(step_faces, dof, unknowns);
    Eigen::SparseMatrix<double>& K = system.matrix();
    // A local optimisation (`movable`) has a small system: the simplicial factorisation.
    SparseCholesky solver(K, local_only);

    const BorderGuard guard(loop, box_lo, box_hi);

    // Per face: its share of the Newton system, from the closed-form eigensystem of the energy's
    // Hessian with respect to J, projected to be non-negative (face_newton.h, newton_system.h).
    std::vector<FaceHessian> local(na);  // per active face
    for (int i = 0; i < na; ++i)
        if (active_frame[i].area == 0) local[i] = face_hessian(active_frame[i], FaceNewton(), 0);  // none
    std::vector<Vec2> d(nv), trial(nv);
    Eigen::VectorXd rhs(unknowns), y(unknowns);

    stats.stop = "iterations";
    // The Hessian is refactorised when the last step with it gained less than half of what the
    // first step with it did, when a step was cut short (by the flip-free bound or the line
    // search: the stale step after one gained a twentieth of a new one on mannequin-devil with 50
    // features, and the nine-row total of iterations fell from 2,677 to 1,460), after a few steps,
    // or when its step fails; in between, the gradient is new and the factorisation is reused,
    // which is a descent direction still (the stale Hessian is positive definite) and costs a
    // solve instead of a factorisation. When a new Hessian's step fails too, the steepest descent
    // direction is tried before giving up.
    bool refresh = true, steepest = false;
    std::vector<int> pin_until(nv, -1);  // border vertices held at a contact: fixed until this iteration
    int stale = 0, stalled = 0, contact = 0;
    double fresh_gain = 0;
    for (int it = 0; it < o.max_iterations;) {
        const double e0 = objective;
        for_faces(na, o.parallel, [&](int i) {
            const FaceFrame& F = active_frame[i];
            if (F.area == 0) return;  // its share stays the zeros set below
            const Tri& t = active_tris[i];
            const FaceNewton L = face_newton(face_jacobian(F, uv[t[0]], uv[t[1]], uv[t[2]]));
            if (refresh) local[i] = face_hessian(F, L, 1 / area_sum);
            else face_gradient(F, L, 1 / area_sum, local[i].gradient);  // the blocks stay the factorised ones'
        });
        // The Newton system in the unknowns (newton_system.h).
        system.assemble(local, refresh, rhs, o.parallel);
        // The barrier's Newton terms: dx = sign * dist, so the gradient is w phi' sign and the
        // Hessian w phi'' on the vertex's own coordinate.
        barrier.for_terms(uv, [&](int v, int c, double sign, double d1, double d2) {
            const int r = dof[v].first + c;
            rhs[r] -= d1 * sign;
            if (refresh) K.valuePtr()[system.diagonal(r)] += d2;
        });
        // A whisper of regularisation keeps the system definite where zero-area faces leave a
        // vertex without energy and where the projected Hessian is only semi-definite.
        if (refresh) {
            double trace = 0;
            for (int c = 0; c < unknowns; ++c) trace += K.valuePtr()[system.diagonal(c)];
            const double whisper = 1e-10 * trace / unknowns;
            for (int c = 0; c < unknowns; ++c) K.valuePtr()[system.diagonal(c)] += whisper;
            // Border vertices held at a contact in the last iterations stay put in this step: a
            // stiff spring on their unknowns, so that the rest of the step is the Newton step with
            // them fixed (zeroing them in the free step afterwards need not leave a descent direction).
            for (int v : loop)
                if (dof[v].n > 0 && pin_until[v] > it)
                    for (int i = 0; i < dof[v].n; ++i) K.valuePtr()[system.diagonal(dof[v].first + i)] += 1e8 * trace / unknowns;
            ++stats.factorisations;
            if (!solver.factorize(K)) {
                stats.stop = "no descent step";
                break;
            }
        }
        if (steepest) {
            // The steepest descent direction, scaled to the minimum of the quadratic model along
            // it; held border vertices stay put (their stiff diagonal would make the scale tiny:
            // mushroom, 80 features, seed 23, stalled on steps that gained 1e-10).
            Eigen::VectorXd r = rhs;
            for (int v : loop)
                if (dof[v].n > 0 && pin_until[v] > it)
                    for (int i = 0; i < dof[v].n; ++i) r[dof[v].first + i] = 0;
            const Eigen::VectorXd Kr = K.selfadjointView<Eigen::Upper>() * r;
            const double curvature = r.dot(Kr);
            y = curvature > 0 ? Eigen::VectorXd(r.dot(r) / curvature * r) : r;
        } else {
            y = solver.solve(rhs);
        }
        // The Newton decrement: the decrease the quadratic model predicts for the whole step. It
        // decides convergence (on a new Hessian only): a step cut short by the flip-free bound or
        // the line search may gain little far from the minimum, the model's prediction does not.
        const double predicted = 0.5 * rhs.dot(y);
        const bool model_converged = refresh && !(predicted >= o.tolerance * e0);
        for (int v = 0; v < nv; ++v) {
            const Dof& dv = dof[v];
            if (dv.n == 0 || pin_until[v] > it) {
                d[v] = Vec2::Zero();
                continue;
            }
            Vec2 x = uv[v] + (dv.n == 2 ? Vec2(y[dv.first], y[dv.first + 1]) : Vec2(y[dv.first] * dv.dir));
            // The barrier keeps free border vertices off the rectangle's edges; a goal beyond them
            // is clamped into it all the same, so that the whole segment of the move stays
            // inside (the rectangle is convex and holds the vertex now).
            if (dv.n == 2) x = x.cwiseMax(box_lo).cwiseMin(box_hi);
            d[v] = x - uv[v];
        }
        // Line search: from 0.9 of the flip-free step (or the whole step), halving until the
        // energy drops and the exact predicates and the border guard accept the map.
        // Where the border guard refuses a step because two border edges would meet, the
        // vertices of those edges are held where they are for this iteration and the search
        // starts again (at most 8 times): a contact stops the border there, not the whole map.
        double step = std::min(1.0, 0.9 * max_flip_free_step(step_faces, uv, d, sigma, o.parallel));
        bool accepted = false;
        double e1 = e0, sd1 = 0;
        int holds = 0;
        for (int h = 0; h < 60 && step > 0; ++h, step *= 0.5) {
            if (h > 0) ++stats.halvings;
            for (int v = 0; v < nv; ++v) trial[v] = dof[v].n == 0 ? uv[v] : Vec2(uv[v] + step * d[v]);
            sd1 = energy_of(trial);
            e1 = sd1 + barrier.value(trial);
            if (!(e1 < e0)) continue;
            std::atomic<bool> exact_ok{true};
            for_faces(na, o.parallel, [&](int i) {
                if (!exact_ok.load(std::memory_order_relaxed)) return;
                const Tri& t = active_tris[i];
                if (orientation_2d(trial[t[0]], trial[t[1]], trial[t[2]]) != sigma) exact_ok = false;
            });
            if (!exact_ok) {
                ++stats.exact_rejections;
                continue;
            }
            if (o.check_border ? !guard.ok(trial) : !guard.inside(trial)) {
                ++stats.border_rejections;
                if (o.check_border && holds < 8 && guard.inside(trial)) {
                    const std::vector<int> touching = guard.crossing_vertices(trial);
                    bool held = false;
                    for (int v : touching)
                        if (d[v] != Vec2::Zero()) d[v] = Vec2::Zero(), held = true, pin_until[v] = it + 5;
                    if (held) {
                        ++holds;
                        ++stats.border_holds;
                        step = 2 * std::min(1.0, 0.9 * max_flip_free_step(step_faces, uv, d, sigma, o.parallel));
                        h = -1;  // the loop's step halving and ++h bring it back to the new start
                    }
                }
                continue;
            }
            accepted = true;
            break;
        }
        if (!accepted) {
            if (steepest) {  // the steepest descent step failed as well
                stats.stop = "no descent step";
                break;
            }
            if (!refresh) {  // the stale Hessian's step failed: try again with a new one
                refresh = true;
                continue;
            }
            if (!model_converged) {  // the new Hessian's step failed: the steepest descent direction
                steepest = true;
                refresh = false;
                ++stats.steepest_steps;
                continue;
            }
            stats.stop = model_converged ? "tolerance" : "no descent step";
            stats.converged = model_converged;
            break;
        }
        uv.swap(trial);
        objective = e1;
        stats.energy.push_back(sd1);
        stats.iterations = ++it;
        if (o.on_iteration) o.on_iteration(stats.iterations, uv, sd1);
        const double gain = e0 - e1;
        const bool small = gain < o.tolerance * e0;
        if (model_converged) {
            stats.stop = "tolerance";
            stats.converged = true;
            break;
        }
        // Fresh Newton steps that move nothing, ten in a row: no use going on.
        stalled = refresh && !(gain > 1e-12 * e0) ? stalled + 1 : refresh ? 0 : stalled;
        if (stalled >= 10) {
            stats.stop = "stalled";
            break;
        }
        // The border is in contact with itself and only creeps on: five steps in a row that
        // held border vertices and gained less than the tolerance. (Stopping at the first such
        // step left 3% of the energy on mannequin-devil with 40 features, seed 48: the steps
        // after a small one gained again.)
        contact = holds > 0 && small ? contact + 1 : 0;
        if (contact >= 5) {
            stats.stop = "border contact";
            break;
        }
        if (refresh) fresh_gain = gain, stale = 0;
        else ++stale;
        refresh = !o.reuse_hessian || small || gain < 0.5 * fresh_gain || stale >= 4 || step < 1 || steepest;
        // A new Hessian's step cut to under 1e-3 by the flip-free bound points into a face that
        // is about to collapse; the next Newton steps point there too (lion-head/chelsea: fresh
        // steps of 1e-10 until "stalled" at 49.96). The steepest descent step moves off it
        // (there: one step, then Newton again, 14.95 at convergence).
        const bool blocked = refresh && !steepest && step < 1e-3;
        steepest = blocked;
        if (blocked) refresh = false, ++stats.steepest_steps;
    }
    return stats;
}

}  // namespace ctmap
