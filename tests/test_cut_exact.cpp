// The cut with exact geodesics (CutOptions::exact_geodesics, issue 3): paths from CGAL's
// Surface_mesh_shortest_path, inserted like the approximate ones; where a geodesic breaks the path
// rules the approximate search stands in. The cuts must be as valid as the approximate ones
// (cut_check.h), and the maps built on them certified.
#include <chrono>
#include <initializer_list>

#include "ctmap/certify/certificate.h"
#include "ctmap/io/features.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "cut_check.h"
#include "random_features.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

void expect_certified(const MapResult& r, const std::string& what) {
    const Certificate cert = certify(r.textured(), r.cut.feature_vertex, r.feature_uv, {false});
    EXPECT_TRUE(cert.valid) << what;
    EXPECT_EQ(cert.flipped, 0) << what;
    EXPECT_EQ(cert.degenerate, 0) << what;
    EXPECT_EQ(cert.feature_max_error, 0.0) << what;
}

MapOptions exact_options() {
    MapOptions opt;
    opt.cut.exact_geodesics = true;
    return opt;
}

TEST(CutExact, NefertitiExample) {
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    FeatureSet fs = read_features(data("features/nefertiti_astronaut.json"));
    resolve_units(fs, 512, 512);
    const MapResult r = map_texture(mesh, map_features(fs, 512, 512), exact_options());
    expect_valid_cut(mesh, r.triangulation, r.cut, "nefertiti, exact geodesics");
    expect_certified(r, "nefertiti, exact geodesics");
    const CutStats& s = r.cut_stats;
    EXPECT_EQ(s.exact_paths + s.exact_rejected, s.paths);
    // Most geodesics between neighbouring features are valid paths as they are: the option must
    // really use them, not fall back everywhere.
    EXPECT_GE(s.exact_paths, s.paths / 2);
    std::cout << "nefertiti, exact geodesics: " << s.paths << " paths, " << s.exact_paths << " exact, "
              << s.exact_rejected << " replaced by the approximate search; length " << s.path_length << "\n";
}

// Each exact path builds CGAL's sequence tree on the whole current mesh (0.1-0.7 s per path on
// mushroom and lion-head): the cases stay on the smaller meshes.
void random_feasible_sets(std::initializer_list<RandomSetCase> cases) {
    int paths = 0, exact = 0;
    for (const RandomSetCase& k : cases) {
        const TriMesh mesh = read_mesh(data(std::string("meshes/") + k.mesh));
        std::mt19937 rng(k.seed);
        const RandomFeatures rf = random_features(mesh, tutte_map(mesh), k.features, 8, k.twist, rng);
        const std::vector<MapFeature> features = map_features_of(rf);
        const std::string what = std::string(k.mesh) + ", " + std::to_string(rf.vertex.size()) + " features, twist " +
                                 std::to_string(k.twist) + ", exact geodesics";
        MapResult r;
        const auto start = std::chrono::steady_clock::now();
        try {
            r = map_texture(mesh, features, exact_options());
        } catch (const std::exception& e) {
            ADD_FAILURE() << what << ": " << e.what();
            continue;
        }
        expect_valid_cut(mesh, r.triangulation, r.cut, what);
        expect_certified(r, what);
        EXPECT_EQ(r.cut_stats.exact_paths + r.cut_stats.exact_rejected, r.cut_stats.paths) << what;
        paths += r.cut_stats.paths;
        exact += r.cut_stats.exact_paths;
        std::cout << what << ": " << r.cut_stats.paths << " paths, " << r.cut_stats.exact_paths << " exact, "
                  << r.cut_stats.exact_rejected << " approximate instead ("
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s)\n";
    }
    EXPECT_GE(exact, paths / 2);
}

// The larger sets carry the CTest label `long` (scripts/test.sh --long).
TEST(CutExactLong, RandomFeasibleSets) {
    random_feasible_sets({{"nefertiti.off", 40, 3.0, 12}, {"nefertiti.off", 60, 1.5, 17}, {"mushroom.off", 12, 2.0, 14}});
}

// The same property on two smaller sets, in the main suite.
TEST(CutExact, RandomFeasibleSets) {
    random_feasible_sets({{"nefertiti.off", 20, 0.5, 11}, {"three_peaks.off", 30, 1.0, 13}});
}

}  // namespace
}  // namespace ctmap::test
