#pragma once
/// \file scaffold.h
/// The free border's scaffold for the distortion optimiser (refine/isometric.h, beyond paper
/// §2.4; Jiang, Schaefer, Zorin and Panozzo 2017, "Simplicial complex augmentation framework for
/// bijective maps", SCAF): the region between the map's UV border and a rectangle around it,
/// triangulated (CGAL's constrained Delaunay triangulation of the border loop and the rectangle's
/// frame points, no points added). Every scaffold triangle must keep its orientation, as the
/// map's do (the line search's flip-free bound and exact predicates include them), so two parts of
/// the border cannot cross; the optimiser remakes it when it limits a step. Each scaffold
/// triangle whose area falls below a reference
/// area (a border edge times a tenth of it: two border parts closer than that) adds the box
/// barrier's term (box_barrier.h) of its area, zero above it and infinite at zero area: a
/// barrier that depends on the map as it is, not on the scaffold's history, so the optimiser finds
/// /// an equilibrium at a contact instead of creeping into it, and that does not resist the border
/// sliding along itself (a shear keeps the areas).
#include <array>
#include <vector>

#include "ctmap/mesh.h"
#include "ctmap/refine/newton_system.h"

namespace ctmap {

class Scaffold {
public:
    /// The scaffold of the map `uv` whose border is `loop` (a simple UV polygon), inside the
    /// rectangle [lo, hi] widened by `margin` times its size on every side (the frame: its corners
    /// and 4 points per side, fixed); each triangle's barrier starts below the area `area_ref`
    /// and has the weight `weight`.
    /// \pre the loop is simple in `uv` and inside [lo, hi]; margin > 0, area_ref > 0, weight > 0.
    /// \throw InternalError if CGAL's triangulation adds or merges a point (the loop not simple).
    Scaffold(const std::vector<int>& loop, const std::vector<Vec2>& uv, Vec2 lo, Vec2 hi, double margin,
             double area_ref, double weight);

    int num_faces() const { return int(faces_.size()); }
    /// The scaffold triangles' total signed area in the map it was made for.
    double area() const { return area_; }

    /// The scaffold's energy in the map x (+infinity when a triangle is degenerate or flipped).
    double energy(const std::vector<Vec2>& x) const;
    /// The smallest positive t at which a scaffold triangle has zero area in x + t d (+infinity
    /// if none), as max_flip_free_step does for the map's.
    double max_step(const std::vector<Vec2>& x, const std::vector<Vec2>& d) const;
    /// Whether every scaffold triangle of x is counter-clockwise, by the exact predicate.
    bool exact_ok(const std::vector<Vec2>& x) const;
    /// Adds the barrier's gradient (minus, into `rhs`) and the diagonal blocks of its Gauss-Newton
    /// Hessian w phi'' grad A grad A^T (into `K`, the upper triangle of the optimiser's system; when
    /// `hessian`) for the unknowns `dof`.
    void add_newton_terms(const std::vector<Vec2>& x, const std::vector<Dof>& dof, bool hessian,
                          Eigen::SparseMatrix<double>& K, Eigen::VectorXd& rhs) const;

private:
    Vec2 at(int k, const std::vector<Vec2>& x) const { return k < nv_ ? x[k] : frame_[k - nv_]; }
    int nv_ = 0;
    std::vector<Vec2> frame_;               // the frame's fixed points (index nv_ + i)
    std::vector<std::array<int, 3>> faces_;  // counter-clockwise
    double area_ref_ = 0, weight_ = 0, area_ = 0;
};

}  // namespace ctmap
