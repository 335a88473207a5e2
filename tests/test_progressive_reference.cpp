// The progressive reference of the distortion optimiser (refine/progressive_reference.h): a face
// within the bound keeps its 3D frame; one beyond it gets a reference against which its map's
// distortion is exactly the bound, with the 3D area and a positive determinant.
#include <gtest/gtest.h>

#include <random>

#include "ctmap/refine/progressive_reference.h"

namespace {

using namespace ctmap;

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
