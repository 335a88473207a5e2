// The coarse-to-fine path search inside the cut (PathSearchOptions): a path searched in the
// corridor of a coarse path must be nearly as short as the whole fine graph's, also where earlier
// paths and blocked vertices narrow the way (GeodesicAccuracy checks it on an empty mesh only).
// Each case is cut twice, with the corridor for every path and with none; both cuts must be valid
// (cut_check.h) and their maps certified, the corridor must really be used, and the total path
// length may grow by at most 2%.
#include <initializer_list>

#include "ctmap/certify/certificate.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "cut_check.h"
#include "random_features.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

void check_corridor(std::initializer_list<RandomSetCase> cases) {
    for (const RandomSetCase& k : cases) {
        const TriMesh mesh = read_mesh(data(std::string("meshes/") + k.mesh));
        std::mt19937 rng(k.seed);
        const RandomFeatures rf = random_features(mesh, tutte_map(mesh), k.features, 8, k.twist, rng);
        const std::vector<MapFeature> features = map_features_of(rf);
        const std::string what = std::string(k.mesh) + ", " + std::to_string(rf.vertex.size()) + " features";
        MapOptions corridor, whole;
        corridor.cut.corridor_min_distance = 0;  // every path through a corridor
        whole.cut.corridor_rings = 0;            // every path in the whole graph
        MapResult rc, rw;
        try {
            rc = map_texture(mesh, features, corridor);
            rw = map_texture(mesh, features, whole);
        } catch (const std::exception& e) {
            ADD_FAILURE() << what << ": " << e.what();
            continue;
        }
        for (const MapResult* r : {&rc, &rw}) {
            expect_valid_cut(mesh, r->triangulation, r->cut, what);
            const Certificate cert = certify(r->textured(), r->cut.feature_vertex, r->feature_uv);
            EXPECT_TRUE(cert.valid) << what;
            EXPECT_EQ(cert.feature_max_error, 0.0) << what;
        }
        const CutStats &c = rc.cut_stats, &w = rw.cut_stats;
        EXPECT_EQ(w.corridor_paths + w.corridor_misses, 0) << what;
        EXPECT_EQ(c.corridor_paths + c.corridor_misses, c.paths) << what;
        EXPECT_GE(c.corridor_paths, c.paths * 9 / 10) << what << ": the corridor is hardly used";
        const double ratio = c.path_length / w.path_length;
        EXPECT_LE(ratio, 1.02) << what;
        EXPECT_GE(ratio, 0.98) << what;  // the cuts differ after the first differing path
        std::cout << what << ": " << c.paths << " paths, " << c.corridor_paths << " in the corridor, "
                  << c.corridor_misses << " missed; total length corridor/whole " << ratio << "\n";
    }
}

// The two larger meshes (16-25 k faces) carry the CTest label `long` (scripts/test.sh --long).
TEST(CutLong, CorridorPathsAreNearlyAsShortAsWholeGraphPaths) {
    check_corridor({{"lion-head.off", 50, 1.0, 21}, {"mannequin-devil.off", 60, 2.0, 22}});
}

// The same property on the smaller meshes, in the main suite.
TEST(Cut, CorridorPathsAreNearlyAsShortAsWholeGraphPaths) {
    check_corridor({{"mushroom.off", 80, 3.0, 23}, {"three_peaks.off", 40, 1.5, 24}});
}

}  // namespace
}  // namespace ctmap::test
