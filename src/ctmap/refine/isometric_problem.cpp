#include "ctmap/refine/isometric_problem.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ctmap/border_loop.h"
#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/refine/sparse_cholesky.h"

namespace ctmap {

namespace {

/// A face's term of the energy (before the division by the total area).
double face_term(const FaceFrame& F, const Tri& t, const std::vector<Vec2>& x) {
    if (F.area == 0) return 0.0;
    return F.area * symmetric_dirichlet_density(face_jacobian(F, x[t[0]], x[t[1]], x[t[2]]));
}

}  // namespace

double IsometricProblem::energy(const std::vector<FaceFrame>& frames, const std::vector<Vec2>& x) const {
    return (held_energy + chunked_sum(int(tris.size()), parallel, [&](int i) { return face_term(frames[i], tris[i], x); })) /
           area_sum;
}

IsometricProblem make_isometric_problem(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                        const std::vector<int>& fixed, const IsometricOptions& o) {
    IsometricProblem p;
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    p.nv = nv;
    p.parallel = o.parallel;
    if (int(uv.size()) != nv)
        throw BadInput("", "optimise_isometric: " + std::to_string(uv.size()) + " UVs for " + std::to_string(nv) +
                               " vertices");
    if (!(o.scale >= 0) || !std::isfinite(o.scale))
        throw BadInput("", "optimise_isometric: the scale must be a finite number >= 0");
    if (!(o.progressive == 0 || o.progressive > 1) || !std::isfinite(o.progressive))
        throw BadInput("", "optimise_isometric: the progressive bound must be 0 (off) or a finite number > 1");
    if (nf == 0) {
        p.nothing = "no free vertex";
        return p;
    }
    std::vector<char> is_fixed(nv, 0);
    for (int v : fixed) {
        if (v < 0 || v >= nv)
            throw BadInput("", "optimise_isometric: fixed vertex " + std::to_string(v) + " is out of range");
        is_fixed[v] = 1;
    }
    p.local = !o.movable.empty();
    if (p.local) {
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
    for (int f = 0; f < nf; ++f) {
        const Tri& t = mesh.faces[f];
        if (!p.local || !is_fixed[t[0]] || !is_fixed[t[1]] || !is_fixed[t[2]]) active.push_back(f);
    }
    const int na = int(active.size());
    // The map's orientation, and the precondition that it is valid.
    for (int f = 0; f < nf; ++f) {
        const Tri& t = mesh.faces[f];
        const int s = orientation_2d(uv[t[0]], uv[t[1]], uv[t[2]]);
        if (p.sigma == 0) p.sigma = s;
        if (s == 0 || s != p.sigma)
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
        p.nothing = "no free vertex";
        return p;
    }
    // (Measured and rejected: the scale at which the entry map's energy is least, or the area
    // median of the faces' scales. They halve the iterations on some sets, but a relaxed map that
    // squeezes most faces gets a tiny scale there and converges to a far more distorted map.)
    const double k = o.scale > 0 ? o.scale : std::sqrt(area2 / area3);
    p.scale = k;
    std::vector<FaceFrame> frame(nf);
    for (int f = 0; f < nf; ++f) {
        const Tri& t = mesh.faces[f];
        frame[f] = face_frame(k * mesh.positions[t[0]], k * mesh.positions[t[1]], k * mesh.positions[t[2]], p.sigma < 0);
        p.area_sum += frame[f].area;
    }
    // The held faces' share, once (0 when every face is active: the same bits as a plain sum).
    if (p.local) {
        std::vector<char> is_active(nf, 0);
        for (int f : active) is_active[f] = 1;
        p.held_energy = chunked_sum(nf, o.parallel, [&](int f) {
            return is_active[f] ? 0.0 : face_term(frame[f], mesh.faces[f], uv);
        });
    }

    // Unknowns per vertex.
    p.loop = border_loop(mesh);
    const std::vector<int>& loop = p.loop;
    std::vector<char> used(nv, 0), on_border(nv, 0);
    for (const Tri& t : mesh.faces)
        for (int v : t) used[v] = 1;
    for (int v : loop) on_border[v] = 1;
    // The image rectangle (widened to hold the starting map).
    const double inf = std::numeric_limits<double>::infinity();
    p.box_lo = o.keep_in_box ? o.box_lo : Vec2(-inf, -inf);
    p.box_hi = o.keep_in_box ? o.box_hi : Vec2(inf, inf);
    for (int v : loop) p.box_lo = p.box_lo.cwiseMin(uv[v]), p.box_hi = p.box_hi.cwiseMax(uv[v]);
    auto on_wall = [&](const Vec2& q) {
        return q.x() <= p.box_lo.x() || q.x() >= p.box_hi.x() || q.y() <= p.box_lo.y() || q.y() >= p.box_hi.y();
    };
    std::vector<Dof>& dof = p.dof;
    dof.assign(nv, Dof());
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
    if (p.local) {
        for (int v = 0; v < nv; ++v)
            if (dof[v].n > 0) order.push_back(v);
    } else {
        std::vector<char> has_unknowns(nv, 0);
        for (int v = 0; v < nv; ++v) has_unknowns[v] = dof[v].n > 0;
        order = fill_reducing_order(mesh.faces, has_unknowns);
    }
    for (int v : order) {
        dof[v].first = p.unknowns;
        p.unknowns += dof[v].n;
        if (dof[v].n == 2) ++p.free_vertices;
        else ++p.sliding_vertices;
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
    p.tris.reserve(na);
    p.frame.reserve(na);
    for (int f : active) p.tris.push_back(mesh.faces[f]), p.frame.push_back(frame[f]);
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
                if (on_border[v] && dof[v].n == 2) barrier_weight[v] += 4 * frame[f].area / 3 / p.area_sum;
    std::vector<int> barrier_vertices;
    for (int v : loop)
        if (barrier_weight[v] > 0) barrier_vertices.push_back(v);
    p.barrier = std::make_unique<BoxBarrier>(std::move(barrier_vertices), std::move(barrier_weight), p.box_lo, p.box_hi, eps);
    return p;
}

}  // namespace ctmap
