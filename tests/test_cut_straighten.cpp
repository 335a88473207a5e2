// Issue 17, must-show 3: paths straightened inside the input faces they cross
// (cut/straighten_path.h). Without it, a path beside earlier ones got a vertex on every edge of
// the strip between them, and the strips' vertex counts added up path after path: three_peaks
// with 400 features and a twist of 8 grew past 1.8 million faces and did not finish in 420 s.
// The twisted layout here (twist 4, the test's time budget) is cut with and without it; both cuts
// must pass the independent cut checks and the map the certificate, and the straightened one
// must bend only where a path crosses an input edge.
#include <cstdio>
#include <set>

#include "ctmap/certify/certificate.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "cut_check.h"
#include "random_features.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// The map of `features` stopping after the paper's relaxation, with the cut checked and the
/// map certified.
MapResult certified_map(const TriMesh& mesh, const std::vector<MapFeature>& features, bool straighten,
                        const std::string& what) {
    MapOptions opt;
    opt.cut.straighten = straighten;
    MapResult r = certified_paper_map(mesh, features, opt, what);
    // Straightening leaves removed vertices without faces: the output must hold none.
    std::vector<char> used(r.cut.mesh.num_vertices(), 0);
    for (const Tri& t : r.cut.mesh.faces)
        for (int v : t) used[v] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << what << ": a vertex no face uses";
    return r;
}

TEST(CutStraighten, TwistedPathsBendOnlyWhereTheyCrossInputEdges) {
    const TriMesh mesh = read_mesh(data("meshes/three_peaks.off"));
    std::mt19937 rng(1);  // bench/hard_layouts twist ... 400 4 (seed 1)
    const std::vector<MapFeature> features = map_features_of(random_features(mesh, tutte_map(mesh), 400, 12, 4.0, rng));
    const MapResult bent = certified_map(mesh, features, false, "three_peaks, twist 4, not straightened");
    const MapResult straight = certified_map(mesh, features, true, "three_peaks, twist 4, straightened");
    const CutStats& s = straight.cut_stats;
    std::printf("three_peaks, 400 features, twist 4: faces %d -> %d not straightened, %d straightened "
                "(%d vertices on input edges, %d inside input faces, %d straightened away, %d runs kept)\n",
                mesh.num_faces(), bent.cut.mesh.num_faces(), straight.cut.mesh.num_faces(), s.vertices_on_input_edges,
                s.vertices_inside_faces, s.straightened_vertices, s.kept_runs);
    // Most runs inside a face go straight; what stays inside faces is a small share.
    EXPECT_GT(s.straightened_vertices, 0);
    EXPECT_LE(s.vertices_inside_faces, s.vertices_on_input_edges / 20)
        << "more than 5% of the added vertices are bends inside input faces";
    EXPECT_EQ(bent.cut_stats.straightened_vertices, 0);
    EXPECT_GT(bent.cut_stats.vertices_inside_faces, s.vertices_inside_faces);
    EXPECT_LT(straight.cut.mesh.num_faces(), bent.cut.mesh.num_faces());
}

}  // namespace
}  // namespace ctmap::test
