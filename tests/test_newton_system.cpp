// The optimiser's Newton system (refine/newton_system.h): one face's share against finite
// differences of its energy, and the assembled system against a dense sum of the faces' shares,
// with fixed, sliding and free vertices numbered in a shuffled order; the same bits with and
// without threads.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "ctmap/refine/newton_system.h"

namespace {

using ctmap::FaceFrame;
using ctmap::Mat2;
using ctmap::Tri;
using ctmap::Vec2;
using ctmap::Vec3;

double face_energy(const FaceFrame& F, const Vec2 x[3], double weight) {
    return weight * F.area * ctmap::symmetric_dirichlet_density(ctmap::face_jacobian(F, x[0], x[1], x[2]));
}

// A face stretched a little (singular values about 1.3: the twist's eigenvalue 2 - 2 (s1^-3 +
// s2^-3) / (s1 + s2) is positive there, as is every other), so the projected Hessian is the
// Hessian itself; both it and the gradient match central differences.
TEST(FaceHessian, MatchesFiniteDifferencesOfTheFaceEnergy) {
    const FaceFrame F = ctmap::face_frame(Vec3(0, 0, 0), Vec3(1.1, 0.1, 0.2), Vec3(0.3, 0.9, -0.1));
    Vec2 x[3] = {Vec2(0.05, -0.02), Vec2(1.4, 0.15), Vec2(0.3, 1.25)};
    const double w = 0.7;
    const ctmap::FaceNewton L = ctmap::face_newton(ctmap::face_jacobian(F, x[0], x[1], x[2]));
    for (double l : L.lambda) ASSERT_GT(l, 0) << "the case must be mild enough for no clamping";
    const ctmap::FaceHessian h = ctmap::face_hessian(F, L, w);
    const double step = 1e-5;
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 2; ++i) {
            Vec2 p[3] = {x[0], x[1], x[2]}, m[3] = {x[0], x[1], x[2]};
            p[a][i] += step, m[a][i] -= step;
            const double fd = (face_energy(F, p, w) - face_energy(F, m, w)) / (2 * step);
            EXPECT_NEAR(h.gradient[a][i], fd, 1e-7 * (1 + std::abs(fd))) << "corner " << a << " coordinate " << i;
            // Second derivatives: differences of the gradient (from face_hessian at the moved points).
            const ctmap::FaceHessian hp =
                ctmap::face_hessian(F, ctmap::face_newton(ctmap::face_jacobian(F, p[0], p[1], p[2])), w);
            const ctmap::FaceHessian hm =
                ctmap::face_hessian(F, ctmap::face_newton(ctmap::face_jacobian(F, m[0], m[1], m[2])), w);
            for (int b = 0; b < 3; ++b)
                for (int j = 0; j < 2; ++j) {
                    const double fd2 = (hp.gradient[b][j] - hm.gradient[b][j]) / (2 * step);
                    EXPECT_NEAR(h.at(b, a)(j, i), fd2, 1e-6 * (1 + std::abs(fd2)))
                        << "block (" << b << ", " << a << ") entry (" << j << ", " << i << ")";
                }
        }
}

TEST(FaceHessian, AFaceOfZeroAreaHasNone) {
    const FaceFrame F = ctmap::face_frame(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0));
    ASSERT_EQ(F.area, 0);
    const ctmap::FaceHessian h = ctmap::face_hessian(F, ctmap::FaceNewton(), 1.0);
    for (const Mat2& b : h.block) EXPECT_EQ(b.norm(), 0);
    for (const Vec2& g : h.gradient) EXPECT_EQ(g.norm(), 0);
}

struct Case {
    std::vector<Tri> faces;
    std::vector<ctmap::Dof> dof;
    std::vector<ctmap::FaceHessian> local;
    int unknowns = 0;
};

// A 7 x 7 grid of vertices over a bumpy surface, mapped with a jittered grid; corners fixed, the
// rest of the first row sliding along random directions, the others free; unknowns numbered in a
// shuffled vertex order.
Case grid_case() {
    const int n = 7;
    Case c;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> jitter(-0.15, 0.15);
    std::vector<Vec3> p(n * n);
    std::vector<Vec2> uv(n * n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            p[i * n + j] = Vec3(j, i, 0.3 * std::sin(1.3 * i + 0.7 * j));
            uv[i * n + j] = Vec2(j + jitter(rng), i + jitter(rng));
        }
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const int a = i * n + j;
            c.faces.push_back({a, a + 1, a + n + 1}), c.faces.push_back({a, a + n + 1, a + n});
        }
    c.dof.resize(n * n);
    std::vector<int> order(n * n);
    for (int v = 0; v < n * n; ++v) order[v] = v;
    std::shuffle(order.begin(), order.end(), rng);
    for (int v : order) {
        if (v == 0 || v == n - 1 || v == n * (n - 1) || v == n * n - 1) continue;  // fixed
        c.dof[v].first = c.unknowns;
        c.dof[v].n = v < n ? 1 : 2;
        if (v < n) c.dof[v].dir = Vec2(1 + jitter(rng), jitter(rng));
        c.unknowns += c.dof[v].n;
    }
    for (const Tri& t : c.faces) {
        const FaceFrame F = ctmap::face_frame(p[t[0]], p[t[1]], p[t[2]]);
        c.local.push_back(ctmap::face_hessian(
            F, ctmap::face_newton(ctmap::face_jacobian(F, uv[t[0]], uv[t[1]], uv[t[2]])), 0.01));
    }
    return c;
}

TEST(NewtonSystem, IsTheSumOfTheFacesSharesInTheUnknowns) {
    const Case c = grid_case();
    // The oracle: each face's 6 x 6 share, projected to the unknowns (dx = P dy), summed densely.
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(c.unknowns, c.unknowns);
    Eigen::VectorXd gradient = Eigen::VectorXd::Zero(c.unknowns);
    for (std::size_t f = 0; f < c.faces.size(); ++f) {
        const Tri& t = c.faces[f];
        for (int a = 0; a < 3; ++a) {
            const ctmap::Dof& da = c.dof[t[a]];
            for (int i = 0; i < da.n; ++i) {
                gradient[da.first + i] += da.column(i).dot(c.local[f].gradient[a]);
                for (int b = 0; b < 3; ++b) {
                    const ctmap::Dof& db = c.dof[t[b]];
                    for (int j = 0; j < db.n; ++j)
                        dense(da.first + i, db.first + j) += da.column(i).dot(c.local[f].at(a, b) * db.column(j));
                }
            }
        }
    }
    ctmap::NewtonSystem system(c.faces, c.dof, c.unknowns);
    Eigen::VectorXd rhs(c.unknowns);
    system.assemble(c.local, true, rhs, false);
    const Eigen::MatrixXd K = Eigen::MatrixXd(system.matrix());
    for (int r = 0; r < c.unknowns; ++r)
        for (int col = 0; col < c.unknowns; ++col)
            if (r <= col) EXPECT_NEAR(K(r, col), dense(r, col), 1e-12 * dense.norm()) << r << ", " << col;
            else EXPECT_EQ(K(r, col), 0) << "below the diagonal: " << r << ", " << col;
    EXPECT_LT((rhs + gradient).norm(), 1e-13 * gradient.norm());
    for (int col = 0; col < c.unknowns; ++col) EXPECT_EQ(system.matrix().valuePtr()[system.diagonal(col)], K(col, col));

    // With threads: the same bits. Without the Hessian: the matrix as it was, the gradient anew.
    ctmap::NewtonSystem threaded(c.faces, c.dof, c.unknowns);
    Eigen::VectorXd rhs2(c.unknowns);
    threaded.assemble(c.local, true, rhs2, true);
    ASSERT_EQ(threaded.matrix().nonZeros(), system.matrix().nonZeros());
    EXPECT_TRUE(std::equal(threaded.matrix().valuePtr(), threaded.matrix().valuePtr() + threaded.matrix().nonZeros(),
                           system.matrix().valuePtr()));
    EXPECT_TRUE(rhs2 == rhs);
    std::vector<ctmap::FaceHessian> halved = c.local;
    for (auto& h : halved)
        for (Vec2& g : h.gradient) g *= 0.5;
    system.assemble(halved, false, rhs2, true);
    EXPECT_TRUE(std::equal(threaded.matrix().valuePtr(), threaded.matrix().valuePtr() + threaded.matrix().nonZeros(),
                           system.matrix().valuePtr()));
    EXPECT_LT((rhs2 - 0.5 * rhs).norm(), 1e-15 * rhs.norm());
}

}  // namespace
