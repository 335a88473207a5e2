// Mesh morphing (issue 14, paper §4): every pair exact, every vertex on both surfaces, the
// target's detail kept, a known correspondence recovered, and bad pair files refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "bad_input_support.h"
#include "ctmap/border_loop.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/morph/morph_meshes.h"
#include "ctmap/morph/morph_quality.h"
#include "ctmap/morph/surface_distance.h"
#include "ctmap/subdivide.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

double diagonal(const TriMesh& m) {
    Eigen::AlignedBox3d box;
    for (const Vec3& p : m.positions) box.extend(p);
    return box.diagonal().norm();
}

// Must-show 1: two real pairs of heads, 11 pairs each.
class MorphRealPairs : public ::testing::TestWithParam<std::array<const char*, 3>> {};

TEST_P(MorphRealPairs, PairsExactVerticesOnBothSurfacesDetailKept) {
    const auto [src, dst, pairs_file] = GetParam();
    const TriMesh source = read_mesh(data(src)), target = read_mesh(data(dst));
    const PairSet pairs = read_pairs(data(pairs_file));
    ASSERT_GE(pairs.pairs.size(), 10u);
    const MorphResult m = morph_meshes(source, target, pairs);
    EXPECT_TRUE(m.target_map.certificate.valid);
    EXPECT_TRUE(m.source_map.certificate.valid);
    const MorphQuality q = measure_morph(m, target);
    std::printf("%s -> %s: %d vertices (%d inserted), pair error %.3g, off target %.3g, off source %.3g of the "
                "diagonal; Hausdorff %.4g vs mean edge %.4g\n",
                src, dst, m.common.mesh.num_vertices(), m.common.inserted, q.pair_error / q.diagonal,
                q.target_off / q.diagonal, q.source_off / diagonal(source), q.hausdorff, q.target_mean_edge);
    EXPECT_LE(q.pair_error, 1e-9 * q.diagonal);
    EXPECT_LE(q.target_off, 1e-9 * q.diagonal);
    EXPECT_LE(q.source_off, 1e-9 * q.diagonal * (1 + m.alignment.block<3, 3>(0, 0).norm()));
    EXPECT_LE(q.hausdorff, q.target_mean_edge);
    // Every input target vertex is in the common mesh at its exact position (the overlay).
    EXPECT_EQ(m.common.inserted + m.common.merged, m.target_map.cut.mesh.num_vertices());
    // The overlay is a disc covering the source's domain once: its UV areas add up to the
    // source map's (each overlay triangle lies in one source triangle, none is left out twice).
    const MeshTopology topo = compute_topology(m.common.mesh);
    EXPECT_TRUE(topo.is_disc) << topo.components << " components, " << topo.border_loops << " border loops, "
                              << topo.non_manifold_edges << " non-manifold edges, Euler " << topo.euler << ", isolated " << topo.isolated_vertices << ", non-manifold vertices " << topo.non_manifold_vertices << ", inconsistent " << topo.inconsistent_edges << ", degenerate " << topo.degenerate_faces << ", duplicated " << topo.duplicated_vertices;
    auto area = [](const std::vector<Vec2>& uv, const std::vector<Tri>& faces) {
        double a = 0;
        for (const Tri& t : faces) {
            const Vec2 e = uv[t[1]] - uv[t[0]], f = uv[t[2]] - uv[t[0]];
            a += 0.5 * std::abs(e.x() * f.y() - e.y() * f.x());
        }
        return a;
    };
    const double domain = area(m.source_map.uv, m.source_map.cut.mesh.faces);
    EXPECT_NEAR(area(m.common.uv, m.common.mesh.faces), domain, 1e-9 * domain);
}

INSTANTIATE_TEST_SUITE_P(
    Heads, MorphRealPairs,
    ::testing::Values(std::array<const char*, 3>{"meshes/nefertiti.off", "meshes/lion-head.off", "pairs/nefertiti_lion-head.json"},
                      std::array<const char*, 3>{"meshes/mannequin-devil.off", "meshes/lion-head.off",
                                                 "pairs/mannequin-devil_lion-head.json"}),
    [](const auto& info) { return info.index == 0 ? std::string("NefertitiToLion") : std::string("MannequinToLion"); });

// Must-show 2: the target is a smooth deformation of the (subdivided) source and the pairs are
// picked through it, so the true correspondence is known: a source point p belongs at f(p).
Vec3 deform(const Vec3& p, double scale) {
    const Vec3 q = p / scale;
    return p + scale * Vec3(0.1 * std::sin(2.0 * q.y()), 0.08 * std::sin(2.5 * q.x()), 0.12 * std::cos(2.0 * (q.x() + q.y())));
}

TEST(MorphKnownTruth, FiftyRandomPairSetsRecoverTheDeformation) {
    const TriMesh source = read_mesh(data("meshes/nefertiti.off"));
    const double scale = diagonal(source);
    TriMesh target = subdivide_midpoint(source, 1);
    for (Vec3& p : target.positions) p = deform(p, scale);
    const std::vector<int> loop = border_loop(source);
    std::vector<int> inner;
    std::vector<bool> on_border(source.positions.size());
    for (int v : loop) on_border[v] = true;
    for (int v = 0; v < source.num_vertices(); ++v)
        if (!on_border[v]) inner.push_back(v);
    std::mt19937 rng(14);
    std::vector<double> means, maxes, border_only_means;
    for (int set = 0; set < 50; ++set) {
        PairSet pairs;
        pairs.path = "set " + std::to_string(set);
        const int nb = 3 + int(rng() % 4), ni = 3 + int(rng() % 12);
        std::vector<int> b(loop.size());
        std::iota(b.begin(), b.end(), 0);
        std::shuffle(b.begin(), b.end(), rng);
        b.resize(nb);
        std::sort(b.begin(), b.end());
        std::vector<int> chosen;
        for (int k : b) chosen.push_back(loop[k]);
        std::vector<int> in = inner;
        std::shuffle(in.begin(), in.end(), rng);
        chosen.insert(chosen.end(), in.begin(), in.begin() + ni);
        for (int v : chosen)
            pairs.pairs.push_back({"v" + std::to_string(v), {v, std::nullopt}, {v, std::nullopt}});
        MorphOptions o;
        o.align = false;  // the truth is in the source's own coordinates
        const MorphResult m = morph_meshes(source, target, pairs, o);
        ASSERT_TRUE(m.source_map.certificate.valid && m.target_map.certificate.valid) << pairs.path;
        double sum = 0, worst = 0;
        for (int v = 0; v < m.common.mesh.num_vertices(); ++v) {
            const double e = (m.common.target_position[v] - deform(m.common.mesh.positions[v], scale)).norm() / scale;
            sum += e;
            worst = std::max(worst, e);
        }
        if (std::getenv("CTMAP_VERBOSE")) {
            int wv = 0;
            double we = 0;
            for (int v = 0; v < m.common.mesh.num_vertices(); ++v) {
                const double e = (m.common.target_position[v] - deform(m.common.mesh.positions[v], scale)).norm() / scale;
                if (e > we) we = e, wv = v;
            }
            std::printf("set %d: %d border + %d interior, mean %.4f max %.4f at vertex %d (uv %.3f %.3f, %s)\n", set, nb, ni,
                        sum / m.common.mesh.num_vertices(), worst, wv, m.common.uv[wv].x(), m.common.uv[wv].y(),
                        wv < m.common.source_vertices ? "source vertex" : "inserted");
        }
        means.push_back(sum / m.common.mesh.num_vertices());
        maxes.push_back(worst);
        for (std::size_t i = 0; i < pairs.pairs.size(); ++i)  // the pairs themselves: exact
            EXPECT_LE((m.common.target_position[m.pair_vertex[i]] - target.positions[chosen[i]]).norm(), 1e-12 * scale);
    }
    const double mean = std::accumulate(means.begin(), means.end(), 0.0) / means.size();
    const double mean_max = std::accumulate(maxes.begin(), maxes.end(), 0.0) / maxes.size();
    std::printf("50 random pair sets (3-6 border + 3-14 interior pairs), error against the true correspondence, "
                "fraction of the diagonal: mean %.4f (worst set %.4f), max %.4f (mean over sets %.4f)\n",
                mean, *std::max_element(means.begin(), means.end()), *std::max_element(maxes.begin(), maxes.end()),
                mean_max);
    // Regression bounds (measured 0.0164 and 0.222 when written): the correspondence is pinned at
    // the pairs only, and the two maps minimise distortion of two differently stretched surfaces.
    EXPECT_LT(mean, 0.025);
    EXPECT_LT(*std::max_element(maxes.begin(), maxes.end()), 0.35);
}

// Pairs given as 3D points: inserted on both surfaces, and the morphed point lands on the target point.
TEST(MorphPoints, PointPairsLandOnTheirTargetPoints) {
    const TriMesh source = read_mesh(data("meshes/nefertiti.off"));
    const TriMesh target = subdivide_midpoint(source, 1);  // the same surface, other connectivity
    const double diag = diagonal(source);
    PairSet pairs;
    pairs.path = "points";
    for (int v : {200, 153, 1, 295, 87}) pairs.pairs.push_back({"v" + std::to_string(v), {v, std::nullopt}, {v, std::nullopt}});
    std::vector<Vec3> points;
    for (int f : {100, 300, 450}) {
        const Tri& t = source.faces[f];
        const Vec3 p = (0.2 * source.positions[t[0]] + 0.3 * source.positions[t[1]] + 0.5 * source.positions[t[2]]);
        points.push_back(p);
        pairs.pairs.push_back({"f" + std::to_string(f), {-1, p}, {-1, p}});
    }
    MorphOptions o;
    o.align = false;
    const MorphResult m = morph_meshes(source, target, pairs, o);
    for (std::size_t k = 0; k < points.size(); ++k) {
        const int v = m.pair_vertex[5 + k];
        EXPECT_LE((m.common.mesh.positions[v] - points[k]).norm(), 1e-9 * diag) << pairs.pairs[5 + k].name;
        EXPECT_LE((m.common.target_position[v] - points[k]).norm(), 1e-9 * diag) << pairs.pairs[5 + k].name;
    }
    // The same surface on both sides: every vertex's two positions are on one surface.
    const SurfaceDistance d(source);
    double worst = 0;
    for (const Vec3& p : m.common.target_position) worst = std::max(worst, d.distance(p));
    EXPECT_LE(worst, 1e-9 * diag);
}

// Must-show 4: bad pair files and meshes, through the real program: exit 2, the pairs named, no output.
std::string pairs_json(const std::string& pairs) { return R"({"units": "mesh", "pairs": [)" + pairs + "]}"; }
// nefertiti's border vertices 200, 153, 1, 295 in the order of its border.
const char* const kBorder3 = R"({"name": "b0", "source": {"vertex": 200}, "target": {"vertex": 200}},
    {"name": "b1", "source": {"vertex": 153}, "target": {"vertex": 153}},
    {"name": "b2", "source": {"vertex": 1}, "target": {"vertex": 1}})";

CliRun morph_run(const TempDir& d, const std::string& pairs, std::vector<std::string> keywords,
                 const std::string& source = data("meshes/nefertiti.off")) {
    write_file(d / "p.json", pairs_json(pairs));
    return {"morph " + q(source) + " " + q(data("meshes/nefertiti.off")) + " " + q(d / "p.json") + " -o " +
                q(d / "out.glb") + " --strip " + q(d / "strip.png"),
            d / "p.json", std::move(keywords)};
}

const Case kMorphCases[] = {
    {"UnknownVertex", [](const TempDir& d) {
         return morph_run(d, std::string(kBorder3) + R"(, {"name": "nose", "source": {"vertex": 99999}, "target": {"vertex": 87}})",
                          {"pair 'nose'", "99999", "does not exist"});
     }},
    {"DuplicateNames", [](const TempDir& d) {
         return morph_run(d, std::string(kBorder3) + R"(, {"name": "b0", "source": {"vertex": 87}, "target": {"vertex": 87}})",
                          {"two pairs are named 'b0'"});
     }},
    {"BorderPairsInAnotherOrder", [](const TempDir& d) {
         return morph_run(d, R"({"name": "b0", "source": {"vertex": 200}, "target": {"vertex": 200}},
             {"name": "b1", "source": {"vertex": 153}, "target": {"vertex": 1}},
             {"name": "b2", "source": {"vertex": 1}, "target": {"vertex": 153}})",
                          {"different cyclic order", "'b0', 'b1', 'b2'", "'b0', 'b2', 'b1'"});
     }},
    // A name from the file is quoted printable and cut (io/printable.h): an escape sequence and
    // 200 bytes become '?[31m' and 59 more bytes with "...".
    {"LongNameWithAnEscapeSequence", [](const TempDir& d) {
         const std::string name = "\\u001b[31m" + std::string(200, 'x');
         return morph_run(d, std::string(kBorder3) + R"(, {"name": ")" + name + R"(", "source": {"vertex": 87}, "target": {"vertex": 87}},
             {"name": ")" + name + R"(", "source": {"vertex": 88}, "target": {"vertex": 88}})",
                          {"two pairs are named '?[31m" + std::string(59, 'x') + "...'"});
     }},
    {"PointOffTheSurface", [](const TempDir& d) {
         return morph_run(d, std::string(kBorder3) + R"(, {"name": "nose", "source": {"point": [0.1, 0.2, 5]}, "target": {"vertex": 87}})",
                          {"pair 'nose'", "off the surface"});
     }},
    {"PairOnOneBorderOnly", [](const TempDir& d) {
         return morph_run(d, std::string(kBorder3) + R"(, {"name": "rim", "source": {"vertex": 295}, "target": {"vertex": 87}})",
                          {"pair 'rim'", "source's border but not on the target's"});
     }},
    {"TwoBorderPairs", [](const TempDir& d) {
         return morph_run(d, R"({"name": "b0", "source": {"vertex": 200}, "target": {"vertex": 200}},
             {"name": "b1", "source": {"vertex": 153}, "target": {"vertex": 153}},
             {"name": "nose", "source": {"vertex": 87}, "target": {"vertex": 87}})",
                          {"only 2 pair(s)", "'b0', 'b1'", "at least 3 border pairs"});
     }},
    {"ClosedMesh", [](const TempDir& d) {
         write_file(d / "tet.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
         CliRun r = morph_run(d, kBorder3, {"closed", "ctmap morph maps discs"}, d / "tet.off");
         r.names_file = d / "tet.off";
         return r;
     }},
    {"NoPairsArray", [](const TempDir& d) {
         write_file(d / "p.json", R"({"features": []})");
         return CliRun{"morph " + q(data("meshes/nefertiti.off")) + " " + q(data("meshes/nefertiti.off")) + " " +
                           q(d / "p.json") + " -o " + q(d / "out.glb"),
                       d / "p.json", {"\"pairs\" array"}};
     }},
};

class BadInputMorph : public ::testing::TestWithParam<Case> {};

TEST_P(BadInputMorph, IsRejectedWithNothingWritten) {
    TempDir dir;
    const CliRun run = GetParam().make(dir);
    expect_rejected(dir, run);
    EXPECT_FALSE(std::filesystem::exists(dir / "strip.png"));
}

INSTANTIATE_TEST_SUITE_P(Pairs, BadInputMorph, ::testing::ValuesIn(kMorphCases),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace ctmap::test
