#pragma once
/// \file face_jacobian.h
/// The Jacobian of a texture map on one triangle, from the triangle's own plane to UV, and the
/// per-face distortion quantities built on it. One implementation shared by the relaxation's
/// energy guard (refine/relax), the distortion optimiser (refine/isometric) and the certificate's
/// measures (certify/), so that the energy one minimises is the energy the other reports.
#include <cmath>
#include <limits>

#include "ctmap/mesh.h"

namespace ctmap {

using Mat2 = Eigen::Matrix2d;

/// A 3D triangle in its own plane: P0 = (0, 0), P1 = (l1, 0), P2 = (px, h), and the inverse of
/// its edge matrix [P1 P2]^-1 = [[i00, i01], [0, i11]]. `area` is 0 (and the inverse unset) for a
/// triangle of zero area, which then contributes nothing to any energy.
struct FaceFrame {
    double area = 0, i00 = 0, i01 = 0, i11 = 0;
};

/// The frame of the triangle (p0, p1, p2). With `mirror`, the triangle is reflected in its plane
/// (h < 0), so that a map whose UV triangles are all clockwise has Jacobians of positive
/// determinant.
inline FaceFrame face_frame(const Vec3& p0, const Vec3& p1, const Vec3& p2, bool mirror = false) {
    const Vec3 e1 = p1 - p0, e2 = p2 - p0;
    const double l1 = e1.norm(), n = e1.cross(e2).norm();
    if (!(l1 > 0) || !(n > 0) || !std::isfinite(n)) return {};
    const double px = e2.dot(e1) / l1, h = (mirror ? -n : n) / l1;
    return {0.5 * n, 1 / l1, -px / (l1 * h), 1 / h};
}

/// The Jacobian J (rows u, v; columns the frame's x, y) of the map sending the frame's triangle
/// to the UV triangle (u0, u1, u2): J = [u1 - u0, u2 - u0] [P1 P2]^-1.
inline Mat2 face_jacobian(const FaceFrame& F, const Vec2& u0, const Vec2& u1, const Vec2& u2) {
    const Vec2 q1 = u1 - u0, q2 = u2 - u0;
    Mat2 J;
    J << q1.x() * F.i00, q1.x() * F.i01 + q2.x() * F.i11, q1.y() * F.i00, q1.y() * F.i01 + q2.y() * F.i11;
    return J;
}

/// The gradients of the three corners' weights in the frame: row k of J is
/// sum_c uv_c[k] * g_c, with g1 = (i00, i01), g2 = (0, i11), g0 = -(g1 + g2).
inline void face_gradients(const FaceFrame& F, Vec2 g[3]) {
    g[1] = Vec2(F.i00, F.i01);
    g[2] = Vec2(0, F.i11);
    g[0] = -(g[1] + g[2]);
}

/// Singular values s1 >= s2 >= 0 of J in closed form.
inline void singular_values(const Mat2& J, double& s1, double& s2) {
    const double E = 0.5 * (J(0, 0) + J(1, 1)), F = 0.5 * (J(0, 0) - J(1, 1));
    const double G = 0.5 * (J(1, 0) + J(0, 1)), H = 0.5 * (J(1, 0) - J(0, 1));
    const double Q = std::hypot(E, H), R = std::hypot(F, G);
    s1 = Q + R;
    s2 = std::abs(Q - R);
}

/// The symmetric Dirichlet density |J|^2 + |J^-1|^2 = s1^2 + s2^2 + s1^-2 + s2^-2 (4 for an
/// isometry); +infinity when det J <= 0 (a degenerate or flipped triangle: the barrier).
inline double symmetric_dirichlet_density(const Mat2& J) {
    const double det = J.determinant();
    if (!(det > 0)) return std::numeric_limits<double>::infinity();
    const double fro = J.squaredNorm();
    return fro + fro / (det * det);
}

}  // namespace ctmap
