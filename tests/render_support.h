#pragma once
// Shared by the picture tests (test_render.cpp, test_render_cli.cpp): the test's own palette and
// pixel helpers, the example map of nefertiti, a texture of colour blobs at the features' image
// points, and which feature vertices the renderer's camera sees.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/render/render_map.h"
#include "test_support.h"

namespace ctmap::test {

using Rgb = std::array<int, 3>;

/// The test's own palette (not the renderer's): the corners and edge midpoints of the RGB cube,
/// {0, 128, 255}^3 without the grey background, so any two differ by >= 127 in some channel.
inline std::vector<Rgb> palette() {
    std::vector<Rgb> p;
    for (int r : {0, 128, 255})
        for (int g : {0, 128, 255})
            for (int b : {0, 128, 255})
                if (!(r == 128 && g == 128 && b == 128)) p.push_back({r, g, b});
    return p;
}
inline constexpr Rgb kGrey{128, 128, 128};

inline Rgb pixel(const Image& img, int x, int y) {
    const std::uint8_t* p = &img.pixels[(std::size_t(y) * img.width + x) * img.channels];
    return {p[0], p[1], p[2]};
}

inline int max_channel_difference(const Rgb& a, const Rgb& b) {
    return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

inline Image filled(int w, int h, const Rgb& c) {
    Image img;
    img.width = w, img.height = h, img.channels = 4;
    img.pixels.resize(std::size_t(w) * h * 4);
    for (std::size_t i = 0; i < img.pixels.size(); i += 4)
        img.pixels[i] = std::uint8_t(c[0]), img.pixels[i + 1] = std::uint8_t(c[1]), img.pixels[i + 2] = std::uint8_t(c[2]),
        img.pixels[i + 3] = 255;
    return img;
}

/// Möller-Trumbore: the parameter t of the ray o + t d at triangle (a, b, c), or infinity.
inline double ray_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
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

inline const Example& example() {
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
inline Image blob_texture(const std::vector<Vec2>& points, double* radius_out = nullptr) {
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
inline std::vector<int> visible_features(const TexturedMesh& m, const std::vector<int>& fv, const Camera& cam) {
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
inline bool sample_pixel(const TexturedMesh& m, int v, const Vec2& image_point, double blob_radius, const Camera& cam,
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

inline std::vector<char> border_vertices(const TriMesh& m) {
    std::map<std::pair<int, int>, int> count;
    for (const Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
    std::vector<char> b(m.num_vertices(), 0);
    for (const auto& [e, n] : count)
        if (n == 1) b[e.first] = b[e.second] = 1;
    return b;
}

}  // namespace ctmap::test
