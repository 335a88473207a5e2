#pragma once
/// \file newton_system.h
/// The distortion optimiser's projected Newton system (refine/isometric.h, beyond paper §2.4):
/// its sparsity pattern in the unknowns, once, then per iteration its values and right-hand side
/// from the faces' eigensystems (refine/face_newton.h), assembled in parallel by columns: each
/// column is summed by the vertex that owns it, over that vertex's faces in face order, so the
/// system has the same bits whatever the threads.
#include <Eigen/SparseCore>

#include <vector>

#include "ctmap/face_jacobian.h"
#include "ctmap/mesh.h"
#include "ctmap/refine/face_newton.h"

namespace ctmap {

/// How a vertex moves in a Newton step: dx = P dy with dy its `n` unknowns (n = 0: fixed; n = 1:
/// along `dir`, P = dir; n = 2: freely, P = I), numbered from `first`.
struct Dof {
    int first = -1, n = 0;
    Vec2 dir = Vec2::Zero();
    Vec2 column(int i) const { return n == 1 ? dir : Vec2(i == 0, i == 1); }
};

/// One face's share of the system in its corners' coordinates: the blocks H_ab (a >= b, listed
/// (0,0), (1,0), (1,1), (2,0), (2,1), (2,2)) of the projected Hessian and the gradient per corner.
struct FaceHessian {
    Mat2 block[6];
    Vec2 gradient[3];
    /// H_ab for any a, b.
    Mat2 at(int a, int b) const {
        return a >= b ? block[a * (a + 1) / 2 + b] : Mat2(block[b * (b + 1) / 2 + a].transpose());
    }
};

/// Face f's share, weighted by `weight` (the optimiser's 1 / total area): H_ab = weight A_f
/// sum_i lambda_i (E_i g_a)(E_i g_b)^T and gradient weight A_f dPsi/dJ g_a, with E_i, lambda_i and
/// dPsi/dJ from `L` and g_a the gradients of the barycentric coordinates in the face's frame. A face
/// of zero area has none.
FaceHessian face_hessian(const FaceFrame& F, const FaceNewton& L, double weight);

/// Only the gradient of face_hessian (for a step on an old Hessian), into `gradient`.
void face_gradient(const FaceFrame& F, const FaceNewton& L, double weight, Vec2 gradient[3]);

class NewtonSystem {
public:
    /// The pattern of the system over `faces` (the optimiser's active faces, in its order: best
    /// in the unknowns' order, for the assembly reads their shares in it) in the unknowns `dof`
    /// numbers (0 .. `unknowns` - 1).
    /// Keeps copies of what it needs (the unknowns per vertex, each corner's neighbours).
    /// \pre every vertex of `faces` has an entry in `dof`; the unknowns are numbered without gaps,
    /// a vertex's unknowns consecutive.
    NewtonSystem(const std::vector<Tri>& faces, const std::vector<Dof>& dof, int unknowns);

    /// The matrix: its upper triangle holds the system (compressed, column-major).
    Eigen::SparseMatrix<double>& matrix() { return K_; }
    const Eigen::SparseMatrix<double>& matrix() const { return K_; }
    /// Where the diagonal entry of unknown c sits in matrix().valuePtr().
    int diagonal(int c) const { return diag_[c]; }

    /// Sums the faces' shares `local` (per face of `faces`) into the matrix (when `hessian`; its
    /// values are overwritten) and minus their gradients into `rhs` (overwritten).
    void assemble(const std::vector<FaceHessian>& local, bool hessian, Eigen::VectorXd& rhs, bool parallel);

private:
    Eigen::SparseMatrix<double> K_;
    std::vector<int> diag_;
    std::vector<Dof> owner_dof_;       // per owner (a vertex with unknowns, in the unknowns' order)
    std::vector<int> corner_start_;    // per owner: its range in corner_
    std::vector<int> corner_;          // 3 f + k: the owner is corner k of face f, faces ascending
    std::vector<int> rank_;            // per (corner s, a): row dof[t[a]].first's rank in the owner's
                                       // columns, -1 when that block is not in the upper triangle
    std::vector<int> neighbour_;       // per (corner s, a): the owner index of t[a] where rank_ is set
};

}  // namespace ctmap
