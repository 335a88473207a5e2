// Pictures (issue 5): the renderer is checked on what it draws, not on the file it writes. A map
// of nefertiti is textured with an image that has a distinct colour blob at each feature's image
// point; every feature vertex that faces the camera and is not hidden must show its own colour
// where the renderer's camera projects it. The image-plane modes are checked the same way.
// (The command line's pictures and the demo's gallery: test_render_cli.cpp.)
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/render/render_map.h"
#include "test_support.h"
#include "render_support.h"

namespace ctmap::test {
namespace {

TEST(Render, TheExampleMapIsCertified) {
    const Example& e = example();
    EXPECT_TRUE(e.map.certificate.valid);
    const Certificate again = certify(e.textured, e.map.cut.feature_vertex, e.map.feature_uv);
    EXPECT_TRUE(again.valid);
    EXPECT_EQ(again.feature_max_error, 0.0);
}

// Must-show 2: each feature's colour is where the renderer's own camera puts the feature vertex.
TEST(Render, EachVisibleFeatureShowsItsBlobColourWhereTheCameraProjectsIt) {
    const Example& e = example();
    ASSERT_LE(e.pixels.size(), palette().size());
    double radius = 0;
    const Image texture = blob_texture(e.pixels, &radius);
    RenderScene scene;
    scene.mesh = &e.textured;
    scene.image = &texture;
    const std::vector<Rgb> colours = palette();
    // Tolerance: 40 of 255 per channel for the texture's own colours (flat). It allows the
    // filtering of the blob's rim and 8-bit rounding; a neighbour's blob or the grey differs by
    // >= 127 in some channel, so a wrong position cannot pass.
    const int tolerance = 40;
    for (RenderView view : {RenderView::front, RenderView::three_quarter, RenderView::side}) {
        SCOPED_TRACE(to_string(view));
        RenderOptions opt;
        opt.width = 900;
        opt.height = 700;  // not square: the aspect must be handled the same by camera and renderer
        opt.view = view;
        opt.mode = RenderMode::textured;
        opt.shading = false;
        const Camera cam = render_camera(scene, opt);
        const Image flat = render_map(scene, opt);
        ASSERT_EQ(flat.width, 900);
        ASSERT_EQ(flat.height, 700);
        opt.shading = true;
        const Image shaded = render_map(scene, opt);
        const std::vector<int> visible = visible_features(e.textured, e.map.cut.feature_vertex, cam);
        const std::vector<char> on_border = border_vertices(e.textured.mesh);
        int checked = 0, mirrored = 0, mirrored_matches = 0;
        for (int i : visible) {
            int x = 0, y = 0;
            if (!sample_pixel(e.textured, e.map.cut.feature_vertex[i], e.pixels[i], radius, cam, on_border, x, y)) {
                std::cout << "  feature " << i << ": no pixel inside its faces maps into its blob\n";
                continue;
            }
            ASSERT_TRUE(x >= 0 && y >= 0 && x < flat.width && y < flat.height) << "feature " << i << " off the picture";
            const Rgb got = pixel(flat, x, y);
            EXPECT_LE(max_channel_difference(got, colours[i]), tolerance)
                << "feature " << i << " at pixel (" << x << ", " << y << "): got (" << got[0] << ", " << got[1] << ", "
                << got[2] << "), want (" << colours[i][0] << ", " << colours[i][1] << ", " << colours[i][2] << ")";
            // Shaded: the colour scaled by the light, k * colour with k in [0.3, 1] (ambient 0.3),
            // to the same tolerance.
            const Rgb s = pixel(shaded, x, y);
            const int top = std::max({colours[i][0], colours[i][1], colours[i][2]});
            const double k = double(std::max({s[0], s[1], s[2]})) / top;
            EXPECT_GE(k, 0.3 - 0.05);
            const Rgb scaled{int(std::lround(k * colours[i][0])), int(std::lround(k * colours[i][1])),
                             int(std::lround(k * colours[i][2]))};
            EXPECT_LE(max_channel_difference(s, scaled), tolerance) << "shaded, feature " << i;
            ++checked;
            // Control: off the symmetry axis, the same check at the mirrored position (the mask is
            // nearly symmetric, and so are the features) must fail, or the check proves nothing.
            if (std::abs(flat.width - 1 - 2 * x) > 40) {
                ++mirrored;
                if (max_channel_difference(pixel(flat, flat.width - 1 - x, y), colours[i]) <= tolerance) ++mirrored_matches;
            }
        }
        EXPECT_EQ(mirrored_matches, 0) << "the colours are found at mirrored positions too";
        std::cout << to_string(view) << ": " << checked << " of " << e.pixels.size()
                  << " features visible and checked (blob radius " << radius << " px); mirrored control: "
                  << mirrored_matches << " of " << mirrored << " match\n";
        // The mask's rim curves back, so its border features face sideways (vertex normals more
        // than 78 degrees from the view): from the front the 8 interior features and 3 of the 8
        // border ones qualify, 11 from three-quarter, 4 from the side.
        EXPECT_GE(checked, view == RenderView::side ? 4 : 11);
    }
}

TEST(Render, CheckerModeShowsBothCheckerColoursOnTheMesh) {
    const Example& e = example();
    RenderScene scene;
    scene.mesh = &e.textured;
    RenderOptions opt;
    opt.width = opt.height = 512;
    opt.mode = RenderMode::checker;
    opt.shading = false;
    opt.background = {255, 0, 0, 255};  // a colour the checker does not have
    const Image img = render_map(scene, opt);
    const Rgb dark{kCheckerDark[0], kCheckerDark[1], kCheckerDark[2]};
    const Rgb light{kCheckerLight[0], kCheckerLight[1], kCheckerLight[2]};
    int n_dark = 0, n_light = 0, n_background = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const Rgb p = pixel(img, x, y);
            if (max_channel_difference(p, dark) <= 12) ++n_dark;
            else if (max_channel_difference(p, light) <= 12) ++n_light;
            else if (max_channel_difference(p, {255, 0, 0}) <= 12) ++n_background;
        }
    const int mesh_pixels = img.width * img.height - n_background;
    std::cout << "checker: dark " << n_dark << ", light " << n_light << " of " << mesh_pixels << " mesh pixels\n";
    // Squares of both colours, in about equal parts (12 squares across the map), and little else
    // than the two colours on the mesh (edges between squares are filtered).
    EXPECT_GT(n_dark, mesh_pixels / 4);
    EXPECT_GT(n_light, mesh_pixels / 4);
    EXPECT_GT(n_dark + n_light, 0.85 * mesh_pixels);
}

TEST(Render, UvModeDrawsEachFeatureMarkerAtItsUv) {
    const Example& e = example();
    // A square image and a wide one: UVs stretch with the image, the markers must follow.
    for (const auto& [w, h, whole] : {std::tuple{512, 512, false}, std::tuple{512, 512, true}, std::tuple{900, 300, true}}) {
        const Image grey = filled(w, h, kGrey);
        RenderScene scene;
        scene.mesh = &e.textured;
        scene.image = &grey;
        scene.feature_uv = e.map.feature_uv;
        RenderOptions opt;
        opt.width = 800;
        opt.height = 640;
        opt.mode = RenderMode::uv;
        opt.whole_image = whole;
        const Camera cam = render_camera(scene, opt);
        const Image img = render_map(scene, opt);
        for (std::size_t i = 0; i < e.map.feature_uv.size(); ++i) {
            // The UV from the features file, independently of the map: image point / size, v up.
            const Vec2 uv(e.pixels[i].x() / 512, 1 - e.pixels[i].y() / 512);
            const Vec3 q = cam.project_uv(uv);
            const std::array<std::uint8_t, 3> c = feature_colour(int(i));
            const Rgb got = pixel(img, int(std::floor(q.x())), int(std::floor(q.y())));
            EXPECT_LE(max_channel_difference(got, {c[0], c[1], c[2]}), 8)
                << "feature " << i << ", image " << w << " x " << h << ", whole image " << whole;
        }
    }
}

TEST(Render, TriangulationModeDrawsEveryEdgeOverTheImage) {
    const Example& e = example();
    const Image grey = filled(512, 512, kGrey);
    RenderScene scene;
    scene.image = &grey;
    scene.triangulation = &e.map.triangulation;
    RenderOptions opt;
    opt.width = opt.height = 700;
    opt.mode = RenderMode::triangulation;
    const Camera cam = render_camera(scene, opt);
    const Image img = render_map(scene, opt);
    // The midpoint of every edge is covered by a line, not the grey image.
    for (const auto& edge : e.map.triangulation.edges) {
        const Vec2 mid = 0.5 * (e.map.triangulation.points[edge[0]] + e.map.triangulation.points[edge[1]]);
        const Vec3 q = cam.project_uv(mid);
        const Rgb got = pixel(img, int(std::floor(q.x())), int(std::floor(q.y())));
        EXPECT_GT(max_channel_difference(got, kGrey), 60) << "edge " << edge[0] << "-" << edge[1];
    }
    // The centroid of every triangle shows the image, unless it is within a few pixels of a line
    // or a marker (thin triangles).
    auto px = [&](const Vec2& uv) { return Vec2(cam.project_uv(uv).head<2>()); };
    int centroids = 0;
    for (const Tri& t : e.map.triangulation.triangles) {
        const auto& pts = e.map.triangulation.points;
        const Vec2 c = px((pts[t[0]] + pts[t[1]] + pts[t[2]]) / 3);
        double clear = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 3; ++k) {
            const Vec2 a = px(pts[t[k]]), b = px(pts[t[(k + 1) % 3]]);
            const double s = std::clamp((c - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
            clear = std::min({clear, (a + s * (b - a) - c).norm(), (a - c).norm() - 10});
        }
        if (clear < 4) continue;
        EXPECT_LE(max_channel_difference(pixel(img, int(c.x()), int(c.y())), kGrey), 2);
        ++centroids;
    }
    EXPECT_GE(centroids, int(e.map.triangulation.triangles.size()) / 2);
}

TEST(Render, PathsModeDrawsTheCutOnTheMesh) {
    const Example& e = example();
    RenderScene scene;
    scene.mesh = &e.textured;
    scene.feature_vertex = e.map.cut.feature_vertex;
    RenderOptions opt;
    opt.width = opt.height = 800;
    opt.mode = RenderMode::paths;
    opt.shading = false;
    const Camera cam = render_camera(scene, opt);
    const Image img = render_map(scene, opt);
    // Midpoints of path edges (between two patches) that face the camera are drawn red: red high,
    // green and blue low. The patches' pastel colours all have every channel above 180.
    const TexturedMesh& m = e.textured;
    std::map<std::pair<int, int>, std::vector<int>> edge_faces;
    for (int f = 0; f < m.mesh.num_faces(); ++f)
        for (int k = 0; k < 3; ++k)
            edge_faces[std::minmax(m.mesh.faces[f][k], m.mesh.faces[f][(k + 1) % 3])].push_back(f);
    int checked = 0, red = 0;
    for (const auto& [edge, faces] : edge_faces) {
        if (faces.size() != 2 || m.patch[faces[0]] == m.patch[faces[1]]) continue;
        const Vec3 a = m.mesh.positions[edge.first], b = m.mesh.positions[edge.second];
        Vec3 n = Vec3::Zero();
        for (int f : faces)
            n += (m.mesh.positions[m.mesh.faces[f][1]] - m.mesh.positions[m.mesh.faces[f][0]])
                     .cross(m.mesh.positions[m.mesh.faces[f][2]] - m.mesh.positions[m.mesh.faces[f][0]]);
        const Vec3 mid = 0.5 * (a + b);
        if (n.normalized().dot((cam.eye - mid).normalized()) < 0.5) continue;
        const Vec3 q = cam.project(mid);
        const Rgb p = pixel(img, int(q.x()), int(q.y()));
        ++checked;
        if (p[0] > 150 && p[1] < 90 && p[2] < 90) ++red;
    }
    std::cout << "paths: " << red << " of " << checked << " front-facing path edge midpoints drawn red\n";
    EXPECT_GT(checked, 50);
    // Markers cover some midpoints next to features; everything else must be red.
    EXPECT_GE(red, 0.9 * checked);
}

}  // namespace
}  // namespace ctmap::test
