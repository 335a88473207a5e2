// The whole pipeline as a library call (map_texture): the nefertiti example and point features.
// Every map is certified by an independent run of the certificate, the cut checked like the cut
// tests check it.
#include "ctmap/errors.h"
#include "ctmap/io/features.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "cut_check.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

std::vector<MapFeature> nefertiti_features(const TriMesh& mesh) {
    FeatureSet fs = read_features(data("features/nefertiti_astronaut.json"));
    resolve_units(fs, 512, 512);
    check_features_on_mesh(fs, mesh, "nefertiti.off");
    return map_features(fs, 512, 512);
}

/// Every feature's UV bitwise equal to its constraint, every UV triangle positive (recomputed here
/// with the same exact predicate, independently of the result's own certificate).
void expect_certified(const MapResult& r, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_TRUE(r.certificate.valid);
    const Certificate again = certify(r.textured(), r.cut.feature_vertex, r.feature_uv);
    EXPECT_TRUE(again.valid);
    EXPECT_EQ(again.flipped, 0);
    EXPECT_EQ(again.degenerate, 0);
    EXPECT_EQ(again.feature_max_error, 0.0);
    for (std::size_t i = 0; i < r.feature_uv.size(); ++i) {
        EXPECT_EQ(r.uv[r.cut.feature_vertex[i]].x(), r.feature_uv[i].x());
        EXPECT_EQ(r.uv[r.cut.feature_vertex[i]].y(), r.feature_uv[i].y());
    }
    int sign = 0;
    for (const Tri& t : r.cut.mesh.faces) {
        const int o = orientation_2d(r.uv[t[0]], r.uv[t[1]], r.uv[t[2]]);
        EXPECT_NE(o, 0);
        if (sign == 0) sign = o;
        EXPECT_EQ(o, sign);
        if (o != sign) break;
    }
}

TEST(Map, NefertitiExampleIsCertifiedAndRefinementLowersDistortion) {
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    const std::vector<MapFeature> features = nefertiti_features(mesh);
    const MapResult r = map_texture(mesh, features);
    expect_certified(r, "nefertiti");
    expect_valid_cut(mesh, r.triangulation, r.cut, "nefertiti");
    EXPECT_LT(r.certificate.distortion.symmetric_dirichlet, r.before_refine.symmetric_dirichlet);
    EXPECT_GT(r.timings_ms.total, 0);
    std::cout << "nefertiti: " << features.size() << " features, " << r.triangulation.triangles.size()
              << " triangles, " << r.cut.mesh.num_faces() << " faces; symmetric Dirichlet "
              << r.before_refine.symmetric_dirichlet << " -> " << r.certificate.distortion.symmetric_dirichlet << "\n";
}

TEST(Map, PointFeaturesBecomeVerticesOnTheSurface) {
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    std::vector<MapFeature> features = nefertiti_features(mesh);
    // Interior features moved to a point inside one of their faces: the map must put exactly
    // that point on the image point.
    int moved = 0;
    std::vector<char> is_border(mesh.num_vertices(), 0);
    for (int v : border_features(mesh, [&] {
             std::vector<int> all(mesh.num_vertices());
             for (int i = 0; i < mesh.num_vertices(); ++i) all[i] = i;
             return all;
         }()))
        is_border[v] = 1;
    for (MapFeature& f : features) {
        if (is_border[f.vertex] || moved == 3) continue;
        for (const Tri& t : mesh.faces) {
            if (t[0] != f.vertex) continue;
            f.point = 0.8 * mesh.positions[t[0]] + 0.15 * mesh.positions[t[1]] + 0.05 * mesh.positions[t[2]];
            f.vertex = -1;
            ++moved;
            break;
        }
    }
    ASSERT_EQ(moved, 3);
    const MapResult r = map_texture(mesh, features);
    EXPECT_EQ(r.point_features, 3);
    expect_certified(r, "nefertiti with point features");
    for (std::size_t i = 0; i < features.size(); ++i) {
        const int v = r.cut.feature_vertex[i];
        if (features[i].vertex >= 0) {
            EXPECT_EQ(v, features[i].vertex);
        } else {
            EXPECT_GE(v, mesh.num_vertices());  // appended: the input's vertex order is kept
            EXPECT_LT((r.cut.mesh.positions[v] - features[i].point).norm(), 1e-12);
        }
    }
    for (int v = 0; v < mesh.num_vertices(); ++v) EXPECT_EQ(r.cut.mesh.positions[v], mesh.positions[v]);
}

TEST(Map, TwoFeaturesAtOneVertexAreRejected) {
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    std::vector<MapFeature> features = nefertiti_features(mesh);
    features.back().vertex = -1;
    features.back().point = mesh.positions[features.front().vertex];
    try {
        naming_file("f.json", [&] { return map_texture(mesh, features); });
        FAIL() << "no error";
    } catch (const BadInput& e) {
        // map_texture names no file (issue 16); naming_file adds the caller's.
        EXPECT_EQ(e.file(), "f.json") << e.what();
        EXPECT_EQ(std::string(e.what()).rfind("f.json: ", 0), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find(features.front().name), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace ctmap::test
