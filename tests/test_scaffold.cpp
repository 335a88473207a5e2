// The free border's scaffold (refine/scaffold.h): it tiles the frame rectangle with the map
// (areas add up), its barrier is zero away from contact and grows as two border parts close in,
// its gradient matches finite differences, its flip-free bound is where a triangle collapses, and
// the progressive reference (refine/progressive_reference.h) bounds a face's distortion.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ctmap/certify/certificate.h"
#include "ctmap/refine/progressive_reference.h"
#include "ctmap/refine/scaffold.h"

namespace {

using namespace ctmap;

/// A U-shaped border loop (counter-clockwise): two prongs of width 0.2 with a gap `gap` between
/// them, on [0.2, 0.8]^2; vertices 0.05 apart along every side.
std::vector<Vec2> u_shape(double gap) {
    const double w = 0.2, x0 = 0.2, y0 = 0.2, top = 0.8;
    const double xl = x0 + w, xr = xl + gap, x1 = xr + w;
    const std::vector<Vec2> corner{{x0, y0}, {x1, y0}, {x1, top}, {xr, top}, {xr, y0 + w}, {xl, y0 + w}, {xl, top}, {x0, top}};
    std::vector<Vec2> loop;
    for (std::size_t i = 0; i < corner.size(); ++i) {
        const Vec2 a = corner[i], b = corner[(i + 1) % corner.size()];
        const int n = std::max(1, int(std::lround((b - a).norm() / 0.05)));
        for (int k = 0; k < n; ++k) loop.push_back(a + (b - a) * (double(k) / n));
    }
    return loop;
}

double polygon_area(const std::vector<Vec2>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec2& u = p[i];
        const Vec2& v = p[(i + 1) % p.size()];
        a += u.x() * v.y() - u.y() * v.x();
    }
    return 0.5 * a;
}

std::vector<int> iota(std::size_t n) {
    std::vector<int> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = int(i);
    return v;
}

TEST(Scaffold, TilesTheFrameWithTheMapAndIsZeroAwayFromContact) {
    const std::vector<Vec2> uv = u_shape(0.2);
    const Scaffold s(iota(uv.size()), uv, Vec2(0.2, 0.2), Vec2(0.8, 0.8), 0.05, 0.05 * 0.05 * 0.05, 1.0);
    ASSERT_GT(s.num_faces(), 0);
    EXPECT_TRUE(s.exact_ok(uv));
    // The frame is [0.2, 0.8] widened by 5% of 0.6 on each side: 0.66^2; the scaffold's
    // triangles, all counter-clockwise, cover it with the U exactly when they tile it.
    EXPECT_NEAR(s.area() + polygon_area(uv), 0.66 * 0.66, 1e-12);
    EXPECT_EQ(s.energy(uv), 0.0) << "no two border parts are within a tenth of an edge";
}

TEST(Scaffold, BarrierGrowsAsTheGapClosesAndItsGradientMatches) {
    // The gap between the prongs closes to 0.004 (a tenth of an edge 0.05 is 0.005: the barrier's
    // area is 0.05 x 0.005 / 2).
    const double area_ref = 0.5 * 0.05 * 0.005;
    double last = 0;
    for (double gap : {0.02, 0.004, 0.002, 0.001}) {
        const std::vector<Vec2> uv = u_shape(gap);
        const Scaffold s(iota(uv.size()), uv, Vec2(0.2, 0.2), Vec2(0.8, 0.8), 0.05, area_ref, 1.0);
        ASSERT_TRUE(s.exact_ok(uv));
        const double e = s.energy(uv);
        if (gap < 0.005) EXPECT_GT(e, last) << "gap " << gap;
        else EXPECT_EQ(e, 0.0) << "gap " << gap;
        last = e;
        if (e == 0) continue;
        // The gradient the Newton system gets against central differences, per coordinate.
        std::vector<Dof> dof(uv.size());
        for (std::size_t v = 0; v < uv.size(); ++v) dof[v].first = int(2 * v), dof[v].n = 2;
        Eigen::SparseMatrix<double> K(int(2 * uv.size()), int(2 * uv.size()));
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * uv.size());
        s.add_newton_terms(uv, dof, false, K, rhs);
        int checked = 0;
        const double scale = rhs.cwiseAbs().maxCoeff();  // finite differences' rounding is relative to it
        for (std::size_t v = 0; v < uv.size(); ++v)
            for (int c = 0; c < 2; ++c) {
                if (rhs[2 * v + c] == 0) continue;
                const double h = 1e-4 * gap;
                std::vector<Vec2> a = uv, b = uv;
                a[v][c] += h, b[v][c] -= h;
                const double fd = (s.energy(a) - s.energy(b)) / (2 * h);
                EXPECT_NEAR(-rhs[2 * v + c], fd, 1e-4 * std::abs(fd) + 1e-6 * scale) << "vertex " << v << " gap " << gap;
                ++checked;
            }
        EXPECT_GT(checked, 0);
    }
}

TEST(Scaffold, FlipFreeBoundIsWhereATriangleCollapses) {
    const std::vector<Vec2> uv = u_shape(0.05);
    const Scaffold s(iota(uv.size()), uv, Vec2(0.2, 0.2), Vec2(0.8, 0.8), 0.05, 1e-6, 1.0);
    // Move the right prong left, across the gap: some scaffold triangle in the gap collapses at
    // the bound; just before it every triangle is still counter-clockwise, just after not.
    std::vector<Vec2> d(uv.size(), Vec2::Zero());
    for (std::size_t v = 0; v < uv.size(); ++v)
        if (uv[v].x() > 0.44 && uv[v].y() > 0.41) d[v] = Vec2(-0.1, 0);
    const double t = s.max_step(uv, d);
    ASSERT_TRUE(std::isfinite(t));
    EXPECT_LE(t, 0.5 + 1e-9) << "the gap is 0.05: the prongs meet at t = 0.5";
    auto moved = [&](double f) {
        std::vector<Vec2> x = uv;
        for (std::size_t v = 0; v < uv.size(); ++v) x[v] += f * d[v];
        return x;
    };
    EXPECT_TRUE(s.exact_ok(moved(0.999 * t)));
    EXPECT_FALSE(s.exact_ok(moved(1.001 * t)));
    EXPECT_TRUE(std::isinf(s.energy(moved(1.001 * t))));
}

TEST(ProgressiveReference, BoundsTheDistortionAndKeepsTheArea) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const FaceFrame F = face_frame(Vec3(0, 0, 0), Vec3(1.3, 0.1, 0.2), Vec3(0.4, 0.9, -0.1));
    int bounded = 0;
    for (int k = 0; k < 200; ++k) {
        Mat2 J;
        J << 1 + 3 * u(rng), u(rng), u(rng), 0.05 + std::abs(u(rng));
        if (!(J.determinant() > 0)) continue;
        for (double bound : {1.5, 5.0, 20.0}) {
            const FaceFrame R = progressive_frame(F, J, bound);
            EXPECT_EQ(R.area, F.area);
            // The map's Jacobian from the reference: J R^-1 in the frames' coordinates, through
            // the UV triangle the frame F and J make.
            const Vec2 p1 = J * Vec2(1 / F.i00, 0), p2 = J * Vec2(-F.i01 / (F.i00 * F.i11), 1 / F.i11);
            const Mat2 Jr = face_jacobian(R, Vec2(0, 0), p1, p2);
            const double before = symmetric_dirichlet_density(J) / 4, after = symmetric_dirichlet_density(Jr) / 4;
            if (before <= bound) {
                EXPECT_EQ(R.i00, F.i00);
                EXPECT_EQ(R.i01, F.i01);
                EXPECT_EQ(R.i11, F.i11);
                EXPECT_NEAR(after, before, 1e-9 * before);
            } else {
                EXPECT_NEAR(after, bound, 1e-6 * bound) << "the reference bounds the distortion at the bound";
                EXPECT_GT(Jr.determinant(), 0);
                ++bounded;
            }
        }
    }
    EXPECT_GT(bounded, 50);
}

}  // namespace
