#pragma once
/// \file face_newton.h
/// One face's share of the distortion optimiser's projected Newton step (refine/isometric.h,
/// beyond paper §2.4): the symmetric Dirichlet density's gradient and its Hessian with respect to
/// the Jacobian, from the closed-form eigensystem, projected to be positive semi-definite.
#include "ctmap/face_jacobian.h"

namespace ctmap {

/// One face's share of the Newton step: with J = U diag(s1, s2) V^T (U, V rotations; det J > 0),
/// the energy density Psi = s1^2 + s2^2 + s1^-2 + s2^-2 has dPsi/dJ = U diag(Psi_1, Psi_2) V^T
/// and a Hessian with respect to J whose eigenvectors are known in closed form (Smith, de Goes and
/// Kim 2019, "Analytic eigensystems for isotropic distortion energies", 2D case): the scalings
/// U diag(1, 0) V^T and U diag(0, 1) V^T with eigenvalues Psi_11 = 2 + 6 s1^-4 and
/// Psi_22 = 2 + 6 s2^-4, the flip U [[0, 1], [1, 0]] V^T / sqrt 2 with
/// 2 + 2 (s1^2 + s1 s2 + s2^2) / (s1 s2)^3 (always positive) and the twist
/// U [[0, -1], [1, 0]] V^T / sqrt 2 with 2 - 2 (s1^-3 + s2^-3) / (s1 + s2), the only one that can
/// be negative; it is clamped to 0, which makes the Hessian positive semi-definite. (Its absolute
/// value instead, Chen et al. 2024, was measured: more iterations on lion-head with 50 features.)
struct FaceNewton {
    Mat2 mode[4] = {Mat2::Zero(), Mat2::Zero(), Mat2::Zero(), Mat2::Zero()};  ///< scalings, flip, twist
    double lambda[4] = {0, 0, 0, 0};  ///< their eigenvalues, the twist's clamped at 0
    Mat2 dpsi = Mat2::Zero();         ///< dPsi/dJ
};

/// The eigensystem above for the Jacobian J of one face.
/// \pre det J > 0 (a sliver whose determinant rounds to zero or below is treated as s2 = 1e-12).
FaceNewton face_newton(const Mat2& J);

}  // namespace ctmap
