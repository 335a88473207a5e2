// Issue 17, must-show 3: the cut never gives up on a feasible dense layout. Every border vertex of
// nefertiti plus 10,000 3D point features inside its 562 faces (about 18 to a face), imaged by a
// one-to-one map (the barycentric mix of Tutte's embedding), so a valid map exists. Before the
// path spacing followed the distance between a path's ends (CutOptions::reach_spacing_factor),
// this gave "cut: no valid path between features 651 and 7855 after refinement". The map stops
// after the paper's relaxation (the optimiser on the 202 k faces the cut makes is timed by bench/hard_layouts).
#include <cstdio>

#include "ctmap/certify/certificate.h"
#include "ctmap/cut/work_mesh.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "cut_check.h"
#include "random_features.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// `points` random point features inside nefertiti's faces and its 34 border vertices: the cut is
/// valid, the map certified with every feature exact.
void dense_points(int points) {
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    std::mt19937 rng(1);  // bench/hard_layouts points ... 10000 (seed 1)
    const std::vector<MapFeature> features =
        point_features(mesh, tutte_map(mesh), points, int(WorkMesh(mesh).border_loop().size()), rng);
    ASSERT_EQ(features.size(), std::size_t(points) + 34);
    MapOptions opt;
    opt.refine_mode = RefineMode::paper;
    const MapResult r = map_texture(mesh, features, opt);
    const std::string what = "nefertiti, " + std::to_string(features.size()) + " point features";
    // The cut's input: the mesh with the point features inserted as vertices (as map_texture does).
    TriMesh with_points = mesh;
    const std::vector<int> vertex = place_point_features(with_points, features);
    ASSERT_EQ(vertex, r.cut.feature_vertex);
    expect_valid_cut(with_points, r.triangulation, r.cut, what);
    const Certificate cert = certify(r.textured(), r.cut.feature_vertex, r.feature_uv, {false});
    EXPECT_TRUE(cert.valid) << what;
    EXPECT_EQ(cert.flipped, 0) << what;
    EXPECT_EQ(cert.feature_max_error, 0.0) << what;
    std::printf("%s: faces %d -> %d, %d paths, %d Steiner vertices, cut %.0f ms, certificate %s\n", what.c_str(),
                mesh.num_faces(), r.cut.mesh.num_faces(), r.cut_stats.paths, r.cut_stats.steiner_vertices,
                r.timings_ms.paths, cert.valid ? "valid" : "INVALID");
}

// CTest label `long` (scripts/test.sh --long): the 10,000 points.
TEST(CutDenseLong, TenThousandPointFeaturesOnNefertitiGiveACertifiedMap) { dense_points(10000); }

// The same property with 2,000 points (about 4 to a face), in the main suite.
TEST(CutDense, TwoThousandPointFeaturesOnNefertitiGiveACertifiedMap) { dense_points(2000); }


}  // namespace
}  // namespace ctmap::test
