#pragma once
/// \file isometric.h
/// The distortion optimiser (beyond paper §2.4): starting from a valid map (the paper's
/// relaxation), it minimises the symmetric Dirichlet energy with every feature fixed at its exact
/// UV, and every iterate is a valid map. Each iteration is a projected Newton step: per face, the
/// energy's Hessian with respect to the Jacobian from its closed-form eigensystem (Smith, de Goes
/// and Kim 2019) with its negative eigenvalue clamped; one sparse symmetric positive definite
/// system (CHOLMOD, supernodal Cholesky; the symbolic analysis is done once, a factorisation is
/// reused while its steps gain); and a line search towards the solution, never past
/// the largest flip-free step (flip_free_step.h), taking a step only if it lowers the energy, the
/// exact orientation predicates agree on every triangle and the border guard accepts it
/// (line_search.h). A very distorted start can be measured against progressive references first
/// (progressive_reference.h). The set-up is isometric_problem.h.
#include <functional>
#include <string>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// What the border vertices (those that are not features) may do.
enum class BorderMode {
    free,   ///< move anywhere, the UV border staying simple and inside the image rectangle
    fixed,  ///< slide along the straight side between their two border features
};

/// Options of `optimise_isometric`.
struct IsometricOptions {
    int max_iterations = 1000;  ///< iteration cap (`--iterations`)
    /// Stop when the Newton step (with a new Hessian) is predicted to lower the energy by less
    /// than this fraction of it (the Newton decrement).
    double tolerance = 1e-6;
    BorderMode border = BorderMode::free;
    /// The rectangle the free border stays in: the image, [0, 1]^2 in UV (widened to hold the
    /// starting map if that reaches outside).
    Vec2 box_lo{0, 0}, box_hi{1, 1};
    /// Check that the UV border stays simple (border_guard.h). Only tests switch it off, to show
    /// what it prevents.
    bool check_border = true;
    /// Keep the free border in that rectangle; off (`--border-mode unbounded`), only simple.
    bool keep_in_box = true;
    /// Reuse the Hessian's factorisation for the next steps while they are whole steps that gain
    /// at least half of what the first step with it gained (at most 4 reuses): such iterations
    /// cost a solve instead of a factorisation. Off: a new Hessian every iteration (plain
    /// projected Newton).
    bool reuse_hessian = true;
    /// The progressive reference (Liu et al. 2018): while > 0, each face's energy is measured
    /// against a reference between its 3D triangle and its UV one whose distortion to the map is at
    /// most this (symmetric Dirichlet / 4 per face); 0: always against the 3D triangle.
    double progressive = 0;
    bool parallel = true;  ///< per-face work with TBB (the result is the same bit for bit either way)
    /// The factor the mesh is scaled by in the energy (the energy is not scale invariant). 0: the
    /// one that makes the mesh's area the map's UV area on entry. A run continued from another's
    /// map passes that run's `IsometricStats::scale`, so that both minimise the same energy.
    double scale = 0;
    /// If not empty: only these vertices may move (the others are held like `fixed`), and the
    /// per-face work of each iteration runs over the faces that touch them; the energy is still the
    /// whole map's. An optimisation local to a region, e.g. around a feature just moved
    /// (edit/incremental_remap). Indices out of range are a BadInput.
    std::vector<int> movable;
    /// Called after every accepted iteration with the map and its symmetric Dirichlet energy
    /// (tests certify each iterate). The line search decreases that energy plus the free
    /// border's barrier (zero away from the image's edges).
    std::function<void(int iteration, const std::vector<Vec2>& uv, double energy)> on_iteration;
};

/// What `optimise_isometric` did.
struct IsometricStats {
    int iterations = 0;           ///< accepted iterations
    std::vector<double> energy;   ///< energy[0] on entry, energy[i] after iteration i
    bool converged = false;       ///< stopped by the tolerance (or at a point no step can improve)
    /// "tolerance" (converged), "iterations" (the cap), "no free vertex"; and short of
    /// convergence (`ctmap map` warns): "no descent step" (neither the Newton step nor the
    /// steepest descent step lowers the energy), "border contact" (the free border touches itself
    /// and five steps in a row that it held gained less than the tolerance), "stalled" (ten steps
    /// in a row with a new Hessian gained less than 1e-12 of the energy each)
    std::string stop;
    int factorisations = 0;       ///< numeric Cholesky factorisations (the dominant cost)
    /// times border vertices at a contact were held (they then stay fixed for five iterations,
    /// the Newton system solved with them fixed)
    long border_holds = 0;
    long halvings = 0;            ///< line-search step halvings in all
    long exact_rejections = 0;    ///< trial steps the floating-point test passed and the exact predicates refused
    long border_rejections = 0;   ///< trial steps the border guard refused
    /// steepest descent steps: tried when a new Hessian's step failed or was cut below 1e-3 by
    /// the flip-free bound (it then points into a face about to collapse)
    int steepest_steps = 0;
    int free_vertices = 0;        ///< vertices that move in the plane
    int sliding_vertices = 0;     ///< border vertices that slide along a side (fixed border)
    double scale = 0;             ///< the factor the mesh was scaled by in the energy (IsometricOptions::scale)
    double energy_before() const { return energy.empty() ? 0 : energy.front(); }
    double energy_after() const { return energy.empty() ? 0 : energy.back(); }
};

/// Minimises the symmetric Dirichlet energy of the per-vertex map `uv` of `mesh` with the
/// vertices `fixed` held bitwise where they are. The energy is the area-weighted mean of
/// |J|^2 + |J^-1|^2 over the faces (4 for an isometry), the mesh scaled so that its area is the
/// map's UV area on entry (the certificate's normalisation, held fixed while the map moves), or by
/// `options.scale` if that is positive.
/// \pre uv.size() == mesh.num_vertices(); `mesh` is a manifold disc with its border loop; the map
///      is valid (every triangle of one nonzero orientation, exactly; the border simple).
/// \throw BadInput if the sizes do not match, a fixed vertex is out of range, the scale is negative
///        or not finite, or the map is not valid on entry.
IsometricStats optimise_isometric(const TriMesh& mesh, std::vector<Vec2>& uv, const std::vector<int>& fixed,
                                  const IsometricOptions& options = {});

}  // namespace ctmap
