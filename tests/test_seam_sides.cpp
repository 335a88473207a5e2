// Issue 40: seams that keep every chart's features on its side. The layouts are images of
// one-to-one maps (tests/seam_cases.h), so each has a valid map; ctmap must find seams through
// the seam features that leave every interior feature on its chart's side, and map them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "ctmap/cut/chart_regions.h"
#include "ctmap/cut/seam_guide.h"
#include "ctmap/errors.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/read_mesh.h"
#include "seam_cases.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

using json = nlohmann::json;
constexpr int kSize = 512;  // every chart's image, in pixels

/// The layout as a charts features file (DESIGN §3: pixels, y down).
json charts_json(const SeamCase& sc) {
    json j;
    j["units"] = "pixels";
    for (const ChartInput& ch : sc.charts) {
        json c;
        c["name"] = ch.name;
        c["image_size"] = {kSize, kSize};
        c["features"] = json::array();
        for (const MapFeature& f : ch.features)
            c["features"].push_back({{"name", f.name}, {"vertex", f.vertex}, {"image", {f.uv.x() * kSize, (1 - f.uv.y()) * kSize}}});
        c["border"] = ch.border;
        j["charts"].push_back(c);
    }
    return j;
}

/// The outlines chart_regions takes for the layout.
std::vector<ChartOutline> outlines_of(const SeamCase& sc) {
    std::vector<ChartOutline> out;
    for (const ChartInput& ch : sc.charts) {
        ChartOutline o;
        o.name = ch.name;
        std::vector<Vec2> polygon;
        for (const MapFeature& f : ch.features) {
            if (std::find(ch.border.begin(), ch.border.end(), f.name) != ch.border.end()) {
                o.border.push_back(f.vertex), o.border_names.push_back(f.name), polygon.push_back(f.uv);
            } else {
                o.interior.push_back(f.vertex), o.interior_names.push_back(f.name);
            }
        }
        double area = 0;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const Vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
            area += a.x() * b.y() - a.y() * b.x();
        }
        o.image_ccw = area > 0;
        out.push_back(o);
    }
    return out;
}

/// The seams' validity conditions and sides, from the regions alone: each piece joins its two
/// border features along mesh edges through free interior vertices, no two pieces share an inner
/// vertex, and every interior feature lies in a face of its own chart.
void expect_valid_seams(const TriMesh& mesh, const std::vector<ChartOutline>& outlines, const ChartRegions& r) {
    std::set<int> features, inner;
    for (const ChartOutline& o : outlines) features.insert(o.border.begin(), o.border.end()), features.insert(o.interior.begin(), o.interior.end());
    std::set<std::uint64_t> edges;
    for (const Tri& t : mesh.faces)
        for (int k = 0; k < 3; ++k) edges.insert(edge_key(t[k], t[(k + 1) % 3]));
    for (const std::vector<int>& piece : r.seams) {
        ASSERT_GE(piece.size(), 2u);
        EXPECT_TRUE(features.count(piece.front()) && features.count(piece.back()));
        for (std::size_t i = 0; i + 1 < piece.size(); ++i) EXPECT_TRUE(edges.count(edge_key(piece[i], piece[i + 1])));
        for (std::size_t i = 1; i + 1 < piece.size(); ++i) {
            EXPECT_FALSE(features.count(piece[i])) << "a seam passes through a feature";
            EXPECT_TRUE(inner.insert(piece[i]).second) << "two seam pieces share vertex " << piece[i];
        }
    }
    for (std::size_t c = 0; c < outlines.size(); ++c)
        for (std::size_t i = 0; i < outlines[c].interior.size(); ++i) {
            const int v = outlines[c].interior[i];
            for (int f = 0; f < mesh.num_faces(); ++f)
                for (int k : mesh.faces[f])
                    if (k == v) EXPECT_EQ(r.face_chart[f], int(c)) << outlines[c].interior_names[i] << " outside its chart";
        }
}

/// Tally of a sweep.
struct Sweep {
    int sets = 0, mapped = 0, rerouted_sets = 0, rerouted_pieces = 0;
};

/// One layout through the real program: `ctmap map`, then `ctmap check` of what it wrote.
void map_and_check(const std::string& mesh_path, const SeamCase& sc, Sweep& tally) {
    TempDir dir;
    write_file(dir / "charts.json", charts_json(sc).dump());
    const RunResult m = run_ctmap("map " + q(mesh_path) + " " + q(dir / "charts.json") + " -o " + q(dir / "map.obj") +
                                  " --report " + q(dir / "report.json") + " -q");
    ++tally.sets;
    ASSERT_EQ(m.code, 0) << m.out;
    const RunResult k = run_ctmap("check " + q(dir / "map.obj") + " --features " + q(dir / "charts.json"));
    ASSERT_EQ(k.code, 0) << k.out;
    ASSERT_NE(k.out.find("valid"), std::string::npos) << k.out;
    const json report = json::parse(read_file(dir / "report.json"));
    const int rerouted = report["counts"]["seam_pieces_rerouted"].get<int>();
    ++tally.mapped;
    tally.rerouted_sets += rerouted > 0;
    tally.rerouted_pieces += rerouted;
}

/// The two kinds of layout the sweeps draw: plane-cut two-chart layouts on closed meshes, or one
/// chart on a stretched geodesic disc and the rest in no chart (meshes with border loops or handles).
enum class Layout { plane_cut, disc_chart };

/// The next layout of `kind` on `mesh`, or nullopt if 500 draws find none.
std::optional<SeamCase> draw_layout(const TriMesh& mesh, Layout kind, std::mt19937& rng) {
    std::optional<SeamCase> sc;
    for (int tries = 0; !sc && tries < 500; ++tries)
        sc = kind == Layout::plane_cut ? plane_two_chart_case(mesh, rng) : disc_chart_case(mesh, rng);
    return sc;
}

/// Each sweep's own random sequence.
std::mt19937 layout_rng(Layout kind) { return std::mt19937(kind == Layout::plane_cut ? 40 : 41); }

/// `per_mesh[i]` layouts of `kind` on each mesh, every one mapped and checked.
Sweep sweep(Layout kind, const std::vector<std::pair<const char*, int>>& per_mesh) {
    const char* what = kind == Layout::plane_cut ? "two-chart" : "one-chart";
    Sweep all;
    for (const auto& [name, count] : per_mesh) {
        const std::string path = data(std::string("meshes/") + name + ".off");
        const TriMesh mesh = read_mesh(path);
        std::mt19937 rng = layout_rng(kind);
        Sweep here;
        for (int s = 0; s < count; ++s) {
            const std::optional<SeamCase> sc = draw_layout(mesh, kind, rng);
            if (!sc) {
                ADD_FAILURE() << name << (kind == Layout::plane_cut ? ": no plane cuts it into two discs" : ": no disc found");
                break;
            }
            SCOPED_TRACE(std::string(name) + " set " + std::to_string(s) + ", " + std::to_string(sc->seam_features) +
                         " seam features");
            map_and_check(path, *sc, here);
        }
        std::printf("%s: %d of %d %s layouts mapped and checked; %d needed seams re-routed (%d pieces)\n", name,
                    here.mapped, here.sets, what, here.rerouted_sets, here.rerouted_pieces);
        all.sets += here.sets, all.mapped += here.mapped, all.rerouted_sets += here.rerouted_sets;
        all.rerouted_pieces += here.rerouted_pieces;
    }
    std::printf("%d of %d %s layouts mapped and checked; %d needed seams re-routed (%d pieces)\n", all.mapped,
                all.sets, what, all.rerouted_sets, all.rerouted_pieces);
    EXPECT_EQ(all.mapped, all.sets);
    return all;
}

int count_from_env(const char* var, int fallback) { return std::getenv(var) ? std::atoi(std::getenv(var)) : fallback; }

/// Must-show 1: 300 plane-cut layouts on closed meshes (CTest label `long`; CTMAP_SEAM_SETS=N per
/// mesh for another count).
TEST(SeamsLong, PlaneCutTwoChartLayoutsAreAllMapped) {
    const int n = count_from_env("CTMAP_SEAM_SETS", 0);
    sweep(Layout::plane_cut, {{"cow", n ? n : 80}, {"homer", n ? n : 80}, {"bull", n ? n : 80}, {"bunny00", n ? n : 60}});
}

/// Must-show 2: 120 one-chart layouts on meshes with several border loops or a handle.
TEST(SeamsLong, DiscChartAndTheRestAreAllMapped) {
    const int n = count_from_env("CTMAP_SEAM_SETS", 40);
    sweep(Layout::disc_chart, {{"head", n}, {"holes", n}, {"elk", n}});
}

/// The same in the main suite: the first sets of each sweep, and at least one of them needs a
/// seam re-routed (else this would not test the re-routing).
TEST(Seams, TheFirstPlaneCutAndDiscLayoutsAreMapped) {
    const Sweep a = sweep(Layout::plane_cut, {{"cow", 6}, {"homer", 4}});
    const Sweep b = sweep(Layout::disc_chart, {{"head", 3}, {"holes", 3}});
    EXPECT_GT(a.rerouted_sets + b.rerouted_sets, 0);
}

/// The seams themselves on plane-cut layouts: through the seam features, simple, disjoint, every
/// interior feature in its chart's region; a layout with no misplaced feature keeps the
/// shortest pieces (nothing re-routed).
TEST(Seams, ReRoutedSeamsKeepTheirValidityConditions) {
    const TriMesh mesh = read_mesh(data("meshes/homer.off"));
    std::mt19937 rng(42);
    int rerouted = 0, sets = 0;
    for (int s = 0; s < 40; ++s) {
        std::optional<SeamCase> sc;
        for (int tries = 0; !sc && tries < 500; ++tries) sc = plane_two_chart_case(mesh, rng);
        ASSERT_TRUE(sc);
        const std::vector<ChartOutline> outlines = outlines_of(*sc);
        const ChartRegions r = chart_regions(mesh, outlines);
        SCOPED_TRACE("set " + std::to_string(s));
        expect_valid_seams(mesh, outlines, r);
        rerouted += r.rerouted > 0, ++sets;
        // Without interior features nothing can be misplaced: the shortest seams stay.
        std::vector<ChartOutline> bare = outlines;
        for (ChartOutline& o : bare) o.interior.clear(), o.interior_names.clear();
        EXPECT_EQ(chart_regions(mesh, bare).rerouted, 0);
    }
    std::printf("homer: %d of %d layouts needed seams re-routed\n", rerouted, sets);
    EXPECT_GT(rerouted, 0);
}

/// The library's seams for many more layouts than the CLI sweeps map (CTest label `long`;
/// CTMAP_SEAM_SETS=N per mesh, CTMAP_SEAM_MESH=name for one mesh): every layout gets regions whose seams keep the validity
/// conditions and every feature on its side (expect_valid_seams), the count re-routed printed.
TEST(SeamsLong, RegionsOfManyLayoutsKeepEveryFeatureOnItsSide) {
    const int n = count_from_env("CTMAP_SEAM_SETS", 150);
    struct Case {
        const char* mesh;
        bool plane;  // a plane-cut two-chart layout, else a disc chart and the rest
    };
    for (const Case& c : {Case{"cow", true}, Case{"homer", true}, Case{"bull", true}, Case{"bunny00", true},
                          Case{"head", false}, Case{"holes", false}, Case{"elk", false}}) {
        if (const char* only = std::getenv("CTMAP_SEAM_MESH"); only && std::string(only) != c.mesh) continue;
        const TriMesh mesh = read_mesh(data(std::string("meshes/") + c.mesh + ".off"));
        const Layout kind = c.plane ? Layout::plane_cut : Layout::disc_chart;
        std::mt19937 rng = layout_rng(kind);
        int ok = 0, rerouted = 0;
        for (int s = 0; s < n; ++s) {
            const std::optional<SeamCase> sc = draw_layout(mesh, kind, rng);
            ASSERT_TRUE(sc) << c.mesh;
            SCOPED_TRACE(std::string(c.mesh) + " set " + std::to_string(s));
            const std::vector<ChartOutline> outlines = outlines_of(*sc);
            try {
                const ChartRegions r = chart_regions(mesh, outlines);
                expect_valid_seams(mesh, outlines, r);
                ++ok, rerouted += r.rerouted > 0;
            } catch (const BadInput& e) {
                ADD_FAILURE() << e.what();
            }
        }
        std::printf("%s: %d of %d layouts got seams; %d needed seams re-routed\n", c.mesh, ok, n, rerouted);
    }
}

/// On the elk (genus 1) the shortest pieces between unevenly spaced seam features can take a
/// handle's short way: the first disc layouts all get disc regions with valid seams.
TEST(Seams, ElkDiscLayoutsGetDiscsDespiteTheHandle) {
    const TriMesh mesh = read_mesh(data("meshes/elk.off"));
    std::mt19937 rng = layout_rng(Layout::disc_chart);
    for (int s = 0; s < 22; ++s) {
        const std::optional<SeamCase> sc = draw_layout(mesh, Layout::disc_chart, rng);
        ASSERT_TRUE(sc);
        SCOPED_TRACE("elk set " + std::to_string(s));
        const std::vector<ChartOutline> outlines = outlines_of(*sc);
        const ChartRegions r = chart_regions(mesh, outlines);  // throws if a region is no disc
        expect_valid_seams(mesh, outlines, r);
        EXPECT_EQ(compute_topology(r.charts[0].mesh).euler, 1);
    }
}

/// The guide for one chart draws seams to the level of its border features: weight 1 at every
/// border feature (as far from the interior features as itself), 1 + strength at an interior
/// feature, and >= 1 everywhere.
TEST(Seams, LevelGuideIsLowestAtTheBorderFeaturesLevel) {
    const TriMesh mesh = read_mesh(data("meshes/head.off"));
    std::mt19937 rng(41);
    std::optional<SeamCase> sc;
    while (!sc || sc->charts[0].features.size() == sc->charts[0].border.size()) sc = disc_chart_case(mesh, rng);
    const ChartOutline chart = outlines_of(*sc)[0];
    const SeamGraph graph(mesh);
    const std::vector<double> w = seam_level_weights(mesh, graph, chart, 8.0);
    ASSERT_EQ(int(w.size()), mesh.num_vertices());
    for (double x : w) EXPECT_GE(x, 1.0);
    for (int v : chart.border) EXPECT_NEAR(w[v], 1.0, 1e-12);
    for (int v : chart.interior) EXPECT_NEAR(w[v], 9.0, 1e-12);
}

/// Must-show 3: a feature of the back chart whose every neighbour on the mesh is a feature of
/// the front chart: no seam can pass between them, so no route exists. map and validate both
/// refuse with exit 2, naming the feature, its chart and the seam segment, and write nothing.
TEST(BadInputSeams, NoSeamRouteKeepsAFeatureOnItsSide) {
    const std::string path = data("meshes/cow.off");
    const TriMesh mesh = read_mesh(path);
    std::mt19937 rng(43);
    std::optional<SeamCase> sc;
    while (!sc || sc->charts[0].features.size() < sc->charts[0].border.size() + 1) sc = plane_two_chart_case(mesh, rng);
    ChartInput& front = sc->charts[0];
    ChartInput& back = sc->charts[1];
    // The front's first interior feature moves to the back chart; its one-ring become front features.
    const std::size_t k = front.border.size();
    MapFeature trapped = front.features[k];
    front.features.erase(front.features.begin() + std::ptrdiff_t(k));
    std::set<int> ring;
    for (const Tri& t : mesh.faces)
        for (int j = 0; j < 3; ++j)
            if (t[j] == trapped.vertex) ring.insert(t[(j + 1) % 3]), ring.insert(t[(j + 2) % 3]);
    std::set<int> used;
    for (const ChartInput& ch : sc->charts)
        for (const MapFeature& f : ch.features) used.insert(f.vertex);
    int n = 0;
    for (int w : ring) {
        if (used.count(w)) continue;
        const double a = 2 * M_PI * n / double(ring.size());
        MapFeature f;
        f.name = "ring" + std::to_string(n++);
        f.vertex = w;
        f.uv = trapped.uv + 0.004 * Vec2(std::cos(a), std::sin(a));
        front.features.push_back(f);
    }
    Vec2 centre(0, 0);
    for (std::size_t i = 0; i < back.border.size(); ++i) centre += back.features[i].uv / double(back.border.size());
    trapped.name = "trapped";
    trapped.uv = centre + Vec2(1e-3, 2e-3);
    back.features.push_back(trapped);
    TempDir dir;
    write_file(dir / "trapped.json", charts_json(*sc).dump(2));
    const RunResult m = run_ctmap("map " + q(path) + " " + q(dir / "trapped.json") + " -o " + q(dir / "map.obj"));
    EXPECT_EQ(m.code, 2) << m.out;
    for (const char* w : {"trapped.json", "chart 'back'", "'trapped'", "the seam from 'seam", "would have to pass",
                          "on chart 'front''s side"})
        EXPECT_NE(m.out.find(w), std::string::npos) << "no \"" << w << "\" in: " << m.out;
    EXPECT_EQ(dir.count(), 1) << m.out;
    const RunResult v = run_ctmap("validate " + q(path) + " " + q(dir / "trapped.json"));
    EXPECT_EQ(v.code, 2) << v.out;
    auto last = [](std::string s) {
        while (!s.empty() && s.back() == '\n') s.pop_back();
        return s.substr(s.rfind('\n') == std::string::npos ? 0 : s.rfind('\n') + 1);
    };
    EXPECT_EQ(last(v.out), last(m.out)) << "validate and map disagree";
    EXPECT_EQ(dir.count(), 1) << v.out;
    std::printf("refused: %s", m.out.c_str());
}

}  // namespace
}  // namespace ctmap::test

