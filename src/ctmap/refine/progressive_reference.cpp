#include "ctmap/refine/progressive_reference.h"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace ctmap {
namespace {

/// The symmetric Dirichlet density / 4 of singular values s1^t, s2^t.
double density_at(double l1, double l2, double t) {
    const double a = std::exp(2 * t * l1), b = std::exp(2 * t * l2);
    return 0.25 * (a + b + 1 / a + 1 / b);
}

}  // namespace

FaceFrame progressive_frame(const FaceFrame& F, const Mat2& J, double bound) {
    if (!(F.area > 0) || !(symmetric_dirichlet_density(J) > 4 * bound)) return F;
    // J^T J = V diag(s1^2, s2^2) V^T.
    Eigen::SelfAdjointEigenSolver<Mat2> eig;
    eig.computeDirect(J.transpose() * J);
    const Vec2 s2 = eig.eigenvalues().cwiseMax(1e-300);
    const double l1 = 0.5 * std::log(s2[0]), l2 = 0.5 * std::log(s2[1]);  // log s
    // The density / 4 of s^t grows with t from 1 at t = 0 to > bound at t = 1: bisect for t.
    double lo = 0, hi = 1;
    for (int i = 0; i < 50; ++i) {
        const double mid = 0.5 * (lo + hi);
        (density_at(l1, l2, mid) > bound ? hi : lo) = mid;
    }
    const double w = 1 - lo;
    const Mat2& V = eig.eigenvectors();
    const Mat2 R = V * Vec2(std::exp(w * l1), std::exp(w * l2)).asDiagonal() * V.transpose();
    // The 3D triangle's edge matrix P = [[i00, i01], [0, i11]]^-1, stretched: P' = R P, then
    // written as Q T with Q a rotation and T upper triangular (the frame's own form).
    Mat2 P;
    P << 1 / F.i00, -F.i01 / (F.i00 * F.i11), 0, 1 / F.i11;
    const Mat2 Pr = R * P;
    const double n0 = Pr.col(0).norm();
    const double c = Pr(0, 0) / n0, s = Pr(1, 0) / n0;
    const double t00 = n0, t01 = c * Pr(0, 1) + s * Pr(1, 1), t11 = -s * Pr(0, 1) + c * Pr(1, 1);
    FaceFrame out;
    out.area = F.area;
    out.i00 = 1 / t00;
    out.i11 = 1 / t11;
    out.i01 = -t01 / (t00 * t11);
    return out;
}

}  // namespace ctmap
