// Pictures from the command line (issue 5): `ctmap render` draws each feature's colour where its
// camera puts the feature vertex and refuses bad input; the demo's gallery shows its five pictures.
// (The renderer itself: test_render.cpp.)
#include <cmath>
#include <filesystem>

#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/render/gallery.h"
#include "ctmap/render/render_inputs.h"
#include "ctmap/render/render_map.h"
#include "test_support.h"
#include "render_support.h"

namespace ctmap::test {
namespace {

TEST(Render, CliDrawsTheFeatureColoursAndRejectsBadInput) {
    const Example& e = example();
    TempDir dir;
    double radius = 0;
    const Image texture = blob_texture(e.pixels, &radius);
    write_png(texture, dir / "blobs.png");
    write_obj(e.textured, dir / "map.obj", dir / "blobs.png");
    const RunResult ok = run_ctmap("render " + q(dir / "map.obj") + " -o " + q(dir / "front.png") + " --size 640x480 --flat");
    ASSERT_EQ(ok.code, 0) << ok.out;
    const Image img = read_image(dir / "front.png");
    ASSERT_EQ(img.width, 640);
    ASSERT_EQ(img.height, 480);
    // The CLI's picture is the library's: the camera for the same options finds the colours.
    RenderScene scene;
    scene.mesh = &e.textured;
    scene.image = &texture;
    RenderOptions opt;
    opt.width = 640;
    opt.height = 480;
    const Camera cam = render_camera(scene, opt);
    const std::vector<Rgb> colours = palette();
    const std::vector<char> on_border = border_vertices(e.textured.mesh);
    int checked = 0;
    for (int i : visible_features(e.textured, e.map.cut.feature_vertex, cam)) {
        int x = 0, y = 0;
        if (!sample_pixel(e.textured, e.map.cut.feature_vertex[i], e.pixels[i], radius, cam, on_border, x, y)) continue;
        EXPECT_LE(max_channel_difference(pixel(img, x, y), colours[i]), 40) << "feature " << i;
        ++checked;
    }
    EXPECT_GE(checked, 11);

    // Bad input: exit 2, the message names the problem, nothing written.
    TexturedMesh no_uv;  // positions and faces only
    no_uv.mesh = e.input;
    no_uv.chart.assign(e.input.faces.size(), 0);
    write_obj(no_uv, dir / "no_uv.obj");
    struct Case {
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {q(dir / "no_uv.obj") + " -o " + q(dir / "x.png"), "no texture coordinates"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.png") + " --image " + q(dir / "missing.png"), "missing.png"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.png") + " --size 10x10", "--size"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.png") + " --size 99999", "--size"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.png") + " --size axb", "--size"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.png") + " --mode wireframe", "wireframe"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.png") + " --mode triangulation", "--features"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.png") + " --background pink", "pink"},
        {q(dir / "map.obj") + " -o " + q(dir / "x.jpg"), "PNG"},
        {q(dir / "map.obj") + " -o " + q(dir / "nofolder/x.png"), "nofolder"},
    };
    for (const Case& c : cases) {
        const RunResult r = run_ctmap("render " + c.args);
        EXPECT_EQ(r.code, 2) << c.args << "\n" << r.out;
        EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.args << "\n" << r.out;
    }
    std::filesystem::remove(dir / "blobs.png");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "x.jpg"));
}

// The demo's gallery: five pictures, the same pixels as `ctmap render` draws, and a page that
// shows every one of them with the paper's figure it redraws. Nothing appears before commit.
TEST(Render, GalleryShowsTheFivePicturesOfTheMap) {
    const Example& e = example();
    TempDir dir;
    write_obj(e.textured, dir / "map.obj", data("images/astronaut.png"));
    RenderFiles files;
    files.map = dir / "map.obj";
    files.features = data("features/nefertiti_astronaut.json");
    GalleryOptions opt;
    opt.size = 320;
    opt.title = "nefertiti <test>";
    opt.notes = {"certificate: valid"};
    OutputSet outputs;
    const std::vector<GalleryPicture> pictures = write_gallery(files, dir.path().string(), "nef", opt, outputs);
    ASSERT_EQ(pictures.size(), 5u);
    EXPECT_FALSE(std::filesystem::exists(dir / "index.html"));
    EXPECT_FALSE(std::filesystem::exists(dir / "nef_textured.png"));
    outputs.commit_all();
    const std::string html = read_file(dir / "index.html");
    EXPECT_NE(html.find("nefertiti &lt;test&gt;"), std::string::npos);  // escaped
    for (const GalleryPicture& p : pictures) {
        SCOPED_TRACE(p.file);
        EXPECT_NE(html.find("<img src=\"" + p.file + "\""), std::string::npos);
        EXPECT_NE(html.find(p.figure), std::string::npos);
        const Image img = read_image(dir / p.file);
        EXPECT_EQ(img.width, 320);
        // The same picture as render_map (and so `ctmap render`) with the same options.
        const RenderInputs in = read_render_inputs(files, {p.mode});
        RenderOptions ro;
        ro.mode = p.mode;
        ro.width = img.width;
        ro.height = img.height;
        const Image again = render_map(in.scene(), ro);
        int differing = 0;
        for (std::size_t i = 0; i < img.pixels.size(); ++i) differing += std::abs(int(img.pixels[i]) - int(again.pixels[i])) > 2;
        EXPECT_EQ(differing, 0);
    }
    for (const char* fig : {"Fig. 1c", "Fig. 1d", "Fig. 1e/g", "Fig. 1i", "Fig. 5-7"}) EXPECT_NE(html.find(fig), std::string::npos);
}

}  // namespace
}  // namespace ctmap::test
