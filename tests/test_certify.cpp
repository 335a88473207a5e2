// The validity certificate (issue 4, must-show 4): agreement with an independent recomputation,
// and rejection of hand-broken maps; `ctmap check` exit codes.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <gmp.h>

#include <cmath>
#include <random>
#include <nlohmann/json.hpp>

#include "ctmap/certify/certificate.h"
#include "ctmap/embed/mean_value_embedding.h"
#include "ctmap/errors.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "map_cases.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// A valid map on exact dyadic coordinates: the planar grid with UV = its (x, y) scaled by 1/2
/// and shifted, so that midpoints and collinearities are exact in doubles.
struct GridMap {
    TexturedMesh tm;
    std::vector<int> features;
    std::vector<Vec2> feature_uv;
};
GridMap dyadic_grid(int n = 8) {
    GridMap g;
    const TriMesh m = grid_mesh(n, n, 0.15);
    std::vector<Vec2> uv;
    for (const Vec3& p : m.positions) uv.emplace_back(0.25 + 0.5 * p.x(), 0.125 + 0.5 * p.y());
    g.tm = TexturedMesh::with_vertex_uvs(m, uv);
    g.features = {0, n, (n + 1) * (n + 1) - 1};
    for (int v : g.features) g.feature_uv.push_back(uv[v]);
    return g;
}

/// Recomputes what the certificate decides with plain double cross products and an SVD, for a
/// well-conditioned map (no triangle near degenerate, so doubles decide the signs right).
struct Independent {
    int positive = 0, negative = 0, zero = 0;
    double feature_error = 0;
    double symmetric_dirichlet = 0, conformal_mean = 0, conformal_max = 0, l2 = 0;
};
Independent recompute(const TexturedMesh& tm, const std::vector<int>& fv, const std::vector<Vec2>& fuv) {
    Independent r;
    const TriMesh& m = tm.mesh;
    double a3 = 0, a2 = 0;
    for (int f = 0; f < m.num_faces(); ++f) {
        const Tri& t = m.faces[f];
        const Tri& u = tm.uv_faces[f];
        const Vec2 p = tm.uvs[u[1]] - tm.uvs[u[0]], q = tm.uvs[u[2]] - tm.uvs[u[0]];
        const double cross = p.x() * q.y() - p.y() * q.x();
        (cross > 0 ? r.positive : cross < 0 ? r.negative : r.zero)++;
        a2 += 0.5 * std::abs(cross);
        a3 += 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
    }
    for (std::size_t i = 0; i < fv.size(); ++i)
        for (int f = 0; f < m.num_faces(); ++f)
            for (int k = 0; k < 3; ++k)
                if (m.faces[f][k] == fv[i])
                    r.feature_error = std::max(r.feature_error, (tm.uvs[tm.uv_faces[f][k]] - fuv[i]).norm());
    // Jacobian from 3D to UV as a 2x3 matrix: J = Q (E^T E)^-1 E^T with E = [e1 e2] (3x2).
    const double s = std::sqrt(a3 / a2);
    double w = 0;
    for (int f = 0; f < m.num_faces(); ++f) {
        const Tri& t = m.faces[f];
        const Tri& u = tm.uv_faces[f];
        Eigen::Matrix<double, 3, 2> E;
        E << m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]];
        Eigen::Matrix2d Q;
        Q << s * (tm.uvs[u[1]] - tm.uvs[u[0]]), s * (tm.uvs[u[2]] - tm.uvs[u[0]]);
        const Eigen::Matrix<double, 2, 3> J = Q * (E.transpose() * E).inverse() * E.transpose();
        const Eigen::Vector2d sv = Eigen::JacobiSVD<Eigen::Matrix<double, 2, 3>>(J).singularValues();
        const double A = 0.5 * E.col(0).cross(E.col(1)).norm();
        // Symmetric Dirichlet by another formula: |J|_F^2 (1 + 1 / det^2), det = s1 s2.
        const double fro = J.squaredNorm(), det = sv[0] * sv[1];
        r.symmetric_dirichlet += A * fro * (1 + 1 / (det * det));
        r.conformal_mean += A * sv[0] / sv[1];
        r.conformal_max = std::max(r.conformal_max, sv[0] / sv[1]);
        r.l2 += A * 0.5 * (1 / (sv[0] * sv[0]) + 1 / (sv[1] * sv[1]));
        w += A;
    }
    r.symmetric_dirichlet /= w;
    r.conformal_mean /= w;
    r.l2 = std::sqrt(r.l2 / w);
    return r;
}

TEST(Certify, AgreesWithAnIndependentRecomputation) {
    // A well-conditioned real map: the two-patch grid embedding (3D bump, so distortion is not trivial).
    CutCase c = grid_two_patches(12, 10, 0.3);
    split_flat_edges(c.cut, c.input);
    const TexturedMesh tm = TexturedMesh::with_vertex_uvs(c.cut.mesh, embed_patches(c.cut, c.feature_uv));
    const Certificate cert = certify(tm, c.cut.feature_vertex, c.feature_uv);
    const Independent r = recompute(tm, c.cut.feature_vertex, c.feature_uv);
    EXPECT_TRUE(cert.valid);
    EXPECT_EQ(cert.positive, r.positive);
    EXPECT_EQ(cert.negative, r.negative);
    EXPECT_EQ(cert.degenerate, r.zero);
    EXPECT_EQ(cert.flipped, std::min(r.positive, r.negative));
    EXPECT_EQ(cert.feature_max_error, r.feature_error);
    EXPECT_EQ(cert.triangles, tm.mesh.num_faces());
    const Distortion& d = cert.distortion;
    EXPECT_NEAR(d.symmetric_dirichlet, r.symmetric_dirichlet, 1e-10 * r.symmetric_dirichlet);
    EXPECT_NEAR(d.conformal_mean, r.conformal_mean, 1e-10 * r.conformal_mean);
    EXPECT_NEAR(d.conformal_max, r.conformal_max, 1e-10 * r.conformal_max);
    EXPECT_NEAR(d.l2_stretch, r.l2, 1e-10 * r.l2);
    EXPECT_GT(d.symmetric_dirichlet, 4.0);  // not an isometry: the measure is not trivially at its minimum
    EXPECT_EQ(d.faces_measured, tm.mesh.num_faces());
    // The UV border of a disc: as many edges as the mesh border (8 + 8 + 12 + 12 + the splits' none).
    EXPECT_EQ(cert.border_edges, int(border_loop_by_sets(tm.mesh).size()));
}

TEST(Certify, IsometryHasIdealDistortion) {
    // The planar grid mapped by a rotation and scaling: every measure at its ideal value.
    const TriMesh m = grid_mesh(6, 6, 0.0);
    std::vector<Vec2> uv;
    for (const Vec3& p : m.positions) uv.emplace_back(0.5 + 0.3 * (0.6 * p.x() - 0.8 * p.y()), 0.2 + 0.3 * (0.8 * p.x() + 0.6 * p.y()));
    const Certificate c = certify(TexturedMesh::with_vertex_uvs(m, uv), {0}, {uv[0]});
    EXPECT_TRUE(c.valid);
    EXPECT_NEAR(c.distortion.symmetric_dirichlet, 4.0, 1e-12);
    EXPECT_NEAR(c.distortion.conformal_max, 1.0, 1e-12);
    EXPECT_NEAR(c.distortion.area_max, 1.0, 1e-12);
    EXPECT_NEAR(c.distortion.l2_stretch, 1.0, 1e-12);
}

TEST(Certify, RejectsOneFlippedTriangle) {
    GridMap g = dyadic_grid();
    ASSERT_TRUE(certify(g.tm, g.features, g.feature_uv).valid);
    // Push an interior vertex just across the opposite edge of one of its triangles: that one
    // triangle flips, its neighbours in the fan stay positive.
    const int v = 4 * 9 + 4;  // the centre of the 8 x 8 grid
    int face = -1;
    for (int f = 0; f < g.tm.mesh.num_faces() && face < 0; ++f)
        if (std::count(g.tm.mesh.faces[f].begin(), g.tm.mesh.faces[f].end(), v)) face = f;
    const Tri& t = g.tm.mesh.faces[face];
    int a = -1, b = -1;
    for (int k = 0; k < 3; ++k)
        if (t[k] == v) a = t[(k + 1) % 3], b = t[(k + 2) % 3];
    const Vec2 mid = 0.5 * (g.tm.uvs[a] + g.tm.uvs[b]);
    g.tm.uvs[v] = mid + 0.05 * (mid - g.tm.uvs[v]);
    const Certificate c = certify(g.tm, g.features, g.feature_uv);
    EXPECT_FALSE(c.valid);
    EXPECT_EQ(c.flipped, 1);
    EXPECT_EQ(c.degenerate, 0);
    ASSERT_EQ(c.bad_faces.size(), 1u);
    EXPECT_EQ(c.bad_faces[0], face);
    EXPECT_EQ(c.feature_max_error, 0.0);
    EXPECT_EQ(recompute(g.tm, g.features, g.feature_uv).negative, 1);
    // Exactly on the edge (dyadic midpoint, so exactly collinear): degenerate, not flipped.
    g.tm.uvs[v] = mid;
    const Certificate d = certify(g.tm, g.features, g.feature_uv);
    EXPECT_FALSE(d.valid);
    EXPECT_EQ(d.flipped, 0);
    EXPECT_EQ(d.degenerate, 1);
    EXPECT_FALSE(std::isfinite(d.distortion.symmetric_dirichlet));
    EXPECT_TRUE(nlohmann::json::parse(certificate_to_json(d).dump())["symmetric_dirichlet"].is_null());
}

TEST(Certify, RejectsAFeatureMovedByOneMillionth) {
    GridMap g = dyadic_grid();
    g.tm.uvs[g.features[1]].x() += 1e-6;
    const Certificate c = certify(g.tm, g.features, g.feature_uv);
    EXPECT_FALSE(c.valid);
    EXPECT_EQ(c.flipped, 0);
    EXPECT_TRUE(c.border_simple);
    EXPECT_NEAR(c.feature_max_error, 1e-6, 1e-16);
    EXPECT_EQ(c.worst_feature, 1);
    // One ulp is already an error: "exact" means bitwise.
    GridMap h = dyadic_grid();
    h.feature_uv[2].y() = std::nextafter(h.feature_uv[2].y(), 1.0);
    const Certificate e = certify(h.tm, h.features, h.feature_uv);
    EXPECT_FALSE(e.valid);
    EXPECT_GT(e.feature_max_error, 0.0);
}

TEST(Certify, RejectsABorderThatCrossesItself) {
    // A strip whose UVs wind 2 pi + 0.5: every triangle keeps its orientation, but the strip's
    // end lies over its start.
    std::vector<Vec2> uv;
    const TriMesh m = helix_strip(40, 3, 2 * std::acos(-1.0) + 0.5, 2 * std::acos(-1.0) + 0.5, &uv);
    const TexturedMesh tm = TexturedMesh::with_vertex_uvs(m, uv);
    const Certificate c = certify(tm, {0}, {uv[0]});
    EXPECT_FALSE(c.valid);
    EXPECT_EQ(c.flipped, 0);
    EXPECT_EQ(c.degenerate, 0);
    EXPECT_TRUE(c.mirrored);  // the strip runs clockwise in its (x, y) frame
    EXPECT_FALSE(c.border_simple);
    EXPECT_GT(c.border_crossings, 0);
    // The same strip winding less than a full turn is valid.
    std::vector<Vec2> uv2;
    const TriMesh m2 = helix_strip(40, 3, 2 * std::acos(-1.0) + 0.5, 2 * std::acos(-1.0) - 0.5, &uv2);
    const Certificate ok = certify(TexturedMesh::with_vertex_uvs(m2, uv2), {0}, {uv2[0]});
    EXPECT_TRUE(ok.valid);
    EXPECT_EQ(ok.border_edges, 2 * 40 + 2 * 2);
}

TEST(Certify, RejectsBordersThatTouch) {
    // A bow tie: two triangles whose tips are different mesh vertices (apart in 3D) at one UV
    // point. No triangle is flipped, but the border touches itself there.
    TriMesh bow;
    bow.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.5, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0.1}};
    bow.faces = {{0, 1, 2}, {5, 3, 4}};  // two triangles, separate in 3D (different vertices 2 and 5)
    std::vector<Vec2> buv = {{0, 0}, {1, 0}, {0.5, 0.5}, {1, 1}, {0, 1}, {0.5, 0.5}};
    const Certificate c = certify(TexturedMesh::with_vertex_uvs(bow, buv), {0}, {buv[0]});
    EXPECT_EQ(c.flipped, 0);
    EXPECT_EQ(c.degenerate, 0);
    EXPECT_FALSE(c.border_simple) << "two UV vertices at one point: the border touches itself";
    buv[5] = {0.5, 0.5 + 1.0 / 1024};
    EXPECT_TRUE(certify(TexturedMesh::with_vertex_uvs(bow, buv), {0}, {buv[0]}).border_simple);
}

TEST(Certify, MirroredChartIsValidAndMixedIsNot) {
    GridMap g = dyadic_grid();
    for (Vec2& p : g.tm.uvs) p.x() = 1.0 - p.x();
    for (std::size_t i = 0; i < g.features.size(); ++i) g.feature_uv[i] = g.tm.uvs[g.features[i]];
    const Certificate c = certify(g.tm, g.features, g.feature_uv);
    EXPECT_TRUE(c.valid);
    EXPECT_TRUE(c.mirrored);
    EXPECT_EQ(c.negative, g.tm.mesh.num_faces());
}

TEST(Certify, PerCornerTexCoordsAreOneUvVertex) {
    // The same map written with one `vt` per face corner (as some tools do) certifies the same.
    GridMap g = dyadic_grid();
    TexturedMesh split = g.tm;
    split.uvs.clear();
    for (std::size_t f = 0; f < split.uv_faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            split.uvs.push_back(g.tm.uvs[g.tm.uv_faces[f][k]]);
            split.uv_faces[f][k] = int(split.uvs.size()) - 1;
        }
    const Certificate a = certify(g.tm, g.features, g.feature_uv), b = certify(split, g.features, g.feature_uv);
    EXPECT_TRUE(b.valid);
    EXPECT_EQ(a.border_edges, b.border_edges);
    EXPECT_EQ(a.border_edges, 32);
}

TEST(Certify, BadInputIsReported) {
    GridMap g = dyadic_grid();
    EXPECT_THROW(certify(g.tm, {100000}, {Vec2(0, 0)}), BadInput);
    EXPECT_THROW(certify(g.tm, {0, 1}, {Vec2(0, 0)}), BadInput);
    TexturedMesh bad = g.tm;
    bad.uv_faces.pop_back();
    EXPECT_THROW(certify(bad, g.features, g.feature_uv), BadInput);
}

TEST(Certify, SegmentPredicateIsExact) {
    // Touching at an endpoint, collinear overlap, collinear disjoint, and a crossing at a point
    // that is not representable.
    EXPECT_TRUE(segments_intersect_2d({0, 0}, {1, 1}, {1, 1}, {2, 0}));
    EXPECT_TRUE(segments_intersect_2d({0, 0}, {2, 0}, {1, 0}, {3, 0}));
    EXPECT_FALSE(segments_intersect_2d({0, 0}, {1, 0}, {2, 0}, {3, 0}));
    EXPECT_TRUE(segments_intersect_2d({0, 0}, {1, 1}, {0, 1}, {1, 0}));
    const double e = std::ldexp(1.0, -52);  // one ulp of 0.5 is 2^-53
    EXPECT_FALSE(segments_intersect_2d({0, 0}, {1, 1}, {0.5 + e, 0.5}, {2, 0.5 + e}));
    EXPECT_EQ(orientation_2d({0, 0}, {1, 1}, {0.5 + e, 0.5}), -1);
    // Kettner et al.'s classroom example: p near the line through q and r, perturbed by ulps.
    // The exact sign is sign(j - i); naive double evaluation gets some of these wrong.
    const double u = std::ldexp(1.0, -53);
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
            EXPECT_EQ(orientation_2d({0.5 + i * u, 0.5 + j * u}, {12, 12}, {24, 24}), (j > i) - (j < i))
                << i << ", " << j;
}

/// The exact sign of the orientation determinant, in rationals (GMP: every double is a rational).
int exact_orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
    mpq_t q[6], l, r;
    const double d[6] = {a.x(), a.y(), b.x(), b.y(), c.x(), c.y()};
    for (int i = 0; i < 6; ++i) {
        mpq_init(q[i]);
        mpq_set_d(q[i], d[i]);
    }
    mpq_inits(l, r, nullptr);
    mpq_sub(q[0], q[0], q[4]);  // ax - cx
    mpq_sub(q[1], q[1], q[5]);  // ay - cy
    mpq_sub(q[2], q[2], q[4]);  // bx - cx
    mpq_sub(q[3], q[3], q[5]);  // by - cy
    mpq_mul(l, q[0], q[3]);
    mpq_mul(r, q[1], q[2]);
    const int s = mpq_cmp(l, r);
    for (auto& x : q) mpq_clear(x);
    mpq_clears(l, r, nullptr);
    return (s > 0) - (s < 0);
}

TEST(Certify, OrientationAgreesWithRationalArithmetic) {
    // Nearly collinear triples (the third point on the segment, then moved by a few ulps) at
    // scales from 1e-150 to 1e150, where a floating-point filter is most likely to be wrong.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::uniform_int_distribution<int> ulps(-3, 3), scale_exp(-150, 150);
    int near_zero = 0;
    for (int n = 0; n < 200000; ++n) {
        const double s = std::pow(10.0, scale_exp(rng) * (n % 4 == 0 ? 1 : 0));
        Vec2 a(s * unit(rng), s * unit(rng)), b(s * unit(rng), s * unit(rng));
        // Every third triple exactly collinear before the ulps: t a multiple of 1/8 and a, b
        // rounded to multiples of s/1024 keep c = a + t (b - a) exact.
        const bool dyadic = n % 3 == 0;
        const double t = dyadic ? std::floor(4 * (unit(rng) + 1)) / 8 : 0.5 * (unit(rng) + 1);
        Vec2 c = a + t * (b - a);
        if (dyadic) {
            const double g = std::ldexp(1.0, std::ilogb(s) - 10);
            a = Vec2(std::round(a.x() / g) * g, std::round(a.y() / g) * g);
            b = Vec2(std::round(b.x() / g) * g, std::round(b.y() / g) * g);
            c = a + t * (b - a);
        }
        for (int k = 0; k < 2; ++k)
            for (int m = ulps(rng); m != 0; m += m > 0 ? -1 : 1)
                c[k] = std::nextafter(c[k], m > 0 ? INFINITY : -INFINITY);
        const int expected = exact_orientation(a, b, c);
        near_zero += expected == 0;
        ASSERT_EQ(orientation_2d(a, b, c), expected) << n;
    }
    std::cout << "200000 nearly collinear triples agree with rational arithmetic (" << near_zero << " exactly collinear)\n";
}

TEST(Certify, ScalesToTheLargestMesh) {
    // mannequin-devil (26k triangles) as one patch: embedded and certified valid; the border test
    // is the box-intersection sweep, not all pairs.
    CutCase c = disc_case(read_mesh(data("meshes/mannequin-devil.off")));
    split_flat_edges(c.cut, c.input);
    const TexturedMesh tm = TexturedMesh::with_vertex_uvs(c.cut.mesh, embed_patches(c.cut, c.feature_uv));
    const Certificate cert = certify(tm, c.cut.feature_vertex, c.feature_uv);
    EXPECT_TRUE(cert.valid) << cert.flipped << " flipped, " << cert.degenerate << " degenerate";
    EXPECT_GE(cert.triangles, 25888);
}

// ---- ctmap check ----------------------------------------------------------------------------

/// Writes the nefertiti embedding as OBJ plus a features file (pixels on a 512 x 384 image).
struct CheckFiles {
    TempDir dir;
    std::string obj, features;
    TexturedMesh tm;
    std::vector<int> fv;
    std::vector<Vec2> fuv;
};
void write_check_files(CheckFiles& f, bool break_feature) {
    const std::array<Vec2, 3> px{Vec2(51.3, 340.7), Vec2(460.9, 301.1), Vec2(180.2, 40.6)};
    std::array<Vec2, 3> uv;
    for (int i = 0; i < 3; ++i) uv[i] = image_to_uv(px[i], 512, 384);
    CutCase c = disc_case(read_mesh(data("meshes/nefertiti.off")), uv);
    split_flat_edges(c.cut, c.input);
    std::vector<Vec2> map = embed_patches(c.cut, c.feature_uv);
    if (break_feature) map[c.cut.feature_vertex[1]].y() += 1e-6;
    f.tm = TexturedMesh::with_vertex_uvs(c.cut.mesh, map);
    f.fv = c.cut.feature_vertex;
    f.fuv = c.feature_uv;
    f.obj = f.dir / "map.obj";
    f.features = f.dir / "features.json";
    write_obj(f.tm, f.obj);
    nlohmann::json j;
    j["image_size"] = {512, 384};
    const char* names[] = {"a", "b", "c"};
    for (int i = 0; i < 3; ++i)
        j["features"].push_back({{"name", names[i]}, {"vertex", c.cut.feature_vertex[i]}, {"image", {px[i].x(), px[i].y()}}});
    write_file(f.features, j.dump(2));
}

TEST(CheckCommand, ValidMapExitsZero) {
    CheckFiles f;
    write_check_files(f, false);
    const RunResult r = run_ctmap("check " + q(f.obj) + " --features " + q(f.features));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(": valid"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("flipped 0, degenerate 0, feature error 0, border simple"), std::string::npos) << r.out;
    const RunResult js = run_ctmap("check " + q(f.obj) + " --features " + q(f.features) + " --json");
    ASSERT_EQ(js.code, 0) << js.out;
    const nlohmann::json j = nlohmann::json::parse(js.out);
    EXPECT_EQ(j["valid"], true);
    EXPECT_EQ(j["flipped"], 0);
    EXPECT_EQ(j["degenerate"], 0);
    EXPECT_EQ(j["feature_max_error"], 0.0);
    EXPECT_EQ(j["border_simple"], true);
    // Same numbers as the library on the same map.
    const Certificate c = certify(f.tm, f.fv, f.fuv);
    EXPECT_DOUBLE_EQ(j["symmetric_dirichlet"].get<double>(), c.distortion.symmetric_dirichlet);
}

TEST(CheckCommand, BrokenMapExitsOne) {
    CheckFiles f;
    write_check_files(f, true);
    const RunResult r = run_ctmap("check " + q(f.obj) + " --features " + q(f.features) + " --json");
    EXPECT_EQ(r.code, 1) << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["valid"], false);
    EXPECT_NEAR(j["feature_max_error"].get<double>(), 1e-6, 1e-15);
}

TEST(CheckCommand, BadInputExitsTwo) {
    CheckFiles f;
    write_check_files(f, false);
    TempDir d;
    // Missing OBJ, missing features, garbage features, a feature vertex out of range, an OBJ
    // without texture coordinates, no image size at all.
    EXPECT_EQ(run_ctmap("check " + q(d / "none.obj") + " --features " + q(f.features)).code, 2);
    EXPECT_EQ(run_ctmap("check " + q(f.obj) + " --features " + q(d / "none.json")).code, 2);
    write_file(d / "garbage.json", "{\"features\": [");
    EXPECT_EQ(run_ctmap("check " + q(f.obj) + " --features " + q(d / "garbage.json")).code, 2);
    std::string text = read_file(f.features);
    nlohmann::json j = nlohmann::json::parse(text);
    j["features"][0]["vertex"] = 1000000;
    write_file(d / "range.json", j.dump());
    const RunResult r = run_ctmap("check " + q(f.obj) + " --features " + q(d / "range.json"));
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("1000000"), std::string::npos) << r.out;
    write_file(d / "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    nlohmann::json small;
    small["image_size"] = {10, 10};
    small["features"] = {{{"name", "a"}, {"vertex", 0}, {"image", {1, 1}}},
                         {{"name", "b"}, {"vertex", 1}, {"image", {9, 1}}},
                         {{"name", "c"}, {"vertex", 2}, {"image", {1, 9}}}};
    write_file(d / "small.json", small.dump());
    EXPECT_EQ(run_ctmap("check " + q(d / "plain.obj") + " --features " + q(d / "small.json")).code, 2);
    j = nlohmann::json::parse(text);
    j.erase("image_size");
    write_file(d / "nosize.json", j.dump());
    EXPECT_EQ(run_ctmap("check " + q(f.obj) + " --features " + q(d / "nosize.json")).code, 2);
    EXPECT_EQ(run_ctmap("check " + q(f.obj)).code, 2);  // --features is required
}

}  // namespace
}  // namespace ctmap::test
