#include "ctmap/refine/isometric.h"

#include <Eigen/SparseCore>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

#include "ctmap/errors.h"
#include "ctmap/face_jacobian.h"
#include "ctmap/refine/border_guard.h"
#include "ctmap/refine/face_newton.h"
#include "ctmap/refine/isometric_problem.h"
#include "ctmap/refine/line_search.h"
#include "ctmap/refine/newton_system.h"
#include "ctmap/refine/progressive_reference.h"
#include "ctmap/refine/sparse_cholesky.h"

namespace ctmap {
namespace {

template <class F>
void for_each_index(int n, bool parallel, F&& f) {
    if (parallel) tbb::parallel_for(0, n, [&](int i) { f(i); });
    else for (int i = 0; i < n; ++i) f(i);
}

/// Sets each face's reference (progressive_reference.h) for the map uv; the count of faces whose
/// reference is not their 3D triangle.
int set_references(const IsometricProblem& p, const std::vector<Vec2>& uv, double bound, std::vector<FaceFrame>& frames) {
    std::atomic<int> over{0};
    for_each_index(int(p.tris.size()), p.parallel, [&](int i) {
        const Tri& t = p.tris[i];
        const FaceFrame& F = p.frame[i];
        frames[i] = progressive_frame(F, face_jacobian(F, uv[t[0]], uv[t[1]], uv[t[2]]), bound);
        if (frames[i].i00 != F.i00 || frames[i].i01 != F.i01 || frames[i].i11 != F.i11) ++over;
    });
    return over;
}

}  // namespace

IsometricStats optimise_isometric(const TriMesh& mesh, std::vector<Vec2>& uv, const std::vector<int>& fixed,
                                  const IsometricOptions& o) {
    const IsometricProblem p = make_isometric_problem(mesh, uv, fixed, o);
    IsometricStats stats;
    stats.scale = p.scale;
    stats.free_vertices = p.free_vertices;
    stats.sliding_vertices = p.sliding_vertices;
    if (!p.nothing.empty()) {
        stats.stop = p.nothing;
        return stats;
    }
    const int nv = p.nv, na = int(p.tris.size());
    const std::vector<Dof>& dof = p.dof;
    // The energy's frames: the 3D triangles', or for a while the progressive references.
    std::vector<FaceFrame> frames = p.frame;
    stats.energy.push_back(p.energy(p.frame, uv));
    if (p.unknowns == 0) {
        stats.stop = "no free vertex";
        stats.converged = true;
        return stats;
    }
    if (o.max_iterations <= 0) {
        stats.stop = "iterations";
        return stats;
    }
    // The system's pattern, once (newton_system.h); a local optimisation (`movable`) has a small
    // system: the simplicial factorisation.
    NewtonSystem system(p.tris, dof, p.unknowns);
    Eigen::SparseMatrix<double>& K = system.matrix();
    SparseCholesky solver(K, p.local);
    const BorderGuard guard(p.loop, p.box_lo, p.box_hi);
    auto objective_of = [&](double energy) { return energy + p.barrier->value(uv); };
    double objective = objective_of(stats.energy.back());

    // Per face: its share of the Newton system, from the closed-form eigensystem of the energy's
    // Hessian with respect to J, projected to be non-negative (face_newton.h, newton_system.h).
    std::vector<FaceHessian> local(na);
    for (int i = 0; i < na; ++i)
        if (p.frame[i].area == 0) local[i] = face_hessian(p.frame[i], FaceNewton(), 0);  // none
    std::vector<Vec2> d(nv), trial(nv);
    Eigen::VectorXd rhs(p.unknowns), y(p.unknowns);
    bool progressive = o.progressive > 0 && !p.local;

    stats.stop = "iterations";
    // The Hessian is refactorised when the last step with it gained less than half of what the
    // first step with it did, when a step was cut short (by the flip-free bound or the line
    // search), after a few steps, or when its step fails; in between, the gradient is new and the
    // factorisation is reused, which is a descent direction still (the stale Hessian is positive
    // definite) and costs a solve instead of a factorisation. When a new Hessian's step fails
    // too, the steepest descent direction is tried before giving up.
    bool refresh = true, steepest = false;
    std::vector<int> pin_until(nv, -1);  // border vertices held at a contact: fixed until this iteration
    int stale = 0, stalled = 0, contact = 0;
    double fresh_gain = 0;
    for (int it = 0; it < o.max_iterations;) {
        if (progressive) {
            // New references for the map as it is, and the objective against them.
            if (set_references(p, uv, o.progressive, frames) == 0) progressive = false;
            objective = objective_of(p.energy(frames, uv));
            refresh = true;
        }
        const double e0 = objective;
        for_each_index(na, o.parallel, [&](int i) {
            const FaceFrame& F = frames[i];
            if (F.area == 0) return;  // its share stays the zeros set above
            const Tri& t = p.tris[i];
            const FaceNewton L = face_newton(face_jacobian(F, uv[t[0]], uv[t[1]], uv[t[2]]));
            if (refresh) local[i] = face_hessian(F, L, 1 / p.area_sum);
            else face_gradient(F, L, 1 / p.area_sum, local[i].gradient);  // the blocks stay the factorised ones'
        });
        system.assemble(local, refresh, rhs, o.parallel);
        // The barrier's Newton terms: dx = sign * dist, so the gradient is w phi' sign and the
        // Hessian w phi'' on the vertex's own coordinate.
        p.barrier->for_terms(uv, [&](int v, int c, double sign, double d1, double d2) {
            const int r = dof[v].first + c;
            rhs[r] -= d1 * sign;
            if (refresh) K.valuePtr()[system.diagonal(r)] += d2;
        });
        if (refresh) {
            // A whisper of regularisation keeps the system definite where zero-area faces leave a
            // vertex without energy and where the projected Hessian is only semi-definite.
            double trace = 0;
            for (int c = 0; c < p.unknowns; ++c) trace += K.valuePtr()[system.diagonal(c)];
            const double whisper = 1e-10 * trace / p.unknowns;
            for (int c = 0; c < p.unknowns; ++c) K.valuePtr()[system.diagonal(c)] += whisper;
            // Border vertices held at a contact in the last iterations stay put in this step: a
            // stiff spring on their unknowns, so that the rest of the step is the Newton step with
            // them fixed (zeroing them in the free step afterwards need not leave a descent direction).
            for (int v : p.loop)
                if (dof[v].n > 0 && pin_until[v] > it)
                    for (int i = 0; i < dof[v].n; ++i)
                        K.valuePtr()[system.diagonal(dof[v].first + i)] += 1e8 * trace / p.unknowns;
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
            for (int v : p.loop)
                if (dof[v].n > 0 && pin_until[v] > it)
                    for (int i = 0; i < dof[v].n; ++i) r[dof[v].first + i] = 0;
            const Eigen::VectorXd Kr = K.selfadjointView<Eigen::Upper>() * r;
            const double curvature = r.dot(Kr);
            y = curvature > 0 ? Eigen::VectorXd(r.dot(r) / curvature * r) : r;
        } else {
            y = solver.solve(rhs);
        }
        // The Newton decrement: the decrease the quadratic model predicts for the whole step. It
        // decides convergence (on a new Hessian, against the 3D triangles): a step cut short by
        // the flip-free bound or the line search may gain little far from the minimum, the
        // model's prediction does not.
        const double predicted = 0.5 * rhs.dot(y);
        const bool model_converged = refresh && !progressive && !(predicted >= o.tolerance * e0);
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
            if (dv.n == 2) x = x.cwiseMax(p.box_lo).cwiseMin(p.box_hi);
            d[v] = x - uv[v];
        }
        LineSearchResult ls = flip_free_line_search(p, frames, guard, o.check_border, uv, d, e0, trial);
        stats.halvings += ls.halvings;
        stats.exact_rejections += ls.exact_rejections;
        stats.border_rejections += ls.border_rejections;
        stats.border_holds += ls.holds;
        for (int v : ls.held) pin_until[v] = it + 5;
        if (!ls.accepted) {
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
            stats.stop = "tolerance";
            stats.converged = true;
            break;
        }
        uv.swap(trial);
        double energy = ls.energy;
        bool left_progressive = false;
        if (o.progressive > 0 && !p.local) {
            // The energy against the 3D triangles; the references are left once a step gains less
            // than 1% of it.
            const double before = stats.energy.back();
            energy = p.energy(p.frame, uv);
            if (progressive && !(energy < 0.99 * before)) {
                progressive = false;
                frames = p.frame;
                left_progressive = true;
            }
        }
        stats.energy.push_back(energy);
        stats.iterations = ++it;
        objective = left_progressive ? objective_of(energy) : ls.objective;
        if (o.on_iteration) o.on_iteration(stats.iterations, uv, energy);
        const double gain = e0 - ls.objective;
        const bool small = gain < o.tolerance * e0;
        if (model_converged) {
            stats.stop = "tolerance";
            stats.converged = true;
            break;
        }
        // Fresh Newton steps that move nothing, ten in a row: no use going on (a defect: the
        // map's report and `ctmap map` say so).
        stalled = refresh && !(gain > 1e-12 * e0) ? stalled + 1 : refresh ? 0 : stalled;
        if (stalled >= 10) {
            stats.stop = "stalled";
            break;
        }
        // The border is in contact with itself and only creeps on: five steps in a row that
        // held border vertices and gained less than the tolerance. (Stopping at the first such
        // step left 3% of the energy on mannequin-devil with 40 features, seed 48: the steps
        // after a small one gained again.)
        contact = ls.holds > 0 && small ? contact + 1 : 0;
        if (contact >= 5) {
            stats.stop = "border contact";
            break;
        }
        if (refresh) fresh_gain = gain, stale = 0;
        else ++stale;
        refresh = !o.reuse_hessian || small || gain < 0.5 * fresh_gain || stale >= 4 || ls.step < 1 || steepest ||
                  left_progressive;
        // A new Hessian's step cut to under 1e-3 by the flip-free bound points into a face that
        // is about to collapse; the next Newton steps point there too (lion-head/chelsea: fresh
        // steps of 1e-10 until "stalled" at 49.96). The steepest descent step moves off it
        // (there: one step, then Newton again, 14.95 at convergence).
        const bool blocked = refresh && !steepest && ls.step < 1e-3;
        steepest = blocked;
        if (blocked) refresh = false, ++stats.steepest_steps;
    }
    return stats;
}

}  // namespace ctmap
