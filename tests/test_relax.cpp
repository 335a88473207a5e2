// The paper's relaxation (§2.4, Fig. 4): virtual-image weights for border vertices, moves that
// never flip a triangle or break the border, features bitwise fixed, distortion lowered.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <iostream>
#include <random>

#include "ctmap/certify/certificate.h"
#include "ctmap/embed/mean_value_embedding.h"
#include "ctmap/errors.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/refine/relax.h"
#include "ctmap/map_texture.h"
#include "map_cases.h"
#include "random_features.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

const double kPi = std::acos(-1.0);

TEST(VirtualImageWeights, SumToOneAndReproduceAPlanarFan) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(0, 1);
    const Vec3 o(0.1, 0.2, -0.3), ex = Vec3(0.6, 0.8, 0).normalized(), ey = Vec3(-0.48, 0.36, 0.8).normalized();
    int tested = 0;
    for (int trial = 0; trial < 300; ++trial) {
        // A fan from angle 0 to theta (convex, straight or reflex border vertex); the virtual
        // circuit is star-shaped when the interior angles lie in (theta - pi, pi).
        const double theta = (0.4 + 0.8 * U(rng)) * kPi;
        const int n = 3 + trial % 6;
        const double lo = std::max(0.0, theta - kPi) + 0.05, hi = std::min(theta, kPi) - 0.05;
        if (hi <= lo) continue;
        std::vector<double> ang{0};
        for (int j = 1; j + 1 < n; ++j) ang.push_back(lo + (hi - lo) * (j - 0.5 + 0.8 * (U(rng) - 0.5)) / (n - 2));
        ang.push_back(theta);
        std::vector<Vec3> fan;
        for (double a : ang) {
            const double r = 0.3 + U(rng);
            fan.push_back(o + r * std::cos(a) * ex + r * std::sin(a) * ey);
        }
        const std::vector<double> mu = border_mean_value_weights(o, fan);
        // A nearly straight border vertex always has the form. Elsewhere the vertex lies outside
        // its neighbours' hull (an extrapolation, weights of mixed sign) and the form may be too
        // ill-conditioned (sum |mu| > 20); the vertex is then left alone.
        if (std::abs(theta - kPi) <= 0.05 * kPi) ASSERT_EQ(mu.size(), fan.size()) << "trial " << trial;
        if (mu.empty()) continue;
        ASSERT_EQ(mu.size(), fan.size());
        double sum = 0;
        Vec3 p = Vec3::Zero();
        for (std::size_t j = 0; j < fan.size(); ++j) {
            sum += mu[j];
            p += mu[j] * fan[j];
        }
        EXPECT_NEAR(sum, 1.0, 1e-13);
        EXPECT_LE((p - o).norm(), 1e-12) << "trial " << trial << " theta " << theta;
        ++tested;
    }
    EXPECT_GT(tested, 150);  // of about 290 fans
    EXPECT_LT(tested, 290);  // and the conditioning rule did reject some
    // A straight border (theta = pi) with a symmetric fan: by symmetry the interior neighbours'
    // weights cancel and the vertex is the average of its two border neighbours.
    const std::vector<Vec3> straight{{1, 0, 0}, {0.3, 0.7, 0}, {-0.3, 0.7, 0}, {-1, 0, 0}};
    const std::vector<double> mu = border_mean_value_weights(Vec3::Zero(), straight);
    EXPECT_NEAR(mu[0], 0.5, 1e-14);
    EXPECT_NEAR(mu[3], 0.5, 1e-14);
    EXPECT_NEAR(mu[1], 0.0, 1e-14);
    EXPECT_NEAR(mu[2], 0.0, 1e-14);
    // No interior neighbour: no form.
    EXPECT_TRUE(border_mean_value_weights(Vec3::Zero(), {{1, 0, 0}, {0, 1, 0}}).empty());
}

/// Embeds `c` (after splitting flat edges) and returns the per-vertex UVs.
std::vector<Vec2> embedded(CutCase& c) {
    split_flat_edges(c.cut, c.input);
    return embed_patches(c.cut, c.feature_uv);
}

Certificate certify_uv(const CutCase& c, const std::vector<Vec2>& uv) {
    return certify(TexturedMesh::with_vertex_uvs(c.cut.mesh, uv), c.cut.feature_vertex, c.feature_uv);
}

TEST(Relax, NefertitiLowersDistortionKeepsFeaturesAndNeverFlips) {
    CutCase c = disc_case(read_mesh(data("meshes/nefertiti.off")));
    std::vector<Vec2> uv = embedded(c);
    const Certificate before = certify_uv(c, uv);
    ASSERT_TRUE(before.valid);
    const std::vector<Vec2> initial = uv;
    const RelaxStats st = relax(c.cut.mesh, uv, c.cut.feature_vertex);
    const Certificate after = certify_uv(c, uv);
    EXPECT_TRUE(after.valid) << after.flipped << " flipped, " << after.degenerate << " degenerate, border crossings "
                             << after.border_crossings;
    for (int f = 0; f < 3; ++f) {
        EXPECT_EQ(uv[c.cut.feature_vertex[f]].x(), c.feature_uv[f].x());  // bitwise
        EXPECT_EQ(uv[c.cut.feature_vertex[f]].y(), c.feature_uv[f].y());
    }
    const Distortion &d0 = before.distortion, &d1 = after.distortion;
    std::cout << "nefertiti (3 border features), before -> after relaxation (" << st.iterations << " sweeps, "
              << st.moves << " moves, " << st.moves_shortened << " shortened, " << st.moves_rejected
              << " rejected, gain " << st.last_gain << "):\n"
              << "  symmetric Dirichlet " << d0.symmetric_dirichlet << " -> " << d1.symmetric_dirichlet << "\n"
              << "  conformal mean " << d0.conformal_mean << " -> " << d1.conformal_mean << ", max "
              << d0.conformal_max << " -> " << d1.conformal_max << "\n"
              << "  area mean " << d0.area_mean << " -> " << d1.area_mean << ", max " << d0.area_max << " -> "
              << d1.area_max << "\n"
              << "  L2 stretch " << d0.l2_stretch << " -> " << d1.l2_stretch << "\n";
    EXPECT_LT(d1.symmetric_dirichlet, 0.9 * d0.symmetric_dirichlet);
    // The guard's energy, kept up to date move by move, is the certificate's measure.
    EXPECT_NEAR(st.energy_before, d0.symmetric_dirichlet, 1e-10 * d0.symmetric_dirichlet);
    EXPECT_NEAR(st.energy_after, d1.symmetric_dirichlet, 1e-9 * d1.symmetric_dirichlet);
    EXPECT_LT(d1.conformal_mean, 0.9 * d0.conformal_mean);
    EXPECT_GT(st.moves, 0);
    EXPECT_GT(st.iterations, 1);
    // Border vertices moved too (the virtual images), not only interior ones.
    int border_moved = 0;
    for (int v : border_loop_by_sets(c.cut.mesh)) border_moved += uv[v] != initial[v];
    EXPECT_GT(border_moved, 10);

    // The paper's relaxation alone (no energy guard) also stays valid and lowers it here.
    std::vector<Vec2> pure = initial;
    RelaxOptions paper;
    paper.energy_guard = false;
    const RelaxStats sp = relax(c.cut.mesh, pure, c.cut.feature_vertex, paper);
    const Certificate cp = certify_uv(c, pure);
    EXPECT_TRUE(cp.valid);
    EXPECT_LT(cp.distortion.symmetric_dirichlet, d0.symmetric_dirichlet);
    std::cout << "  without the energy guard (" << sp.iterations << " sweeps): symmetric Dirichlet "
              << cp.distortion.symmetric_dirichlet << ", conformal mean " << cp.distortion.conformal_mean
              << ", area mean " << cp.distortion.area_mean << ", L2 stretch " << cp.distortion.l2_stretch << "\n";
}

TEST(Relax, TwoPatchGridPathVerticesMoveAndTheMapStaysValid) {
    CutCase c = grid_two_patches(16, 12, 0.35);
    std::vector<Vec2> uv = embedded(c);
    const Certificate before = certify_uv(c, uv);
    ASSERT_TRUE(before.valid);
    const std::vector<Vec2> initial = uv;
    RelaxOptions opt;
    opt.max_iterations = 300;
    relax(c.cut.mesh, uv, c.cut.feature_vertex, opt);
    const Certificate after = certify_uv(c, uv);
    EXPECT_TRUE(after.valid);
    EXPECT_LT(after.distortion.symmetric_dirichlet, before.distortion.symmetric_dirichlet);
    // Vertices on the cut between the patches have whole neighbourhoods in the assembled map:
    // they leave the straight image edge.
    int moved = 0;
    const std::vector<int>& path = c.cut.patches[1].sides[0];
    for (std::size_t i = 1; i + 1 < path.size(); ++i) moved += (uv[path[i]] - initial[path[i]]).norm() > 1e-4;
    EXPECT_GT(moved, int(path.size()) / 2);
    for (std::size_t f = 0; f < 4; ++f) EXPECT_EQ(uv[c.cut.feature_vertex[f]], c.feature_uv[f]);
}

TEST(Relax, RealMeshesStayValid) {
    for (const std::string name : {"meshes/mushroom.off", "meshes/three_peaks.off", "meshes/lion-head.off"})
        for (const bool guard : {true, false}) {
            SCOPED_TRACE(name + (guard ? " with the energy guard" : " without the energy guard"));
            // Lopsided image triangle: the initial map is far from the relaxed one, many moves hit
            // the flip guard.
            CutCase c = disc_case(read_mesh(data(name)), {Vec2(0.02, 0.05), Vec2(0.97, 0.11), Vec2(0.9, 0.3)});
            std::vector<Vec2> uv = embedded(c);
            const Certificate before = certify_uv(c, uv);
            ASSERT_TRUE(before.valid);
            RelaxOptions opt;
            opt.energy_guard = guard;
            const RelaxStats st = relax(c.cut.mesh, uv, c.cut.feature_vertex, opt);
            const Certificate after = certify_uv(c, uv);
            EXPECT_TRUE(after.valid) << after.flipped << " flipped, " << after.degenerate << " degenerate, "
                                     << after.border_crossings << " border crossings";
            EXPECT_EQ(after.feature_max_error, 0.0);
            EXPECT_GT(st.moves, 0);
            // With the guard the relaxation is a descent on the certificate's energy. Without it
            // only validity is promised: Gauss-Seidel on the virtual-image rows (affine weights,
            // some negative) need not converge, and on lion-head it squeezes triangles (conformal
            // mean 7 -> 669) while the flip test keeps every one of them valid.
            if (guard) EXPECT_LT(after.distortion.symmetric_dirichlet, before.distortion.symmetric_dirichlet);
        }
}

TEST(Relax, ParallelSweepsGiveTheSameMapWithAnyNumberOfThreads) {
    // Colour classes move in parallel; the result must not depend on the threads (fixed chunks,
    // tallies added in order), so one thread, two threads and parallel = false (the same colour
    // order, no TBB) agree bit for bit, and the map stays valid. (On a one-core runner the
    // "two threads" run may use one: this checks the ordering, a race detector checks races.) Lion-head with 50 random features, embedded but not relaxed:
    // the paths' vertices and their neighbours have far to go.
    const TriMesh mesh = read_mesh(data("meshes/lion-head.off"));
    std::mt19937 rng(7);
    const auto rf = random_features(mesh, tutte_map(mesh), 50, 12, 1.0, rng);
    const std::vector<MapFeature> mf = map_features_of(rf);
    MapOptions bare;
    bare.refine = false;
    const MapResult r = map_texture(mesh, mf, bare);
    auto run = [&](bool parallel, int threads, RelaxStats* st) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        RelaxOptions opt;
        opt.parallel = parallel;
        std::vector<Vec2> uv = r.uv;
        *st = relax(r.cut.mesh, uv, r.cut.feature_vertex, opt);
        return uv;
    };
    RelaxStats s1, s2, s0;
    const std::vector<Vec2> one = run(true, 1, &s1), two = run(true, 2, &s2), seq = run(false, 1, &s0);
    EXPECT_GT(s2.moves, 1000);
    EXPECT_EQ(s1.moves, s2.moves);
    EXPECT_EQ(s0.moves, s2.moves);
    EXPECT_EQ(s1.iterations, s2.iterations);
    EXPECT_EQ(s1.energy_after, s2.energy_after);
    EXPECT_LT(s2.energy_after, s2.energy_before);
    int differ = 0;
    for (std::size_t v = 0; v < r.uv.size(); ++v) differ += (one[v] != two[v]) + (seq[v] != two[v]);
    EXPECT_EQ(differ, 0);
    EXPECT_TRUE(certify(TexturedMesh::with_vertex_uvs(r.cut.mesh, two), r.cut.feature_vertex, r.feature_uv).valid);
}

TEST(Relax, BorderCheckStopsABorderVertexAtAnotherBorderEdge) {
    // One free border vertex v (UV (0, 0), border along the x axis, its interior above). Its 3D
    // fan is planar with v at (0, -0.3), so its virtual-image average in UV is (0, -0.3). Below
    // it, a fixed triangle of another part of the map has a border edge at y = -0.15: moving v
    // all the way flips nothing but makes v's border edges cross that edge.
    TriMesh m;
    m.positions = {{0, -0.3, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0},          // v and its fan
                   {-0.5, -0.15, 1}, {0, -1, 1}, {0.5, -0.15, 1}};           // the other part, apart in 3D
    m.faces = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}};
    const std::vector<Vec2> uv0 = {{0, 0}, {1, 0}, {0, 1}, {-1, 0}, {-0.5, -0.15}, {0, -1}, {0.5, -0.15}};
    const std::vector<int> fixed{1, 2, 3, 4, 5, 6};
    std::vector<Vec2> fixed_uv;
    for (int v : fixed) fixed_uv.push_back(uv0[v]);
    ASSERT_TRUE(certify(TexturedMesh::with_vertex_uvs(m, uv0), fixed, fixed_uv).valid);
    ASSERT_EQ(border_mean_value_weights(m.positions[0], {m.positions[1], m.positions[2], m.positions[3]}).size(), 3u);

    RelaxOptions opt;
    opt.max_iterations = 200;
    opt.tolerance = 1e-9;
    opt.check_border = false;
    opt.over_relaxation = 1;  // plain moves: the vertex walks to its target and stops there
    std::vector<Vec2> unchecked = uv0;
    relax(m, unchecked, fixed, opt);
    EXPECT_NEAR(unchecked[0].y(), -0.3, 1e-9) << "the free vertex should reach its target";
    const Certificate bad = certify(TexturedMesh::with_vertex_uvs(m, unchecked), fixed, fixed_uv);
    EXPECT_EQ(bad.flipped, 0);
    EXPECT_FALSE(bad.border_simple) << "the case does not reach the other edge: it proves nothing";

    opt.check_border = true;
    std::vector<Vec2> checked = uv0;
    const RelaxStats st = relax(m, checked, fixed, opt);
    const Certificate good = certify(TexturedMesh::with_vertex_uvs(m, checked), fixed, fixed_uv);
    EXPECT_TRUE(good.valid) << good.border_crossings << " border crossings";
    EXPECT_GT(st.border_rejections, 0);
    EXPECT_GT(checked[0].y(), -0.15);  // stopped short of the other edge ...
    EXPECT_LT(checked[0].y(), -0.1);   // ... after getting close to it
    for (std::size_t i = 0; i < fixed.size(); ++i) EXPECT_EQ(checked[fixed[i]], fixed_uv[i]);
}

TEST(Relax, WindingStripStaysValid) {
    // A strip turning 2 pi + 0.6 in 3D (a split washer) relaxed from UVs turning 2 pi - 0.6 with
    // its first two columns fixed: the map must stay valid (the strip may not close over itself).
    const double turn = 2 * kPi + 0.6;
    std::vector<Vec2> uv0;
    const TriMesh m = helix_strip(32, 5, turn, 2 * kPi - 0.6, &uv0);
    std::vector<int> fixed;
    for (int v = 0; v < 10; ++v) fixed.push_back(v);
    std::vector<Vec2> fixed_uv;
    for (int v : fixed) fixed_uv.push_back(uv0[v]);
    const Certificate before = certify(TexturedMesh::with_vertex_uvs(m, uv0), fixed, fixed_uv);
    ASSERT_TRUE(before.valid);
    std::vector<Vec2> uv = uv0;
    RelaxOptions opt;
    opt.max_iterations = 2000;
    opt.energy_tolerance = 0;  // run to the move tolerance
    const RelaxStats st = relax(m, uv, fixed, opt);
    const Certificate after = certify(TexturedMesh::with_vertex_uvs(m, uv), fixed, fixed_uv);
    EXPECT_TRUE(after.valid);
    EXPECT_GT(st.moves, 1000);
    EXPECT_LT(after.distortion.symmetric_dirichlet, before.distortion.symmetric_dirichlet);
}

TEST(Relax, RejectsAnInvalidStartAndStopsAtTheTolerance) {
    CutCase c = grid_two_patches(8, 8);
    std::vector<Vec2> uv = embedded(c);
    std::vector<Vec2> broken = uv;
    std::swap(broken[c.cut.feature_vertex[0]], broken[c.cut.feature_vertex[2]]);
    EXPECT_THROW(relax(c.cut.mesh, broken, c.cut.feature_vertex), InternalError);
    // A loose tolerance stops early; a tight one goes on.
    RelaxOptions loose;
    loose.tolerance = 1e-1;
    std::vector<Vec2> a = uv;
    const RelaxStats sa = relax(c.cut.mesh, a, c.cut.feature_vertex, loose);
    EXPECT_TRUE(sa.converged);
    EXPECT_LE(sa.iterations, 2);
    RelaxOptions tight;
    tight.tolerance = 1e-9;
    tight.energy_tolerance = 0;
    tight.max_iterations = 5000;
    std::vector<Vec2> b = uv;
    const RelaxStats sb = relax(c.cut.mesh, b, c.cut.feature_vertex, tight);
    EXPECT_TRUE(sb.converged);
    EXPECT_GT(sb.iterations, sa.iterations);
    EXPECT_LT(sb.last_gain, 1e-9);
    // The energy rule (stop when a sweep gains less than 0.1% of the energy here) stops in
    // between. (With the default 1%, this small grid, whose interior starts at its mean value
    // solution, stops after the first sweep, which gains 0.98%.)
    std::vector<Vec2> c2 = uv;
    RelaxOptions energy_rule;
    energy_rule.energy_tolerance = 1e-3;
    const RelaxStats sc = relax(c.cut.mesh, c2, c.cut.feature_vertex, energy_rule);
    EXPECT_TRUE(sc.converged);
    EXPECT_GT(sc.iterations, sa.iterations);
    EXPECT_LT(sc.iterations, sb.iterations);
    EXPECT_LE(sc.energy_after, sc.energy_before);
    // At convergence every free vertex sits at its weighted average: relaxing again moves nothing.
    std::vector<Vec2> again = b;
    tight.max_iterations = 1;
    relax(c.cut.mesh, again, c.cut.feature_vertex, tight);
    double most = 0;
    for (std::size_t v = 0; v < b.size(); ++v) most = std::max(most, (again[v] - b[v]).norm());
    EXPECT_LT(most, 1e-8);
}

}  // namespace
}  // namespace ctmap::test
