// Patch embedding (paper §2.4, issue 4): mean value weights, flat-edge splitting, the embedding
// of hand-built cuts (a disc as one patch, a grid cut into two), all certified by exact predicates.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <set>

#include "ctmap/certify/certificate.h"
#include "ctmap/embed/mean_value_embedding.h"
#include "ctmap/errors.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/io/features.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/refine/relax.h"
#include "map_cases.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// Certificate of the embedding `uv` of `c.cut` (features at their vertices).
Certificate certify_cut(const CutCase& c, const std::vector<Vec2>& uv) {
    return certify(TexturedMesh::with_vertex_uvs(c.cut.mesh, uv), c.cut.feature_vertex, c.feature_uv);
}

/// Every side vertex on its image triangle's side, in arc-length order: the parameter along the
/// side equals the 3D arc length fraction, and the distance to the side's line is at rounding level.
void expect_sides_on_triangle(const CutCase& c, const std::vector<Vec2>& uv) {
    for (const Patch& p : c.cut.patches)
        for (int k = 0; k < 3; ++k) {
            const std::vector<int>& s = p.sides[k];
            const Vec2 A = c.feature_uv[p.corners[k]], B = c.feature_uv[p.corners[(k + 1) % 3]];
            double total = 0;
            for (std::size_t i = 1; i < s.size(); ++i)
                total += (c.cut.mesh.positions[s[i]] - c.cut.mesh.positions[s[i - 1]]).norm();
            double arc = 0, last_t = -1;
            for (std::size_t i = 0; i < s.size(); ++i) {
                if (i > 0) arc += (c.cut.mesh.positions[s[i]] - c.cut.mesh.positions[s[i - 1]]).norm();
                const Vec2 d = uv[s[i]] - A, e = B - A;
                const double t = d.dot(e) / e.squaredNorm();
                const double off = std::abs(d.x() * e.y() - d.y() * e.x()) / e.norm();
                EXPECT_LE(off, 1e-15) << "side vertex " << s[i] << " is off its side";
                EXPECT_NEAR(t, arc / total, 1e-13) << "side vertex " << s[i];
                EXPECT_GT(t, last_t) << "side vertices out of order";
                last_t = t;
            }
        }
}

TEST(MeanValueWeights, PositiveSumToOneAndReproduceLinearFunctions) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0, 1);
    const double pi = std::acos(-1.0);
    // A tilted plane: the weights use 3D angles and lengths only.
    const Vec3 o(0.3, -0.2, 0.5), ex = Vec3(1, 0.2, -0.4).normalized();
    const Vec3 ey = ex.cross(Vec3(0.1, 0.9, 0.3)).normalized().cross(ex);
    for (int trial = 0; trial < 200; ++trial) {
        const int n = 3 + trial % 9;
        // A star-shaped ring: increasing angles with every gap below pi, random radii.
        std::vector<double> ang(n);
        double a = 0;
        for (int j = 0; j < n; ++j) {
            ang[j] = a;
            a += 2 * pi / n * (0.5 + U(rng));
        }
        for (double& x : ang) x *= 2 * pi / a;
        // Keep every gap below pi (the centre in the ring's kernel), else retry.
        bool star = true;
        for (int j = 0; j < n; ++j) star &= (j + 1 < n ? ang[j + 1] : 2 * pi) - ang[j] < 0.95 * pi;
        if (!star) continue;
        std::vector<Vec3> ring;
        for (int j = 0; j < n; ++j) {
            const double r = 0.2 + U(rng);
            ring.push_back(o + r * std::cos(ang[j]) * ex + r * std::sin(ang[j]) * ey);
        }
        const std::vector<double> w = mean_value_weights(o, ring);
        double sum = 0;
        Vec3 p = Vec3::Zero();
        for (int j = 0; j < n; ++j) {
            EXPECT_GT(w[j], 0);
            sum += w[j];
            p += w[j] * ring[j];
        }
        EXPECT_NEAR(sum, 1.0, 1e-14);
        EXPECT_LE((p - o).norm(), 1e-12) << "trial " << trial;
        // Any linear function f(x) = g.x + c is reproduced: f(o) = sum w_j f(ring_j).
        const Vec3 g(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5);
        double f = 0;
        for (int j = 0; j < n; ++j) f += w[j] * (g.dot(ring[j]) + 0.7);
        EXPECT_NEAR(f, g.dot(o) + 0.7, 1e-12);
    }
}

TEST(MeanValueWeights, NonPlanarRingGivesPositiveWeightsAndRejectsCoincidentPoints) {
    const Vec3 o(0, 0, 0);
    const std::vector<Vec3> ring{{1, 0, 0.5}, {0, 1, -0.3}, {-1, 0, 0.8}, {0, -1, -0.6}};
    const std::vector<double> w = mean_value_weights(o, ring);
    for (double x : w) EXPECT_GT(x, 0);
    EXPECT_THROW(mean_value_weights(o, {{1, 0, 0}, {0, 0, 0}, {0, 1, 0}}), std::invalid_argument);
    // The half-angle tangent stays accurate for tiny angles (1 - cos would lose every digit).
    const double eps = 1e-9;
    EXPECT_NEAR(half_angle_tangent(Vec3(1, 0, 0), Vec3(std::cos(eps), std::sin(eps), 0)), std::tan(eps / 2),
                1e-24);
}

TEST(Embed, PlanarTriangleIsReproducedExactlyByTheAffineMap) {
    // A planar patch whose border is a triangle: mean value coordinates reproduce linear
    // functions, so the embedding must be the affine map of the 3D triangle onto the image one.
    std::vector<Vec2> param;
    CutCase c = planar_triangle(12, 0.3, 11, &param);
    ASSERT_EQ(count_flat_edges(c.cut), 0);
    for (auto solver : {EmbedOptions::Solver::sparse_lu, EmbedOptions::Solver::bicgstab}) {
        EmbedOptions opt;
        opt.solver = solver;
        const std::vector<Vec2> uv = embed_patches(c.cut, c.feature_uv, opt);
        const Vec2 A = c.feature_uv[0], B = c.feature_uv[1], C = c.feature_uv[2];
        double worst = 0;
        for (int v = 0; v < c.cut.mesh.num_vertices(); ++v) {
            const Vec2 expected = A + param[v].x() * (B - A) + param[v].y() * (C - A);
            worst = std::max(worst, (uv[v] - expected).norm());
        }
        EXPECT_LE(worst, 1e-12) << (solver == EmbedOptions::Solver::sparse_lu ? "SparseLU" : "BiCGSTAB");
        EXPECT_TRUE(certify_cut(c, uv).valid);
    }
}

TEST(Embed, SplitFlatEdgesRemovesEveryFlatEdgeAndKeepsTheSurface) {
    CutCase c = grid_two_patches(8, 8);
    // The alternating diagonals give one flat edge in each corner cell of the square.
    EXPECT_EQ(count_flat_edges(c.cut), 4);
    EXPECT_THROW(embed_patches(c.cut, c.feature_uv), InternalError);
    const int nv0 = c.cut.mesh.num_vertices(), nf0 = c.cut.mesh.num_faces();
    const CutMesh before = c.cut;
    const FlatEdgeStats st = split_flat_edges(c.cut, c.input);
    EXPECT_EQ(st.edges_split, 4);
    EXPECT_EQ(count_flat_edges(c.cut), 0);
    EXPECT_EQ(c.cut.mesh.num_vertices(), nv0 + 4);
    EXPECT_EQ(c.cut.mesh.num_faces(), nf0 + 8);
    ASSERT_EQ(c.cut.face_patch.size(), c.cut.mesh.faces.size());
    ASSERT_EQ(c.cut.vertex_face.size(), c.cut.mesh.positions.size());
    // Vertex order kept; new vertices on the input surface, with correct barycentric coordinates.
    for (int v = 0; v < nv0; ++v) EXPECT_EQ(c.cut.mesh.positions[v], before.mesh.positions[v]);
    for (int v = nv0; v < c.cut.mesh.num_vertices(); ++v) {
        const Tri& t = c.input.faces[c.cut.vertex_face[v]];
        const Vec3& l = c.cut.vertex_bary[v];
        EXPECT_GE(l.minCoeff(), -1e-12);
        const Vec3 p = l[0] * c.input.positions[t[0]] + l[1] * c.input.positions[t[1]] + l[2] * c.input.positions[t[2]];
        EXPECT_LE((p - c.cut.mesh.positions[v]).norm(), 1e-14);
    }
    // Same area per patch, and every face keeps its orientation (normals agree with the input's).
    auto patch_area = [](const CutMesh& m, int p) {
        double a = 0;
        for (int f = 0; f < m.mesh.num_faces(); ++f)
            if (m.face_patch[f] == p) {
                const Tri& t = m.mesh.faces[f];
                a += 0.5 * (m.mesh.positions[t[1]] - m.mesh.positions[t[0]])
                               .cross(m.mesh.positions[t[2]] - m.mesh.positions[t[0]])
                               .norm();
            }
        return a;
    };
    for (int p = 0; p < 2; ++p) EXPECT_NEAR(patch_area(c.cut, p), patch_area(before, p), 1e-14);
    for (const Tri& t : c.cut.mesh.faces) {
        const Vec3 n = (c.cut.mesh.positions[t[1]] - c.cut.mesh.positions[t[0]])
                           .cross(c.cut.mesh.positions[t[2]] - c.cut.mesh.positions[t[0]]);
        EXPECT_GT(n.z(), 0);
    }
    // Idempotent.
    EXPECT_EQ(split_flat_edges(c.cut, c.input).edges_split, 0);
}

TEST(Embed, GridCutIntoTwoPatchesIsValidWithSharedSidesBitwiseEqual) {
    CutCase c = grid_two_patches(10, 8);
    split_flat_edges(c.cut, c.input);
    const std::vector<Vec2> uv = embed_patches(c.cut, c.feature_uv);
    const Certificate cert = certify_cut(c, uv);
    EXPECT_TRUE(cert.valid);
    EXPECT_EQ(cert.flipped, 0);
    EXPECT_EQ(cert.degenerate, 0);
    EXPECT_EQ(cert.feature_max_error, 0.0);
    EXPECT_TRUE(cert.border_simple);
    for (std::size_t f = 0; f < c.feature_uv.size(); ++f) {
        EXPECT_EQ(uv[c.cut.feature_vertex[f]].x(), c.feature_uv[f].x());  // bitwise
        EXPECT_EQ(uv[c.cut.feature_vertex[f]].y(), c.feature_uv[f].y());
    }
    expect_sides_on_triangle(c, uv);
    // The cut's vertices lie on the segment L-R of both image triangles; the lower patch lies on
    // one side of it and the upper on the other.
    const Vec2 L = c.feature_uv[0], R = c.feature_uv[2];
    const std::set<int> cut_path(c.cut.patches[1].sides[0].begin(), c.cut.patches[1].sides[0].end());
    for (int f = 0; f < c.cut.mesh.num_faces(); ++f)
        for (int v : c.cut.mesh.faces[f]) {
            if (cut_path.count(v)) continue;  // within rounding of the line, checked above
            EXPECT_EQ(orientation_2d(L, R, uv[v]), c.cut.face_patch[f] == 0 ? -1 : 1);
        }
    // The parallel and the sequential solve agree bitwise (independent patches).
    EmbedOptions seq;
    seq.parallel = false;
    EXPECT_EQ(embed_patches(c.cut, c.feature_uv, seq), uv);
}

TEST(Embed, RealDiscMeshesAsOnePatchAreValid) {
    for (const std::string name : {"meshes/nefertiti.off", "meshes/mushroom.off", "meshes/three_peaks.off"}) {
        SCOPED_TRACE(name);
        CutCase c = disc_case(read_mesh(data(name)));
        const FlatEdgeStats st = split_flat_edges(c.cut, c.input);
        EXPECT_EQ(count_flat_edges(c.cut), 0);
        const std::vector<Vec2> uv = embed_patches(c.cut, c.feature_uv);
        const Certificate cert = certify_cut(c, uv);
        EXPECT_TRUE(cert.valid) << "flipped " << cert.flipped << ", degenerate " << cert.degenerate
                                << ", feature error " << cert.feature_max_error << ", border crossings "
                                << cert.border_crossings << " (" << st.edges_split << " flat edges split)";
        EXPECT_EQ(cert.feature_max_error, 0.0);
        for (int f = 0; f < 3; ++f) EXPECT_EQ(uv[c.cut.feature_vertex[f]], c.feature_uv[f]);
        expect_sides_on_triangle(c, uv);
        // Every vertex off the sides strictly inside the image triangle (exact predicates; the
        // side vertices are within rounding of their sides, checked above).
        const Vec2 A = c.feature_uv[0], B = c.feature_uv[1], C = c.feature_uv[2];
        std::set<int> on_side;
        for (const auto& s : c.cut.patches[0].sides) on_side.insert(s.begin(), s.end());
        for (int v = 0; v < c.cut.mesh.num_vertices(); ++v) {
            ASSERT_TRUE(uv[v].allFinite());
            if (on_side.count(v)) continue;
            EXPECT_EQ(orientation_2d(A, B, uv[v]), 1);
            EXPECT_EQ(orientation_2d(B, C, uv[v]), 1);
            EXPECT_EQ(orientation_2d(C, A, uv[v]), 1);
        }
    }
}

TEST(Embed, NefertitiExampleThroughTheRealCut) {
    // The shipped example end to end through the library: cut (issue 3), flat edges split,
    // embedded, relaxed; certified valid before and after, features bitwise exact.
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    const FeatureSet fs = read_features(data("features/nefertiti_astronaut.json"));
    std::vector<int> fv;
    std::vector<std::string> names;
    std::vector<Vec2> fuv;
    for (const Feature& f : fs.features) {
        fv.push_back(f.vertex);
        names.push_back(f.name);
        fuv.push_back(image_to_uv(f.image, 512, 512));  // astronaut.png is 512 x 512
    }
    const FeatureTriangulation ft = triangulate_features(fuv, border_features(mesh, fv), names);
    CutMesh cut = cut_mesh(mesh, fv, ft);
    const FlatEdgeStats st = split_flat_edges(cut, mesh);
    EXPECT_EQ(count_flat_edges(cut), 0);
    std::vector<Vec2> uv = embed_patches(cut, fuv);
    auto cert = [&] { return certify(TexturedMesh::with_vertex_uvs(cut.mesh, uv), cut.feature_vertex, fuv); };
    const Certificate before = cert();
    EXPECT_TRUE(before.valid) << before.flipped << " flipped, " << before.degenerate << " degenerate";
    const RelaxStats rs = relax(cut.mesh, uv, cut.feature_vertex);
    const Certificate after = cert();
    EXPECT_TRUE(after.valid) << after.flipped << " flipped, " << after.degenerate << " degenerate";
    EXPECT_EQ(after.feature_max_error, 0.0);
    EXPECT_LT(after.distortion.symmetric_dirichlet, before.distortion.symmetric_dirichlet);
    const Distortion &d0 = before.distortion, &d1 = after.distortion;
    std::cout << "nefertiti example: " << ft.triangles.size() << " patches, " << cut.mesh.num_faces()
              << " faces, " << st.edges_split << " flat edges split; relaxation " << rs.iterations << " sweeps\n"
              << "  symmetric Dirichlet " << d0.symmetric_dirichlet << " -> " << d1.symmetric_dirichlet
              << "\n  conformal mean " << d0.conformal_mean << " -> " << d1.conformal_mean << ", max "
              << d0.conformal_max << " -> " << d1.conformal_max << "\n  area mean " << d0.area_mean << " -> "
              << d1.area_mean << ", max " << d0.area_max << " -> " << d1.area_max << "\n  L2 stretch "
              << d0.l2_stretch << " -> " << d1.l2_stretch << "\n";
}

TEST(Embed, RejectsMalformedCuts) {
    CutCase c = grid_two_patches(6, 6);
    split_flat_edges(c.cut, c.input);
    {
        CutMesh bad = c.cut;
        std::reverse(bad.patches[0].sides[1].begin(), bad.patches[0].sides[1].end());
        EXPECT_THROW(embed_patches(bad, c.feature_uv), InternalError);
    }
    {
        CutMesh bad = c.cut;
        bad.patches[1].sides[0].erase(bad.patches[1].sides[0].begin() + 2);  // sides of the cut disagree
        EXPECT_THROW(embed_patches(bad, c.feature_uv), InternalError);
    }
    {
        std::vector<Vec2> uv = c.feature_uv;
        uv[0] = Vec2(0, 0.5), uv[1] = Vec2(0.5, 0.5), uv[2] = Vec2(1, 0.5);  // image triangle (L, B, R) flat
        EXPECT_THROW(embed_patches(c.cut, uv), InternalError);
    }
    EXPECT_THROW(embed_patches(c.cut, {Vec2(0, 0)}), InternalError);
}

}  // namespace
}  // namespace ctmap::test
