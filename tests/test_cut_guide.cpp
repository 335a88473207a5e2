// Issue 17, must-show 3: the guided path search (cut/guide_map.h). On a strongly twisted layout
// the surface's shortest paths leave each feature in other directions than its image neighbours
// lie, and later paths wind around earlier ones: three_peaks with 400 features and a twist of 8
// grew to 366,405 faces. The automatic cut gives the surface cut up past its growth limit and
// cuts again with paths short in the guide (the features' biharmonic interpolation); untwisted
// layouts never reach the limit and keep the paper's surface paths.
#include <algorithm>
#include <cstdio>

#include "ctmap/certify/certificate.h"
#include "ctmap/cut/guide_map.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "cut_check.h"
#include "random_features.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// The map stopping after the paper's relaxation with the cut's `guide`, checked and certified.
MapResult certified_map(const TriMesh& mesh, const std::vector<MapFeature>& features, CutOptions::Guide guide,
                        const std::string& what) {
    MapOptions opt;
    opt.cut.guide = guide;
    return certified_paper_map(mesh, features, opt, what);
}

std::vector<MapFeature> twisted(const TriMesh& mesh, double twist) {
    std::mt19937 rng(1);  // bench/hard_layouts twist three_peaks.off 400 TWIST (seed 1)
    return map_features_of(random_features(mesh, tutte_map(mesh), 400, 12, twist, rng));
}

TEST(CutGuide, PinsFeaturesAndPutsTheBorderOnItsSides) {
    const TriMesh mesh = read_mesh(data("meshes/three_peaks.off"));
    const MapResult r = certified_map(mesh, twisted(mesh, 4.0), CutOptions::Guide::off, "three_peaks, twist 4");
    // The input's feature vertices (the cut keeps the input's vertex ids).
    std::vector<int> fv(r.cut.feature_vertex.begin(), r.cut.feature_vertex.end());
    for (int v : fv) ASSERT_LT(v, mesh.num_vertices());
    const std::vector<Vec2> g = guide_map(mesh, fv, r.triangulation);
    ASSERT_EQ(int(g.size()), mesh.num_vertices());
    for (std::size_t i = 0; i < fv.size(); ++i) EXPECT_EQ(g[fv[i]], r.triangulation.points[i]) << "feature " << i;
    // Every border vertex on the segment between the border features around it (1e-12 of the
    // image's size), in order along it.
    std::vector<int> loop = WorkMesh(mesh).border_loop();
    std::vector<int> feature_at(mesh.num_vertices(), -1);
    for (std::size_t i = 0; i < fv.size(); ++i) feature_at[fv[i]] = int(i);
    std::rotate(loop.begin(), std::find_if(loop.begin(), loop.end(), [&](int v) { return feature_at[v] >= 0; }), loop.end());
    loop.push_back(loop.front());
    int checked = 0;
    for (std::size_t start = 0, end = 1; end < loop.size(); ++end) {
        if (feature_at[loop[end]] < 0) continue;
        const Vec2 a = g[loop[start]], d = g[loop[end]] - a;
        double last = 0;
        for (std::size_t j = start + 1; j < end; ++j, ++checked) {
            const Vec2 p = g[loop[j]] - a;
            EXPECT_LE(std::abs(d.x() * p.y() - d.y() * p.x()) / d.norm(), 1e-12) << "border vertex " << loop[j];
            const double t = p.dot(d) / d.squaredNorm();
            EXPECT_GT(t, last) << "border vertex " << loop[j];
            EXPECT_LT(t, 1.0) << "border vertex " << loop[j];
            last = t;
        }
        start = end;
    }
    EXPECT_EQ(checked, int(loop.size()) - 1 - 12) << "every border vertex but the 12 features";
}

TEST(CutGuide, ATwistedLayoutIsCutAgainGuidedAndGrowsLess) {
    const TriMesh mesh = read_mesh(data("meshes/three_peaks.off"));
    // Twist 4: the surface cut stays below its limit, nothing changes.
    const MapResult mild = certified_map(mesh, twisted(mesh, 4.0), CutOptions::Guide::automatic, "twist 4");
    EXPECT_FALSE(mild.cut_stats.guided);
    EXPECT_EQ(mild.cut_stats.guide_restart_faces, 0);
    // Twist 8: the surface cut alone, and the automatic one.
    const std::vector<MapFeature> features = twisted(mesh, 8.0);
    const MapResult surface = certified_map(mesh, features, CutOptions::Guide::off, "twist 8, surface paths");
    const MapResult automatic = certified_map(mesh, features, CutOptions::Guide::automatic, "twist 8, automatic");
    std::printf("three_peaks, 400 features, twist 8: %d faces in; surface paths %d faces out; automatic: restarted at "
                "%d faces, guided %d faces out\n",
                mesh.num_faces(), surface.cut.mesh.num_faces(), automatic.cut_stats.guide_restart_faces,
                automatic.cut.mesh.num_faces());
    EXPECT_FALSE(surface.cut_stats.guided);
    EXPECT_TRUE(automatic.cut_stats.guided);
    EXPECT_GT(automatic.cut_stats.guide_restart_faces, 0);
    EXPECT_LT(automatic.cut_stats.guide_restart_faces, surface.cut.mesh.num_faces());
    EXPECT_LT(automatic.cut.mesh.num_faces(), surface.cut.mesh.num_faces() / 2);
}

}  // namespace
}  // namespace ctmap::test
