// Pictures (issue 5): the renderer is checked on what it draws, not on the file it writes. A map
// of nefertiti is textured with an image that has a distinct colour blob at each feature's image
// point; every feature vertex that faces the camera and is not hidden must show its own colour
// where the renderer's camera projects it. The image-plane modes are checked the same way.
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/render/gallery.h"
#include "ctmap/render/render_inputs.h"
#include "ctmap/render/render_map.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

using Rgb = std::array<int, 3>;

/// The test's own palette (not the renderer's): the corners and edge midpoints of the RGB cube,
/// {0, 128, 255}^3 without the grey background, so any two differ by >= 127 in some channel.
std::vector<Rgb> palette() {
    std::vector<Rgb> p;
    for (int r : {0, 128, 255})
        for (int g : {0, 128, 255})
            for (int b : {0, 128, 255})
                if (!(r == 128 && g == 128 && b == 128)) p.push_back({r, g, b});
    return p;
}
constexpr Rgb kGrey{128, 128, 128};

Rgb pixel(const Image& img, int x, int y) {
    const std::uint8_t* p = &img.pixels[(std::size_t(y) * img.width + x) * img.channels];
    return {p[0], p[1], p[2]};
}

int max_channel_difference(const Rgb& a, const Rgb& b) {
    return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

Image filled(int w, int h, const Rgb& c) {
    Image img;
    img.width = w, img.height = h, img.channels = 4;
    img.pixels.resize(std::size_t(w) * h * 4);
    for (std::size_t i = 0; i < img.pixels.size(); i += 4)
        img.pixels[i] = std::uint8_t(c[0]), img.pixels[i + 1] = std::uint8_t(c[1]), img.pixels[i + 2] = std::uint8_t(c[2]),
        img.pixels[i + 3] = 255;
    return img;
}

/// Möller-Trumbore: the parameter t of the ray o + t d at triangle (a, b, c), or infinity.
double ray_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-14) return std::numeric_limits<double>::infinity();
    const Vec3 s = o - a;
    const double u = s.dot(p) / det;
    if (u < 0 || u > 1) return std::numeric_limits<double>::infinity();
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0 || u + v > 1) return std::numeric_limits<double>::infinity();
    return e2.dot(q) / det;
}

/// The nefertiti example mapped once for all tests here; certified by map_texture (it throws
/// otherwise) and checked again below.
struct Example {
    TriMesh input;
    MapResult map;
    TexturedMesh textured;
    std::vector<Vec2> pixels;  ///< per feature, its image point in pixels (512 x 512)
};

const Example& example() {
    static const Example e = [] {
        Example x;
        x.input = read_mesh(data("meshes/nefertiti.off"));
        FeatureSet fs = read_features(data("features/nefertiti_astronaut.json"));
        resolve_units(fs, 512, 512);
        x.map = map_texture(x.input, map_features(fs, 512, 512));
        x.textured = x.map.textured();
        for (const Feature& f : fs.features) x.pixels.push_back(f.image);
        return x;
    }();
    return e;
}

/// A 512 x 512 grey texture with a disc of palette colour i around feature i's image point. The
/// radius stays below half the closest distance between two features, so discs never touch.
Image blob_texture(const std::vector<Vec2>& points, double* radius_out = nullptr) {
    double closest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t j = i + 1; j < points.size(); ++j) closest = std::min(closest, (points[i] - points[j]).norm());
    const double radius = std::min(0.4 * closest, 8.0);
    if (radius_out) *radius_out = radius;
    Image img = filled(512, 512, kGrey);
    const std::vector<Rgb> colours = palette();
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int y = 0; y < 512; ++y)
            for (int x = 0; x < 512; ++x)
                if ((Vec2(x + 0.5, y + 0.5) - points[i]).norm() <= radius) {
                    std::uint8_t* p = &img.pixels[(std::size_t(y) * 512 + x) * 4];
                    for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(colours[i][c]);
                }
    return img;
}

/// Feature vertices that face the camera (normal within ~78 degrees of the direction to the eye)
/// and that no other triangle hides (a ray from the eye, independent of the renderer).
std::vector<int> visible_features(const TexturedMesh& m, const std::vector<int>& fv, const Camera& cam) {
    std::vector<int> out;
    for (std::size_t i = 0; i < fv.size(); ++i) {
        const int v = fv[i];
        const Vec3 p = m.mesh.positions[v];
        Vec3 n = Vec3::Zero();
        for (const Tri& t : m.mesh.faces)
            if (t[0] == v || t[1] == v || t[2] == v)
                n += (m.mesh.positions[t[1]] - m.mesh.positions[t[0]]).cross(m.mesh.positions[t[2]] - m.mesh.positions[t[0]]);
        const Vec3 to_eye = cam.eye - p;
        if (n.normalized().dot(to_eye.normalized()) < 0.2) continue;
        bool hidden = false;
        for (const Tri& t : m.mesh.faces) {
            if (t[0] == v || t[1] == v || t[2] == v) continue;
            const double s = ray_triangle(cam.eye, p - cam.eye, m.mesh.positions[t[0]], m.mesh.positions[t[1]],
                                          m.mesh.positions[t[2]]);
            if (s > 0 && s < 1 - 1e-9) hidden = true;
        }
        if (!hidden) out.push_back(int(i));
    }
    return out;
}

/// Where to read feature i's colour in a picture: the pixel at its projected vertex for an
/// interior feature. A border feature's vertex lies on the mesh's outline, where a pixel is partly
/// background, so there the pixel nearest to it whose square lies inside one of its front-facing
/// faces (centre at least 0.75 px from the projected edges) is taken, if the surface point there
/// maps into the inner 60% of the blob. Returns false when no such pixel exists.
bool sample_pixel(const TexturedMesh& m, int v, const Vec2& image_point, double blob_radius, const Camera& cam,
                  const std::vector<char>& on_border, int& px, int& py) {
    const Vec3 a = cam.project(m.mesh.positions[v]);
    if (!on_border[v]) {
        px = int(std::floor(a.x())), py = int(std::floor(a.y()));
        return true;
    }
    double best = std::numeric_limits<double>::infinity();
    for (int f = 0; f < m.mesh.num_faces(); ++f) {
        const Tri& t = m.mesh.faces[f];
        const int k = t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : -1;
        if (k < 0) continue;
        const Vec3& p0 = m.mesh.positions[t[0]];
        const Vec3 n = (m.mesh.positions[t[1]] - p0).cross(m.mesh.positions[t[2]] - p0);
        if (n.normalized().dot((cam.eye - p0).normalized()) < 0.2) continue;
        Vec2 s[3], uv[3];
        for (int j = 0; j < 3; ++j) {
            s[j] = cam.project(m.mesh.positions[t[j]]).head<2>();
            uv[j] = m.uvs[m.uv_faces[f][j]];
        }
        const double area = (s[1] - s[0]).x() * (s[2] - s[0]).y() - (s[1] - s[0]).y() * (s[2] - s[0]).x();
        if (std::abs(area) < 1e-9) continue;
        for (int y = int(a.y()) - 5; y <= int(a.y()) + 5; ++y)
            for (int x = int(a.x()) - 5; x <= int(a.x()) + 5; ++x) {
                const Vec2 c(x + 0.5, y + 0.5);
                double bary[3], margin = std::numeric_limits<double>::infinity();
                for (int j = 0; j < 3; ++j) {
                    const Vec2 &p = s[(j + 1) % 3], &q = s[(j + 2) % 3];
                    const double twice = (q - p).x() * (c - p).y() - (q - p).y() * (c - p).x();
                    bary[j] = twice / area;
                    margin = std::min(margin, bary[j] * std::abs(area) / (q - p).norm());
                }
                if (margin < 0.75) continue;
                const Vec2 u = bary[0] * uv[0] + bary[1] * uv[1] + bary[2] * uv[2];
                if ((Vec2(u.x() * 512, (1 - u.y()) * 512) - image_point).norm() > 0.6 * blob_radius) continue;
                if (const double d = (c - a.head<2>()).norm(); d < best) best = d, px = x, py = y;
            }
        (void)k;
    }
    return best < std::numeric_limits<double>::infinity();
}

std::vector<char> border_vertices(const TriMesh& m) {
    std::map<std::pair<int, int>, int> count;
    for (const Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
    std::vector<char> b(m.num_vertices(), 0);
    for (const auto& [e, n] : count)
        if (n == 1) b[e.first] = b[e.second] = 1;
    return b;
}

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

}  // namespace
}  // namespace ctmap::test


namespace ctmap::test {
namespace {

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
