#include "ctmap/refine/face_newton.h"

#include <algorithm>
#include <cmath>

namespace ctmap {
namespace {

/// cos and sin of atan2(y, x) / 2 without trigonometric calls (half-angle formulas, each from the
/// side that does not cancel); (1, 0) for the zero vector, as atan2(0, 0) = 0.
void half_angle(double x, double y, double& c, double& s) {
    const double n = std::sqrt(x * x + y * y);
    if (!(n > 0)) {
        c = 1, s = 0;
        return;
    }
    const double cn = x / n, sn = y / n;
    if (cn >= 0) {
        c = std::sqrt(0.5 * (1 + cn));
        s = sn / (2 * c);
    } else {
        s = std::copysign(std::sqrt(0.5 * (1 - cn)), sn);
        c = sn / (2 * s);
    }
}

}  // namespace

FaceNewton face_newton(const Mat2& J) {
    // The signed SVD J = U diag(s1, s2) V^T with U, V rotations, in closed form: with
    // E, F, G, H the halved sums and differences of J's entries, s1 = |(E, H)| + |(F, G)|
    // and U, V rotate by phi = (a2 + a1) / 2 and -theta = -(a2 - a1) / 2 (a1 = atan2(G, F),
    // a2 = atan2(H, E); taken by half angles, which matched atan2, cos and sin to 1.2e-15 on 10^6
    // random and sliver Jacobians);
    // s2 = det J / s1 rather than the difference of the hypotenuses, which cancels for a sliver.
    // (Eigen's JacobiSVD gave the same to rounding at twice the cost.)
    const double E = 0.5 * (J(0, 0) + J(1, 1)), F = 0.5 * (J(0, 0) - J(1, 1));
    const double G = 0.5 * (J(1, 0) + J(0, 1)), H = 0.5 * (J(1, 0) - J(0, 1));
    double s1 = std::sqrt(E * E + H * H) + std::sqrt(F * F + G * G);
    double s2 = s1 > 0 ? J.determinant() / s1 : 0;
    double c1, h1, c2, h2;  // cos and sin of a1 / 2 and a2 / 2
    half_angle(F, G, c1, h1);
    half_angle(E, H, c2, h2);
    const double cp = c2 * c1 - h2 * h1, sp = h2 * c1 + c2 * h1;  // phi = (a2 + a1) / 2
    const double ct = c2 * c1 + h2 * h1, st = h2 * c1 - c2 * h1;  // theta = (a2 - a1) / 2
    Mat2 U, V;
    U << cp, -sp, sp, cp;
    V << ct, st, -st, ct;
    // det J > 0 (the line search keeps it so) gives s2 > 0; a sliver whose determinant rounds to
    // zero or below gets the smallest positive value, so that its terms push it open.
    s1 = std::max(s1, 1e-12);
    s2 = std::max(s2, 1e-12);
    FaceNewton n;
    const double r = 1 / std::sqrt(2.0);
    Mat2 m[4];
    m[0] << 1, 0, 0, 0;
    m[1] << 0, 0, 0, 1;
    m[2] << 0, r, r, 0;
    m[3] << 0, -r, r, 0;
    for (int i = 0; i < 4; ++i) n.mode[i] = U * m[i] * V.transpose();
    n.lambda[0] = 2 + 6 / (s1 * s1 * s1 * s1);
    n.lambda[1] = 2 + 6 / (s2 * s2 * s2 * s2);
    const double p = s1 * s2;
    n.lambda[2] = 2 + 2 * (s1 * s1 + s1 * s2 + s2 * s2) / (p * p * p);
    n.lambda[3] = std::max(0.0, 2 - 2 * (1 / (s1 * s1 * s1) + 1 / (s2 * s2 * s2)) / (s1 + s2));
    n.dpsi = U * Vec2(2 * s1 - 2 / (s1 * s1 * s1), 2 * s2 - 2 / (s2 * s2 * s2)).asDiagonal() * V.transpose();
    return n;
}

}  // namespace ctmap
