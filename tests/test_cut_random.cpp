// Random feasible feature sets through the whole pipeline (issue 3 must-show 1 and 3, issue 4
// must-show 1): features that are the images of mesh vertices under a known one-to-one map of the
// disc (Tutte's embedding, then a twist of up to a full turn), 3 to 300 of them, some mirrored, on
// the real meshes. Every case must give a valid cut (cut_check.h) and a certified map (0 flipped,
// feature error exactly 0); the fallback's statistics are printed. One test per mesh so that
// CTest runs them side by side. CTMAP_VERBOSE=1 prints every case; CTMAP_CASE=k runs case k
// alone and prints its slow paths.
#include <chrono>

#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "cut_check.h"
#include "random_features.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

struct Plan {
    const char* mesh;
    int cases;
    int max_features;
    double max_twist;  ///< radians
    /// Every this many cases (from case 0) also runs the distortion optimiser; the others stop
    /// after the paper's relaxation, so that the suite stays short.
    int isometric_every = 5;
};

struct Totals {
    int cases = 0, valid = 0, fired_cases = 0, fired = 0, steiner = 0, paths = 0;
    long faces_in = 0, faces_out = 0;
};

Totals run_plan(const Plan& plan, std::uint32_t seed) {
    Totals t;
    std::mt19937 rng(seed);
    const TriMesh mesh = read_mesh(data(std::string("meshes/") + plan.mesh));
    const std::vector<Vec2> tutte = tutte_map(mesh);
    for (int c = 0; c < plan.cases; ++c) {
        // Feature counts spread log-uniformly so that small and large sets are both common.
        const double lf = std::uniform_real_distribution<double>(std::log(3.0), std::log(plan.max_features + 0.5))(rng);
        const int total = c == 0 ? 3 : c == 1 ? plan.max_features : int(std::exp(lf));
        std::uniform_int_distribution<int> border_d(3, std::max(3, std::min(40, total / 3 + 3)));
        const int nb = std::min(total, border_d(rng));
        // Strong twists with many features make the greedy cut wind paths around each other and
        // grow the mesh a thousandfold (three_peaks, 234 features, twist 5.1: 3.7k -> 5M faces,
        // valid but minutes): above 80 features the twist is scaled down, so that every case runs
        // in seconds. Strong twists are still tested with up to 80 features.
        const double twist =
            std::uniform_real_distribution<double>(0.0, plan.max_twist * std::min(1.0, 80.0 / total))(rng);
        const bool mirror = c % 7 == 3;
        const RandomFeatures rf = random_features(mesh, tutte, total, nb, twist, rng, mirror);
        const std::string what = std::string(plan.mesh) + " case " + std::to_string(c) + " (" +
                                 std::to_string(rf.vertex.size()) + " features, " + std::to_string(nb) +
                                 " on the border, twist " + std::to_string(twist) + (mirror ? ", mirrored" : "") + ")";
        const std::vector<MapFeature> features = map_features_of(rf);
        if (const char* only = std::getenv("CTMAP_CASE"); only && std::atoi(only) != c) continue;  // one case alone
        ++t.cases;
        if (std::getenv("CTMAP_VERBOSE")) std::cout << what << " ..." << std::endl;
        MapResult r;
        try {
            MapOptions opt;
            opt.refine_mode = c % plan.isometric_every == 0 ? RefineMode::isometric : RefineMode::paper;
            auto last = std::chrono::steady_clock::now();
            if (std::getenv("CTMAP_CASE"))  // slow-path hunting: the paths that take over 0.2 s
                opt.progress = [&](const std::string& stage, int done, int total) {
                    const auto now = std::chrono::steady_clock::now();
                    const double s = std::chrono::duration<double>(now - last).count();
                    if (s > 0.2) std::cout << "  " << stage << " " << done << "/" << total << ": " << s << " s" << std::endl;
                    last = now;
                };
            r = map_texture(mesh, features, opt);
        } catch (const std::exception& e) {
            ADD_FAILURE() << what << ": " << e.what();
            continue;
        }
        EXPECT_EQ(r.triangulation.mirrored, mirror) << what;
        expect_valid_cut(mesh, r.triangulation, r.cut, what);
        // The certificate again, from scratch, on the map as it would be written.
        const Certificate cert = certify(r.textured(), r.cut.feature_vertex, r.feature_uv, {false});
        EXPECT_TRUE(cert.valid) << what;
        EXPECT_EQ(cert.flipped, 0) << what;
        EXPECT_EQ(cert.feature_max_error, 0.0) << what;
        if (c % plan.isometric_every == 0 && !r.isometric_stats.energy.empty()) {
            const IsometricStats& is = r.isometric_stats;
            EXPECT_LE(is.energy_after(), is.energy_before()) << what;
            // Converged, or stopped for a reason the report names (BENCHMARKS.md counts them).
            EXPECT_TRUE(is.converged || is.stop == "iterations" || is.stop == "border contact" || is.stop == "no descent step" ||
                        is.stop == "stalled")
                << what << ": " << is.stop;
        }
        t.valid += cert.valid;
        t.fired_cases += r.cut_stats.fallback_fired > 0;
        t.fired += r.cut_stats.fallback_fired;
        t.steiner += r.cut_stats.steiner_vertices;
        t.paths += r.cut_stats.paths;
        t.faces_in += mesh.num_faces();
        t.faces_out += r.cut.mesh.num_faces();
        if (std::getenv("CTMAP_VERBOSE"))
            std::cout << what << ": " << r.cut_stats.paths << " paths, " << r.cut.mesh.num_faces() << " faces, fallback "
                      << r.cut_stats.fallback_fired << ", Steiner " << r.cut_stats.steiner_vertices << ", "
                      << int(r.timings_ms.total) << " ms" << std::endl;
    }
    std::cout << plan.mesh << ": " << t.cases << " random feasible cases, " << t.valid << " certified valid; "
              << t.paths << " interior paths; fallback fired on " << t.fired << " path(s) in " << t.fired_cases
              << " case(s), adding " << t.steiner << " Steiner vertices; faces " << t.faces_in << " -> " << t.faces_out
              << " in all\n";
    EXPECT_EQ(t.valid, t.cases);
    return t;
}

// 250 cases in all (issue 3 asks for at least 200), split so that each test takes a similar time.
// Up to 300 features on the meshes with a few thousand faces, up to 60 on the larger ones.
TEST(RandomFeasible, Nefertiti) { run_plan({"nefertiti.off", 110, 60, 2 * M_PI}, 1); }
TEST(RandomFeasible, ThreePeaks) { run_plan({"three_peaks.off", 50, 300, 2 * M_PI}, 2); }
TEST(RandomFeasible, Mushroom) { run_plan({"mushroom.off", 50, 300, 2 * M_PI}, 3); }
// The two larger meshes carry the CTest label `long` (scripts/test.sh --long); the three above check
// the same in the main suite.
// The distortion optimiser runs on 22 + 10 + 10 + 3 + 2 = 47 of them, twists up to 2 pi.
TEST(RandomFeasibleLong, LionHead) { run_plan({"lion-head.off", 24, 60, 2 * M_PI, 10}, 4); }
TEST(RandomFeasibleLong, MannequinDevil) { run_plan({"mannequin-devil.off", 16, 60, 2 * M_PI, 8}, 5); }

}  // namespace
}  // namespace ctmap::test
