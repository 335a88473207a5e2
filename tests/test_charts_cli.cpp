// Issue 13 through the real program: starter-features --charts 2, map, check, render on closed
// meshes; bad charts files refused with exit 2 naming the charts and features, nothing written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "ctmap/certify/certificate.h"
#include "ctmap/domain/bisection_seam.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"

#include <cmath>
#include "test_support.h"

namespace ctmap::test {
namespace {

using json = nlohmann::json;

/// A starter two-chart file for `mesh` on astronaut.png (and its mirror) in `dir`.
json make_starter(const TempDir& dir, const std::string& mesh) {
    const RunResult s = run_ctmap("starter-features " + q(data("meshes/" + mesh + ".off")) + " --image " +
                                  q(data("images/astronaut.png")) + " --charts 2 -o " + q(dir / "charts.json"));
    EXPECT_EQ(s.code, 0) << s.out;
    return json::parse(read_file(dir / "charts.json"));
}

/// The map `ctmap map` wrote, certified here from the features file's own numbers: each
/// chart's faces are its material's, each feature's UV is (x / W, 1 - y / H) of its pixels.
Certificate certify_written(const std::string& obj, const json& charts, int width, int height) {
    std::vector<ChartMaterial> materials;
    const TexturedMesh tm = read_textured_obj(obj, nullptr, &materials);
    std::vector<int> vertex, chart;
    std::vector<Vec2> uv;
    for (const json& c : charts["charts"]) {
        int index = -1;
        for (std::size_t m = 0; m < materials.size(); ++m)
            if (materials[m].name == "chart_" + c["name"].get<std::string>()) index = int(m);
        EXPECT_GE(index, 0) << "no material for chart " << c["name"];
        std::map<std::string, int> vertex_of;  // a feature's vertex may be given in one chart only
        for (const json& d : charts["charts"])
            for (const json& f : d["features"])
                if (f.contains("vertex")) vertex_of[f["name"]] = f["vertex"];
        for (const json& f : c["features"]) {
            vertex.push_back(vertex_of.at(f["name"]));
            uv.emplace_back(f["image"][0].get<double>() / width, 1.0 - f["image"][1].get<double>() / height);
            chart.push_back(index);
        }
    }
    CertifyOptions opt;
    opt.feature_chart = chart;
    return certify(tm, vertex, uv, opt);
}

TEST(ChartsCli, StarterMapCheckAndRenderOnClosedMeshes) {
    for (const char* mesh : {"cow", "homer"}) {
        TempDir dir;
        const json charts = make_starter(dir, mesh);
        ASSERT_EQ(charts["charts"].size(), 2u);
        const std::string before = read_file(dir / "charts.json");
        // validate says yes to what map takes, writes nothing, and names both charts.
        const int files = dir.count();
        const RunResult v = run_ctmap("validate " + q(data(std::string("meshes/") + mesh + ".off")) + " " +
                                      q(dir / "charts.json"));
        EXPECT_EQ(v.code, 0) << v.out;
        for (const char* w : {"oriented manifold", "2 charts", "chart 'front'", "chart 'back'", "patches"})
            EXPECT_NE(v.out.find(w), std::string::npos) << "no \"" << w << "\" in: " << v.out;
        EXPECT_EQ(dir.count(), files) << v.out;
        const RunResult m = run_ctmap("map " + q(data(std::string("meshes/") + mesh + ".off")) + " " + q(dir / "charts.json") +
                                      " -o " + q(dir / "map.obj") + " --glb " + q(dir / "map.glb") + " --report " +
                                      q(dir / "report.json"));
        ASSERT_EQ(m.code, 0) << m.out;
        std::printf("%s", m.out.c_str());
        EXPECT_EQ(read_file(dir / "charts.json"), before) << "the features file changed";
        const Certificate c = certify_written(dir / "map.obj", charts, 512, 512);
        EXPECT_TRUE(c.valid) << mesh << ": " << c.flipped << " flipped, feature error " << c.feature_max_error
                             << ", border crossings " << c.border_crossings;
        // Both charts in the MTL, each with its own image.
        const std::string mtl = read_file(dir / "map.mtl");
        EXPECT_NE(mtl.find("newmtl chart_front"), std::string::npos);
        EXPECT_NE(mtl.find("newmtl chart_back"), std::string::npos);
        EXPECT_NE(mtl.find("astronaut_mirrored.png"), std::string::npos);
        const json report = json::parse(read_file(dir / "report.json"));
        EXPECT_EQ(report["charts"].size(), 2u);
        EXPECT_TRUE(report["certificate"]["valid"].get<bool>());
        for (const char* out : {"map.obj", "map.glb"}) {
            const RunResult k = run_ctmap("check " + q(dir / out) + " --features " + q(dir / "charts.json"));
            EXPECT_EQ(k.code, 0) << k.out;
            EXPECT_NE(k.out.find("2 charts"), std::string::npos) << k.out;
        }
        const RunResult r = run_ctmap("render " + q(dir / "map.obj") + " -o " + q(dir / "front.png") + " --size 128 -q");
        EXPECT_EQ(r.code, 0) << r.out;
        const RunResult u = run_ctmap("render " + q(dir / "map.obj") + " -o " + q(dir / "uv.png") +
                                      " --mode uv --chart back --size 128 -q");
        EXPECT_EQ(u.code, 0) << u.out;
    }
}

/// The last non-empty line of a program's output (its error message).
std::string last_line(const std::string& out) {
    std::string s = out;
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    const std::size_t nl = s.rfind('\n');
    return nl == std::string::npos ? s : s.substr(nl + 1);
}

/// `ctmap validate` on a refused charts file: exit 2 with map's own message, nothing written
/// (issue 17: validate and map run the same checks).
void expect_validate_agrees(const std::string& mesh, const std::string& features, const RunResult& map,
                            const TempDir& dir) {
    const int files = dir.count();
    const RunResult v = run_ctmap("validate " + q(mesh) + " " + q(features));
    EXPECT_EQ(v.code, 2) << v.out;
    EXPECT_EQ(last_line(v.out), last_line(map.out)) << "validate and map disagree";
    EXPECT_EQ(dir.count(), files) << v.out;
}

/// A charts file changed by `edit`, mapped and validated: exit 2, the message holds every word of `expect`,
/// nothing written.
void expect_refused(const std::string& mesh, const std::function<void(json&)>& edit,
                    const std::vector<std::string>& expect) {
    TempDir dir;
    json charts = make_starter(dir, mesh);
    edit(charts);
    write_file(dir / "bad.json", charts.dump(2));
    const int files = dir.count();
    const RunResult m = run_ctmap("map " + q(data("meshes/" + mesh + ".off")) + " " + q(dir / "bad.json") + " -o " +
                                  q(dir / "map.obj") + " --glb " + q(dir / "map.glb"));
    EXPECT_EQ(m.code, 2) << m.out;
    for (const std::string& w : expect) EXPECT_NE(m.out.find(w), std::string::npos) << "no \"" << w << "\" in: " << m.out;
    EXPECT_NE(m.out.find("bad.json"), std::string::npos) << m.out;
    EXPECT_EQ(dir.count(), files) << "an output was left: " << m.out;
    expect_validate_agrees(data("meshes/" + mesh + ".off"), dir / "bad.json", m, dir);
    std::printf("refused: %s", m.out.c_str());
}

json& chart(json& j, const std::string& name) {
    for (json& c : j["charts"])
        if (c["name"] == name) return c;
    throw std::runtime_error("no chart " + name);
}

TEST(BadInputCharts, SeamOrderDisagrees) {
    expect_refused("cow", [](json& j) { std::swap(chart(j, "back")["border"][1], chart(j, "back")["border"][3]); },
                   {"'front'", "'back'", "different orders", "seam1", "seam3"});
}

TEST(BadInputCharts, FeatureVertexDiffersBetweenCharts) {
    expect_refused("cow",
                   [](json& j) {
                       for (json& f : chart(j, "back")["features"])
                           if (f["name"] == "seam2") f["vertex"] = f["vertex"].get<int>() + 1;
                   },
                   {"'seam2'", "'front'", "'back'", "one place on the mesh"});
}

TEST(BadInputCharts, UnknownBorderName) {
    expect_refused("cow", [](json& j) { chart(j, "front")["border"].push_back("nose"); },
                   {"'front'", "'nose'", "not one of the chart's features"});
}

TEST(BadInputCharts, RegionHoldsAnotherChartsFeature) {
    // A landmark of the front half listed in the back chart: the back region does not hold it.
    expect_refused("cow",
                   [](json& j) {
                       json f = chart(j, "front")["features"].back();
                       chart(j, "front")["features"].erase(chart(j, "front")["features"].size() - 1);
                       f["name"] = "stray";
                       chart(j, "back")["features"].push_back(f);
                   },
                   {"chart 'back'", "'stray'", "outside its border", "the seam from"});
}

TEST(BadInputCharts, BorderFeaturesCrossInTheImage) {
    // Two seam features' image points swapped in one chart: its border polygon crosses itself.
    expect_refused("cow",
                   [](json& j) {
                       json& fs = chart(j, "front")["features"];
                       json *a = nullptr, *b = nullptr;
                       for (json& f : fs) {
                           if (f["name"] == "seam1") a = &f;
                           if (f["name"] == "seam5") b = &f;
                       }
                       std::swap((*a)["image"], (*b)["image"]);
                   },
                   {"chart 'front'", "seam"});
}

TEST(BadInputCharts, ChartNameThatCannotNameAMaterial) {
    expect_refused("cow", [](json& j) { chart(j, "back")["name"] = "back side"; },
                   {"'back side'", "letters, digits"});
}

TEST(BadInputCharts, OneVertexUnderTwoNames) {
    // The back chart names the vertex of the front's first landmark under a name of its own.
    expect_refused("cow",
                   [](json& j) {
                       json f = chart(j, "front")["features"].back();
                       f["name"] = "alias";
                       chart(j, "back")["features"].push_back(f);
                   },
                   {"'alias'", "same mesh vertex"});
}

TEST(BadInputCharts, MapRefusesASeamThroughAHandle) {
    // Two charts on the elk (genus 1) bounded by a loop round its middle that a handle passes
    // through: at most one side is a disc, so one chart's region keeps the handle (either may be
    // the one named). Written by hand (starter-features refuses it too).
    TempDir dir;
    const TriMesh elk = read_mesh(data("meshes/elk.off"));
    const std::vector<int> seam = bisection_seam_vertices(elk, 8);
    json j;
    j["units"] = "pixels";
    for (const char* name : {"front", "back"}) {
        json c;
        c["name"] = name;
        c["image_size"] = {512, 512};
        c["features"] = json::array();
        c["border"] = json::array();
        for (std::size_t i = 0; i < seam.size(); ++i) {
            const double a = 2 * M_PI * double(i) / double(seam.size()) * (std::string(name) == "front" ? 1 : -1);
            c["features"].push_back({{"name", "seam" + std::to_string(i)}, {"vertex", seam[i]},
                                     {"image", {256 + 200 * std::cos(a), 256 - 200 * std::sin(a)}}});
            c["border"].push_back("seam" + std::to_string(i));
        }
        j["charts"].push_back(c);
    }
    write_file(dir / "elk.json", j.dump(2));
    const RunResult m = run_ctmap("map " + q(data("meshes/elk.off")) + " " + q(dir / "elk.json") + " -o " + q(dir / "map.obj"));
    EXPECT_EQ(m.code, 2) << m.out;
    EXPECT_NE(m.out.find("elk.json"), std::string::npos) << m.out;
    EXPECT_NE(m.out.find("not a disc"), std::string::npos) << m.out;
    EXPECT_TRUE(m.out.find("chart 'front'") != std::string::npos || m.out.find("chart 'back'") != std::string::npos) << m.out;
    EXPECT_EQ(dir.count(), 1) << m.out;
    expect_validate_agrees(data("meshes/elk.off"), dir / "elk.json", m, dir);
    std::printf("refused: %s", m.out.c_str());
}

TEST(BadInputCharts, RegionIsNotADisc) {
    // On the elk (genus 1) a loop round the middle need not cut it into two discs: a chart whose
    // region keeps a handle is refused.
    TempDir dir;
    const RunResult s = run_ctmap("starter-features " + q(data("meshes/elk.off")) + " --image " +
                                  q(data("images/astronaut.png")) + " --charts 2 -o " + q(dir / "charts.json"));
    EXPECT_EQ(s.code, 2) << s.out;
    EXPECT_NE(s.out.find("not a disc"), std::string::npos) << s.out;
    EXPECT_EQ(dir.count(), 0) << s.out;
    std::printf("refused: %s", s.out.c_str());
}

}  // namespace
}  // namespace ctmap::test

namespace ctmap::test {
namespace {

/// Issue 13's readers give a chart per material; `ctmap check` of a features file without charts
/// must still certify the whole OBJ as one map (a Blender OBJ with two materials is one chart):
/// a face flipped alone in its own material is found, and material changes are no UV border.
TEST(ChartsCli, CheckOfAOneChartMapIgnoresItsMaterials) {
    TempDir dir;
    const std::string features = data("features/nefertiti_astronaut.json");
    const RunResult m = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " + q(features) + " --image " +
                                  q(data("images/astronaut.png")) + " -o " + q(dir / "map.obj") + " -q");
    ASSERT_EQ(m.code, 0) << m.out;
    const std::string obj = read_file(dir / "map.obj");
    std::vector<std::string> lines;
    for (std::size_t at = 0, next; at < obj.size(); at = next + 1) {
        next = obj.find('\n', at);
        lines.push_back(obj.substr(at, next - at));
    }
    std::vector<std::size_t> faces;
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (lines[i].rfind("f ", 0) == 0) faces.push_back(i);
    ASSERT_GT(faces.size(), 10u);
    auto check = [&](const std::string& text) {
        write_file(dir / "edited.obj", text);
        return run_ctmap("check " + q(dir / "edited.obj") + " --features " + q(features) + " --image " +
                         q(data("images/astronaut.png")) + " --json");
    };
    auto join = [](const std::vector<std::string>& ls) {
        std::string s;
        for (const std::string& l : ls) s += l + "\n";
        return s;
    };
    // Two materials, the second from the middle face on: the same certificate as one material.
    std::vector<std::string> two = lines;
    two.insert(two.begin() + std::ptrdiff_t(faces[faces.size() / 2]), "usemtl second");
    const RunResult a = check(join(lines)), b = check(join(two));
    ASSERT_EQ(a.code, 0) << a.out;
    ASSERT_EQ(b.code, 0) << b.out;
    EXPECT_EQ(nlohmann::json::parse(a.out)["border_edges"], nlohmann::json::parse(b.out)["border_edges"]);
    // One face flipped (two corners' vt swapped) and moved alone into a material of its own.
    std::vector<std::string> flipped = lines;
    std::string face = flipped[faces[5]];
    std::istringstream words(face.substr(2));
    std::string c0, c1, c2;
    words >> c0 >> c1 >> c2;
    auto vt = [](const std::string& corner) { return corner.substr(corner.find('/') + 1, corner.rfind('/') - corner.find('/') - 1); };
    auto with_vt = [](const std::string& corner, const std::string& t) {
        return corner.substr(0, corner.find('/') + 1) + t + corner.substr(corner.rfind('/'));
    };
    const std::string swapped = "f " + c0 + " " + with_vt(c1, vt(c2)) + " " + with_vt(c2, vt(c1));
    flipped.erase(flipped.begin() + std::ptrdiff_t(faces[5]));
    flipped.push_back("usemtl alone");
    flipped.push_back(swapped);
    const RunResult f = check(join(flipped));
    EXPECT_EQ(f.code, 1) << f.out;
    EXPECT_GE(nlohmann::json::parse(f.out)["flipped"].get<int>(), 1) << f.out;
}

}  // namespace
}  // namespace ctmap::test
