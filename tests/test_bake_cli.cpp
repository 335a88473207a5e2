// `ctmap bake` end to end (issue 42 must-shows 3 and 4): the real program maps, bakes onto the
// user's layout with --obj, and `ctmap render` draws both from the same view; the two pictures
// must agree inside the silhouette (one chart: nefertiti; two charts: cow, along the seam too).
#include <algorithm>
#include <cmath>
#include <iostream>

#include <nlohmann/json.hpp>

#include "ctmap/cut/cut_to_disc.h"
#include "ctmap/domain/starter_features.h"
#include "ctmap/io/image.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/refine/isometric.h"
#include "bake_cases.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// Writes ONTO: `mesh` with per-corner UVs `uvs` / `uv_faces`, no material (the user's own file).
void write_onto(const std::string& path, const TriMesh& mesh, const std::vector<Vec2>& uvs, const std::vector<Tri>& uv_faces) {
    std::string s = "# a user's mesh with its own UV layout\n";
    char buf[96];
    for (const Vec3& p : mesh.positions) std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z()), s += buf;
    for (const Vec2& t : uvs) std::snprintf(buf, sizeof buf, "vt %.17g %.17g\n", t.x(), t.y()), s += buf;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        s += "f";
        for (int k = 0; k < 3; ++k) s += " " + std::to_string(mesh.faces[f][std::size_t(k)] + 1) + "/" + std::to_string(uv_faces[f][std::size_t(k)] + 1);
        s += "\n";
    }
    write_file(path, s);
}

/// Mean |difference| of the RGB channels over the pixels where `where(i)` holds and both
/// pictures are opaque (inside the silhouette, its anti-aliased edge left out); `count` gets
/// how many.
template <class Where>
double mean_difference(const Image& a, const Image& b, Where where, long long& count) {
    double sum = 0;
    count = 0;
    for (std::size_t i = 0; i < std::size_t(a.width) * std::size_t(a.height); ++i) {
        if (a.pixels[4 * i + 3] != 255 || b.pixels[4 * i + 3] != 255 || !where(i)) continue;
        for (int c = 0; c < 3; ++c) sum += std::abs(int(a.pixels[4 * i + std::size_t(c)]) - int(b.pixels[4 * i + std::size_t(c)]));
        ++count;
    }
    return count ? sum / (3.0 * double(count)) : 1e9;
}

RunResult must_run(const std::string& args) {
    const RunResult r = run_ctmap(args);
    EXPECT_EQ(r.code, 0) << "ctmap " << args << "\n" << r.out;
    return r;
}

TEST(BakeCli, RenderOfTheBakeMatchesTheRenderOfTheMap) {
    // Must-show 3: nefertiti mapped with the shipped features, baked onto itself with a planar
    // layout (--obj), both drawn textured from the front: mean difference <= 2/255 inside.
    TempDir dir;
    const std::string mesh = data("meshes/nefertiti.off");
    must_run("map " + q(mesh) + " " + q(data("features/nefertiti_astronaut.json")) + " --image " +
             q(data("images/astronaut.png")) + " -o " + q(dir / "map.obj") + " -q");
    const TriMesh m = read_mesh(mesh);
    const std::vector<Vec2> uv = planar_uvs(m);
    write_onto(dir / "onto.obj", m, uv, m.faces);
    const std::string onto_before = read_file(dir / "onto.obj");
    const RunResult bake = must_run("bake " + q(dir / "map.obj") + " " + q(dir / "onto.obj") + " -o " + q(dir / "baked.png") +
                                    " --size 2048 --obj " + q(dir / "baked.obj"));
    EXPECT_NE(bake.out.find("exact"), std::string::npos) << bake.out;
    EXPECT_EQ(read_file(dir / "onto.obj"), onto_before) << "ONTO was changed";
    // --obj: ONTO's lines byte for byte, after the one new mtllib line and a usemtl line.
    const std::string relinked = read_file(dir / "baked.obj");
    EXPECT_EQ(relinked.substr(0, relinked.find('\n') + 1), "mtllib baked.mtl\n");
    std::string expected = "mtllib baked.mtl\n" + onto_before;
    expected.insert(expected.find("\nf ") + 1, "usemtl ctmap_baked\n");
    EXPECT_EQ(relinked, expected);
    for (const char* which : {"map", "baked"})
        must_run(std::string("render ") + q(dir / (std::string(which) + ".obj")) + " -o " + q(dir / (std::string(which) + "_render.png")) +
                 " --size 512 --view front --background transparent -q");
    const Image a = read_image(dir / "map_render.png"), b = read_image(dir / "baked_render.png");
    long long n = 0;
    const double mean = mean_difference(a, b, [](std::size_t) { return true; }, n);
    EXPECT_GT(n, 512 * 512 / 4);
    EXPECT_LE(mean, 2.0);
    std::cout << "nefertiti: the map's render and the bake's differ by " << mean << "/255 over " << n << " pixels\n";
}

TEST(BakeCli, TwoChartsBakeOntoOneLayoutWithNoSeamInTheRender) {
    // Must-show 4: cow in two charts, front and back, joined by a seam (starter-features
    // --charts 2), baked onto one UV layout of the whole mesh (cut open into a disc, Tutte's map,
    // then the distortion optimiser so no part is crushed); both drawn from the side, where the
    // seam runs down the head and chest: mean difference <= 2/255 inside, and along the seam.
    // The charts are laid out so that the map itself has no visible seam, as the paper's Igea
    // (§2.4: charts joined by seams): both on the photo, the back chart's seam features on the
    // front chart's image points (the back chart mirrored), a fixed border, so each seam piece is
    // the same segment of the photo from both sides. What the comparison along it sees is then
    // the bake's own seam, if it had one (a gap, background bleeding in, the wrong chart).
    TempDir dir;
    const std::string mesh = data("meshes/cow.off");
    must_run("starter-features " + q(mesh) + " --image " + q(data("images/astronaut.png")) + " --charts 2 --no-mirror -o " +
             q(dir / "starter.json"));
    nlohmann::json charts = nlohmann::json::parse(read_file(dir / "starter.json"));
    ASSERT_EQ(charts["charts"].size(), 2u);
    const double height = charts["charts"][1]["image_size"][1];
    for (auto& f : charts["charts"][1]["features"]) f["image"][1] = height - f["image"][1].get<double>();  // --no-mirror's flip undone
    write_file(dir / "charts.json", charts.dump());
    must_run("map " + q(mesh) + " " + q(dir / "charts.json") + " --border-mode fixed -o " + q(dir / "map.obj") + " -q");
    const TriMesh m = read_mesh(mesh);
    const DiscCut cut = cut_to_disc(m);
    std::vector<Vec2> uv = tutte_map(cut.disc);
    for (Vec2& p : uv) p = Vec2(0.5, 0.5) + 0.45 * p;
    IsometricOptions iopt;
    iopt.box_lo = Vec2(0.01, 0.01), iopt.box_hi = Vec2(0.99, 0.99);
    iopt.keep_in_box = true;
    iopt.border = BorderMode::free;
    optimise_isometric(cut.disc, uv, {}, iopt);
    write_onto(dir / "onto.obj", m, uv, cut.disc.faces);  // disc faces: the input's, in order, on split vertices
    const RunResult bake = must_run("bake " + q(dir / "map.obj") + " " + q(dir / "onto.obj") + " -o " + q(dir / "baked.png") +
                                    " --size 4096 --obj " + q(dir / "baked.obj"));
    EXPECT_NE(bake.out.find("exact"), std::string::npos) << bake.out;
    auto render = [&](const std::string& obj, const std::string& png, const std::string& extra) {
        must_run("render " + q(dir / obj) + " -o " + q(dir / png) + " --size 512 --view side --background transparent -q" + extra);
    };
    render("map.obj", "map_render.png", "");
    render("baked.obj", "baked_render.png", "");
    render("map.obj", "front_render.png", " --chart front");
    const Image a = read_image(dir / "map_render.png"), b = read_image(dir / "baked_render.png"),
                front = read_image(dir / "front_render.png");
    // Where the front chart is what the full picture shows: the same pixel drawn alone.
    const int w = a.width, h = a.height;
    auto shows_front = [&](int x, int y) {
        const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
        return front.pixels[4 * i + 3] == 255 &&
               std::equal(&front.pixels[4 * i], &front.pixels[4 * i + 3], &a.pixels[4 * i]);
    };
    std::vector<char> seam(std::size_t(w) * std::size_t(h), 0);
    long long seam_pixels = 0;
    for (int y = 2; y < h - 2; ++y)
        for (int x = 2; x < w - 2; ++x) {
            bool f = false, other = false;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    const std::size_t j = std::size_t(y + dy) * std::size_t(w) + std::size_t(x + dx);
                    if (a.pixels[4 * j + 3] != 255) continue;
                    (shows_front(x + dx, y + dy) ? f : other) = true;
                }
            seam[std::size_t(y) * std::size_t(w) + std::size_t(x)] = f && other;
            seam_pixels += f && other;
        }
    long long n = 0, ns = 0;
    const double mean = mean_difference(a, b, [](std::size_t) { return true; }, n);
    const double along = mean_difference(a, b, [&](std::size_t i) { return seam[i] != 0; }, ns);
    EXPECT_GT(n, 512 * 512 / 20);  // the cow seen from the side (its head) fills about a tenth
    EXPECT_GT(ns, 200) << "the seam is seen from the side";
    EXPECT_LE(mean, 2.0);
    EXPECT_LE(along, 2.0);
    std::cout << "cow, two charts: the map's render and the bake's differ by " << mean << "/255 over " << n
              << " pixels, " << along << "/255 over " << ns << " pixels along the seam\n";
}

}  // namespace
}  // namespace ctmap::test

namespace ctmap::test {
namespace {

TEST(BakeCli, GlbMapUdimTilesAndMaskAreWritten) {
    // A GLB map (the photo embedded, positions as 32-bit floats) bakes exactly like its OBJ twin;
    // a layout over two UDIM tiles gives one texture and one mask per tile, each tile holding its
    // own triangles only.
    TempDir dir;
    const std::string mesh = data("meshes/nefertiti.off");
    must_run("map " + q(mesh) + " " + q(data("features/nefertiti_astronaut.json")) + " --image " +
             q(data("images/astronaut.png")) + " -o " + q(dir / "map.obj") + " --glb " + q(dir / "map.glb") + " -q");
    const TriMesh m = read_mesh(mesh);
    const std::vector<Vec2> uv = planar_uvs(m);
    write_onto(dir / "onto.obj", m, uv, m.faces);
    must_run("bake " + q(dir / "map.obj") + " " + q(dir / "onto.obj") + " -o " + q(dir / "obj.png") + " --mask " +
             q(dir / "obj_mask.png") + " --padding 0 -q");
    const RunResult glb = must_run("bake " + q(dir / "map.glb") + " " + q(dir / "onto.obj") + " -o " + q(dir / "glb.png") + " --padding 0");
    EXPECT_NE(glb.out.find("exact"), std::string::npos) << glb.out;
    const Image a = read_image(dir / "obj.png"), b = read_image(dir / "glb.png"), mask = read_image(dir / "obj_mask.png");
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    int worst = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) worst = std::max(worst, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
    EXPECT_LE(worst, 1) << "the GLB's float positions move a texel's point by far less than a pixel";

    // Two tiles: the faces whose centroid is right of the middle go to tile 1002 (u + 1).
    std::vector<Vec2> uvs;
    std::vector<Tri> uv_faces;
    int right = 0;
    for (const Tri& t : m.faces) {
        const double cu = (uv[std::size_t(t[0])].x() + uv[std::size_t(t[1])].x() + uv[std::size_t(t[2])].x()) / 3;
        const double shift = cu > 0.5 ? 1 : 0;
        right += cu > 0.5;
        Tri ft;
        for (int k = 0; k < 3; ++k) ft[std::size_t(k)] = int(uvs.size()), uvs.push_back(uv[std::size_t(t[std::size_t(k)])] + Vec2(shift, 0));
        uv_faces.push_back(ft);
    }
    ASSERT_GT(right, 0);
    write_onto(dir / "udim.obj", m, uvs, uv_faces);
    const RunResult u = must_run("bake " + q(dir / "map.obj") + " " + q(dir / "udim.obj") + " -o " + q(dir / "tile.png") +
                                 " --mask " + q(dir / "mask.png") + " --padding 0");
    EXPECT_NE(u.out.find("2 UDIM tiles"), std::string::npos) << u.out;
    EXPECT_FALSE(std::filesystem::exists(dir / "tile.png"));
    const Image t1 = read_image(dir / "tile.1001.png"), t2 = read_image(dir / "tile.1002.png");
    const Image m1 = read_image(dir / "mask.1001.png"), m2 = read_image(dir / "mask.1002.png");
    // Together the tiles cover what the one-tile bake covers, texel for texel, with its colours.
    long long both = 0, differ = 0, coverage_differs = 0;
    for (std::size_t i = 0; i < std::size_t(a.width) * std::size_t(a.height); ++i) {
        const bool in1 = m1.pixels[4 * i] == 255, in2 = m2.pixels[4 * i] == 255, in = mask.pixels[4 * i] == 255;
        both += in1 && in2;
        coverage_differs += (in1 || in2) != in;
        const Image& t = in1 ? t1 : t2;
        if ((in1 || in2) && std::abs(int(t.pixels[4 * i]) - int(a.pixels[4 * i])) > 1) ++differ;
    }
    EXPECT_EQ(coverage_differs, 0);
    EXPECT_EQ(differ, 0);
    std::cout << "UDIM: 2 tiles, " << both << " texels covered in both (a triangle's border on the tiles' shared u)\n";
}

}  // namespace
}  // namespace ctmap::test
