// The free border's barrier (refine/box_barrier.h): its derivatives against finite differences,
// zero beyond eps, infinite at the wall, and the vertex terms the optimiser adds.
#include <gtest/gtest.h>

#include <cmath>

#include "ctmap/refine/box_barrier.h"

namespace {

using ctmap::Vec2;

TEST(BoxBarrier, DerivativesMatchFiniteDifferences) {
    const double eps = 0.05;
    for (double x : {0.001, 0.01, 0.02, 0.04, 0.049}) {
        double phi, d1, d2, pp, p1, p2, mp, m1, m2;
        ctmap::wall_barrier(x, eps, phi, d1, d2);
        const double h = 1e-6 * x;
        ctmap::wall_barrier(x + h, eps, pp, p1, p2);
        ctmap::wall_barrier(x - h, eps, mp, m1, m2);
        EXPECT_NEAR(d1, (pp - mp) / (2 * h), 1e-5 * std::abs(d1)) << "x = " << x;
        EXPECT_NEAR(d2, (p1 - m1) / (2 * h), 1e-5 * std::abs(d2)) << "x = " << x;
        EXPECT_GT(phi, 0);
        EXPECT_LT(d1, 0);  // it falls away from the wall
        EXPECT_GT(d2, 0);
    }
    double phi, d1, d2;
    ctmap::wall_barrier(0.05, eps, phi, d1, d2);
    EXPECT_EQ(phi, 0);
    EXPECT_EQ(d1, 0);
    EXPECT_EQ(d2, 0);
    ctmap::wall_barrier(0.3, eps, phi, d1, d2);
    EXPECT_EQ(phi, 0);
    ctmap::wall_barrier(0.0, eps, phi, d1, d2);
    EXPECT_TRUE(std::isinf(phi));
    ctmap::wall_barrier(-0.01, eps, phi, d1, d2);
    EXPECT_TRUE(std::isinf(phi));
}

// Vertex 1 is near the low x wall and the high y wall, vertex 0 is held but far from every wall,
// vertex 2 is near a wall but not held: the value and the terms are vertex 1's two walls, weighted.
TEST(BoxBarrier, TermsAreTheHeldVerticesNearAWall) {
    const std::vector<Vec2> x = {Vec2(0.5, 0.5), Vec2(0.01, 0.98), Vec2(0.001, 0.5)};
    const ctmap::BoxBarrier barrier({0, 1}, {2.0, 3.0, 5.0}, Vec2(0, 0), Vec2(1, 1), 0.05);
    double phi_x, d1x, d2x, phi_y, d1y, d2y;
    ctmap::wall_barrier(0.01, 0.05, phi_x, d1x, d2x);
    ctmap::wall_barrier(1 - 0.98, 0.05, phi_y, d1y, d2y);
    EXPECT_DOUBLE_EQ(barrier.value(x), 3.0 * phi_x + 3.0 * phi_y);
    int terms = 0;
    barrier.for_terms(x, [&](int v, int axis, double sign, double d1, double d2) {
        ++terms;
        EXPECT_EQ(v, 1);
        const bool low_x = axis == 0;
        EXPECT_EQ(sign, low_x ? 1.0 : -1.0);
        EXPECT_DOUBLE_EQ(d1, 3.0 * (low_x ? d1x : d1y));
        EXPECT_DOUBLE_EQ(d2, 3.0 * (low_x ? d2x : d2y));
    });
    EXPECT_EQ(terms, 2);
}

}  // namespace
