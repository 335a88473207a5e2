#pragma once
/// \file relax.h
/// The paper's refinement (§2.4, Fig. 4): every unconstrained vertex of the assembled UV map is
/// moved towards its mean value average, but only as far as the map stays valid (no triangle
/// flips or degenerates, the UV border stays simple). Border vertices use the paper's "virtual
/// images" to get a full circuit of neighbours. Features never move.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// The paper's "virtual image" weights of a border vertex (§2.4, Fig. 4). `fan` holds the
/// neighbours v1..vn of `center` in order around it, v1 and vn on the border. The interior
/// neighbours v2..v(n-1) are reflected through `center` (v'j = 2 center - vj) to close the
/// circuit v1, v2, ..., vn, v'2, ..., v'(n-1); the 3D mean value weights lambda of that circuit
/// give center = sum lambda_j vj + sum lambda'_j (2 center - vj), which is solved for center:
/// center = sum_j mu_j vj with mu_1 = lambda_1 / D, mu_n = lambda_n / D,
/// mu_j = (lambda_j - lambda'_j) / D, D = 1 - 2 sum lambda'. The mu sum to 1 (an affine
/// combination; interior mu may be negative). For a planar fan they reproduce its center.
/// \return mu, one per entry of `fan`; empty when the form does not exist or is ill-conditioned
///         (n < 3: no interior neighbour; D = 0; sum |mu| > 20, which happens at sharp corners
///         and strongly reflex vertices, where the vertex is then left in place).
/// \pre no point of `fan` equals `center`.
std::vector<double> border_mean_value_weights(const Vec3& center, const std::vector<Vec3>& fan);

/// Options of `relax`.
struct RelaxOptions {
    int max_iterations = 100;    ///< Gauss-Seidel sweeps at most
    /// Stop when a sweep's largest move is below this fraction of the UV bounding-box diagonal.
    double tolerance = 1e-4;
    int max_halvings = 12;       ///< a rejected move is retried at 1/2, 1/4, ... this many times
    bool move_border = true;     ///< also move the border vertices (virtual images)
    /// Keep the UV border simple (check a border vertex's two edges against the other border
    /// edges). Only tests switch it off, to show what it prevents.
    bool check_border = true;
    /// Keep the border vertices in the rectangle [box_lo, box_hi] (map_texture: the image,
    /// [0, 1]^2, widened to hold the starting map), and a thousandth of its size off its edges
    /// (the optimiser's barrier after the relaxation is steep there): a move that would go nearer
    /// is halved like one that would flip. Off by default (a bare UV map has no image).
    bool keep_in_box = false;
    Vec2 box_lo{0, 0}, box_hi{1, 1};
    /// Beyond the paper: take a move (or a shortened one) only if it does not raise the
    /// symmetric Dirichlet energy of the vertex's triangles (UVs scaled to the 3D area at the
    /// start of the sweep). Without it, free border vertices on strongly curved surfaces drift
    /// towards a more conformal but much more area-distorted map (mushroom, lion-head with three
    /// border features: symmetric Dirichlet x2); with it the relaxation is a descent method.
    bool energy_guard = true;
    /// With the energy guard: also stop when a sweep lowers the symmetric Dirichlet energy by
    /// less than this fraction (the "gain is small"; most of the gain comes in the first sweeps).
    double energy_tolerance = 1e-2;
    /// A move first tries this multiple of the way to the target (successive over-relaxation),
    /// then halves as usual; 1 is the paper's plain move. Over-relaxed Gauss-Seidel reaches a
    /// lower energy in fewer sweeps: lion-head and mannequin-devil with 50 features, 1.9 with
    /// tolerance 1e-2 stops after 16-22 sweeps at a lower energy than 1.0 with 3e-3 after 59-64
    /// (BENCHMARKS.md). The energy guard and the validity checks still decide every move; without
    /// the guard the plain move is used.
    double over_relaxation = 1.9;
    /// Move the vertices of one colour class (no two share a face) in parallel, and sum the
    /// energy in parallel (TBB); off, one thread does the same steps in the same order. The
    /// result is the same, bit for bit, with any number of threads or with this off.
    bool parallel = true;
};

/// What `relax` did.
struct RelaxStats {
    int iterations = 0;       ///< sweeps done
    long moves = 0;           ///< moves taken (whole or shortened)
    long moves_shortened = 0; ///< moves taken only part of the way (a longer one would flip or cross)
    long moves_rejected = 0;  ///< moves refused even at the shortest step
    long border_rejections = 0;  ///< trial steps refused because the UV border would not stay simple
    long energy_rejections = 0;  ///< trial steps refused by the energy guard
    int free_vertices = 0;    ///< vertices that may move (not fixed, with usable weights)
    double last_gain = 0;     ///< largest move of the last sweep, relative to the UV bbox diagonal
    double energy_before = 0; ///< symmetric Dirichlet energy (as `certify` reports it) before, with the guard
    double energy_after = 0;  ///< ... and after
    bool converged = false;   ///< stopped by the tolerance, not by max_iterations
};

/// Relaxes the per-vertex UV map `uv` of `mesh` (paper §2.4): Gauss-Seidel sweeps in which each
/// free vertex moves towards the weighted average of its neighbours' UVs (mean value weights
/// from the 3D angles for interior vertices, including those on cut paths; the virtual-image
/// form for border vertices). A move is taken whole if every incident UV triangle keeps the map's
/// orientation (exact predicate) and, for a border vertex, its two border edges cross or touch no
/// other border edge; otherwise it is halved until it is. Since orientation is linear in a
/// vertex's position, the whole segment of a move is then valid, and with a simple border and
/// all triangles positive the map stays one-to-one. Each sweep costs O(V + F). A sweep moves
/// the interior vertices colour by colour (no two of a colour share a face, so a colour moves in
/// parallel with exactly the sequential checks), then the border vertices one by one.
/// \param fixed vertices that never move (the features); their UVs are left bitwise untouched.
/// \pre uv.size() == mesh.num_vertices(); `mesh` is a manifold disc (or several); the map is
///      valid (every UV triangle of the same nonzero orientation).
/// \throw InternalError if the map is not valid on entry (a flipped or degenerate UV triangle)
///        or the mesh is not manifold.
RelaxStats relax(const TriMesh& mesh, std::vector<Vec2>& uv, const std::vector<int>& fixed,
                 const RelaxOptions& options = {});

}  // namespace ctmap
