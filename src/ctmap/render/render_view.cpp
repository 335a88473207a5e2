// The renderer's names, colours, checker texture and camera (render_map.h): everything of a
// picture that is decided before OpenGL is called.
#include "ctmap/render/render_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ctmap/errors.h"

namespace ctmap {

// ---------------------------------------------------------------------------------------------
// Names, colours, checker
// ---------------------------------------------------------------------------------------------

bool is_3d(RenderMode mode) {
    return mode == RenderMode::textured || mode == RenderMode::checker || mode == RenderMode::paths;
}

namespace {
const std::array<std::pair<const char*, RenderView>, 7> kViews{{{"front", RenderView::front},
                                                                 {"side", RenderView::side},
                                                                 {"back", RenderView::back},
                                                                 {"top", RenderView::top},
                                                                 {"three-quarter", RenderView::three_quarter},
                                                                 {"left", RenderView::left},
                                                                 {"bottom", RenderView::bottom}}};
const std::array<std::pair<const char*, RenderMode>, 5> kModes{{{"textured", RenderMode::textured},
                                                                 {"checker", RenderMode::checker},
                                                                 {"uv", RenderMode::uv},
                                                                 {"paths", RenderMode::paths},
                                                                 {"triangulation", RenderMode::triangulation}}};

template <class T, std::size_t N>
T parse_name(const std::array<std::pair<const char*, T>, N>& table, const std::string& name, const char* what) {
    std::string choices;
    for (const auto& [n, v] : table) {
        if (name == n) return v;
        choices += (choices.empty() ? "" : ", ") + std::string(n);
    }
    throw BadInput("", std::string("unknown ") + what + " '" + name + "' (choose one of " + choices + ")");
}

template <class T, std::size_t N>
std::string name_of(const std::array<std::pair<const char*, T>, N>& table, T value) {
    for (const auto& [n, v] : table)
        if (v == value) return n;
    return "?";
}

}  // namespace

RenderView parse_render_view(const std::string& name) { return parse_name(kViews, name, "view"); }
RenderMode parse_render_mode(const std::string& name) { return parse_name(kModes, name, "mode"); }
std::string to_string(RenderView view) { return name_of(kViews, view); }
std::string to_string(RenderMode mode) { return name_of(kModes, mode); }

std::array<std::uint8_t, 3> feature_colour(int i) {
    // The golden angle spreads any number of hues evenly without knowing the count.
    return render_detail::hsv(0.02 + 0.6180339887498949 * i, 0.85, 0.95);
}

Image checker_texture(int cells_x, int cells_y, int cell) {
    if (cells_x < 1 || cells_y < 1 || cell < 1 || double(cells_x) * cell * cells_y * cell > (1 << 26))
        throw BadInput("", "checker texture of " + std::to_string(cells_x) + " x " + std::to_string(cells_y) +
                               " cells of " + std::to_string(cell) + " pixels: out of range");
    Image img;
    img.width = cells_x * cell;
    img.height = cells_y * cell;
    img.channels = 4;
    img.pixels.resize(std::size_t(img.width) * img.height * 4);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const auto& c = ((x / cell + y / cell) % 2) ? kCheckerLight : kCheckerDark;
            std::uint8_t* p = &img.pixels[(std::size_t(y) * img.width + x) * 4];
            p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
        }
    return img;
}

// ---------------------------------------------------------------------------------------------
// Camera
// ---------------------------------------------------------------------------------------------

Vec3 Camera::project(const Vec3& p) const {
    const Eigen::Vector4d clip = projection * view * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    const Vec3 ndc = clip.head<3>() / clip.w();
    // OpenGL's window y grows upwards; the picture's rows go down.
    return Vec3((ndc.x() + 1) * 0.5 * width, height - (ndc.y() + 1) * 0.5 * height, (ndc.z() + 1) * 0.5);
}

namespace {

void check_inputs(const RenderScene& s, const RenderOptions& o) {
    auto size_ok = [](int v) { return v >= RenderOptions::kMinSize && v <= RenderOptions::kMaxSize; };
    if (!size_ok(o.width) || !size_ok(o.height))
        throw BadInput("", "picture size " + std::to_string(o.width) + " x " + std::to_string(o.height) +
                               " out of range (each side " + std::to_string(RenderOptions::kMinSize) + " to " +
                               std::to_string(RenderOptions::kMaxSize) + " pixels)");
    if (o.samples < 1 || o.samples > 64) throw BadInput("", "multisampling " + std::to_string(o.samples) + " out of range (1 to 64)");
    const std::string mode = "render mode '" + to_string(o.mode) + "'";
    if (o.mode == RenderMode::triangulation) {
        if (!s.triangulation) throw BadInput("", mode + " needs the feature triangulation (features)");
    } else {
        if (!s.mesh || s.mesh->mesh.faces.empty()) throw BadInput("", mode + " needs a mesh with faces");
        const TexturedMesh& m = *s.mesh;
        const bool has_uv = !m.uvs.empty() && m.uv_faces.size() == m.mesh.faces.size();
        if (o.mode != RenderMode::paths && !has_uv)
            throw BadInput("", mode + " needs texture coordinates (an OBJ with `vt` and `f v/vt`)");
        if (has_uv)
            for (const Tri& t : m.uv_faces)
                for (int k : t)
                    if (k < 0 || k >= int(m.uvs.size())) throw BadInput("", "UV index out of range");
        for (const Tri& t : m.mesh.faces)
            for (int k : t)
                if (k < 0 || k >= m.mesh.num_vertices()) throw BadInput("", "vertex index out of range");
        if (o.mode == RenderMode::paths && m.patch.size() != m.mesh.faces.size())
            throw BadInput("", mode + " needs the patch of every face (OBJs written by ctmap carry `g patch_<id>` groups)");
        for (int v : s.feature_vertex)
            if (v < 0 || v >= m.mesh.num_vertices())
                throw BadInput("", "feature vertex " + std::to_string(v) + " is not a vertex of the mesh");
    }
    if ((o.mode == RenderMode::textured || !is_3d(o.mode)) &&
        (!s.image || s.image->width <= 0 || s.image->height <= 0 || s.image->pixels.empty()))
        throw BadInput("", mode + " needs the texture image");
    if (s.image && s.image->pixels.size() != std::size_t(s.image->width) * s.image->height * s.image->channels)
        throw BadInput(s.image->path, "image pixel buffer does not match its size");
}

Eigen::Matrix4d look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
    const Vec3 f = (target - eye).normalized();
    const Vec3 s = f.cross(up).normalized();
    const Vec3 u = s.cross(f);
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.block<1, 3>(0, 0) = s.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -s.dot(eye);
    m(1, 3) = -u.dot(eye);
    m(2, 3) = f.dot(eye);
    return m;
}

Eigen::Matrix4d perspective(double fovy, double aspect, double near, double far) {
    const double t = 1.0 / std::tan(fovy / 2);
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    m(0, 0) = t / aspect;
    m(1, 1) = t;
    m(2, 2) = (far + near) / (near - far);
    m(2, 3) = 2 * far * near / (near - far);
    m(3, 2) = -1;
    return m;
}

}  // namespace

Eigen::AlignedBox2d image_plane_region(const RenderScene& scene, const RenderOptions& options) {
    check_inputs(scene, options);
    const double a = double(scene.image->width) / scene.image->height;
    Eigen::AlignedBox2d whole(Vec2(0, 0), Vec2(a, 1));
    Eigen::AlignedBox2d r = whole;
    if (!options.whole_image) {
        const Eigen::AlignedBox2d uv = render_detail::uv_box(scene, options.mode);
        if (!uv.isEmpty() && uv.min().allFinite() && uv.max().allFinite()) {
            r = Eigen::AlignedBox2d(Vec2(uv.min().x() * a, uv.min().y()), Vec2(uv.max().x() * a, uv.max().y()));
            // Room for the markers and some of the picture around the map; never a sliver.
            const double grow = std::max(0.15 * r.sizes().maxCoeff(), 0.02);
            r = Eigen::AlignedBox2d(r.min() - Vec2(grow, grow), r.max() + Vec2(grow, grow));
        }
    } else {
        r = Eigen::AlignedBox2d(whole.min() - Vec2(0.03, 0.03), whole.max() + Vec2(0.03, 0.03));
    }
    return r;
}

Camera render_camera(const RenderScene& scene, const RenderOptions& options) {
    check_inputs(scene, options);
    Camera cam;
    cam.width = options.width;
    cam.height = options.height;
    const double aspect = double(options.width) / options.height;
    if (is_3d(options.mode)) {
        const std::vector<Vec3>& pos = scene.mesh->mesh.positions;
        Eigen::AlignedBox3d box;
        for (const Vec3& p : pos) box.extend(p);
        const Vec3 centre = box.center();
        double radius = 0;
        for (const Vec3& p : pos) radius = std::max(radius, (p - centre).norm());
        if (!(radius > 0) || !std::isfinite(radius)) radius = 1;
        Vec3 dir(0, 0, 1), up(0, 1, 0);
        switch (options.view) {
            case RenderView::front: dir = Vec3(0, 0, 1); break;
            case RenderView::back: dir = Vec3(0, 0, -1); break;
            case RenderView::side: dir = Vec3(1, 0, 0); break;
            case RenderView::top: dir = Vec3(0, 1, 0), up = Vec3(0, 0, -1); break;
            case RenderView::three_quarter: dir = Vec3(0.7, 0.35, 1.0).normalized(); break;
            case RenderView::left: dir = Vec3(-1, 0, 0); break;
            case RenderView::bottom: dir = Vec3(0, -1, 0), up = Vec3(0, 0, 1); break;
        }
        const double fovy = 30.0 * M_PI / 180.0;
        // The sphere fits when its angular radius is below the smaller half field of view.
        const double half = std::min(fovy / 2, std::atan(std::tan(fovy / 2) * aspect));
        const double distance = 1.06 * radius / std::sin(half);
        cam.eye = centre + distance * dir;
        cam.target = centre;
        cam.fovy = fovy;
        cam.view = look_at(cam.eye, centre, up);
        cam.projection = perspective(fovy, aspect, std::max(distance - 1.1 * radius, 1e-3 * distance),
                                     distance + 1.1 * radius);
        cam.perspective = true;
    } else {
        // The region fitted into the picture, centred.
        const double a = double(scene.image->width) / scene.image->height;
        cam.uv_aspect = a;
        const Eigen::AlignedBox2d r = image_plane_region(scene, options);
        const Vec2 c = r.center(), size = r.sizes();
        const double s = std::min(options.width / size.x(), options.height / size.y());  // pixels per unit
        Eigen::Matrix4d p = Eigen::Matrix4d::Identity();
        p(0, 0) = 2 * s / options.width;
        p(1, 1) = 2 * s / options.height;
        p(2, 2) = -1;
        p(0, 3) = -c.x() * p(0, 0);
        p(1, 3) = -c.y() * p(1, 1);
        cam.projection = p;
    }
    return cam;
}

namespace render_detail {

std::array<std::uint8_t, 3> hsv(double h, double s, double v) {
    h = (h - std::floor(h)) * 6;
    const int i = int(h) % 6;
    const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (i) {
        case 1: r = q, g = v, b = p; break;
        case 2: r = p, g = v, b = t; break;
        case 3: r = p, g = q, b = v; break;
        case 4: r = t, g = p, b = v; break;
        case 5: r = v, g = p, b = q; break;
        default: break;
    }
    auto byte = [](double x) { return std::uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255)); };
    return {byte(r), byte(g), byte(b)};
}

/// Bounding box of the map's UVs (all of them, or those of the triangulation's points).
Eigen::AlignedBox2d uv_box(const RenderScene& scene, RenderMode mode) {
    Eigen::AlignedBox2d box;
    if (mode == RenderMode::triangulation)
        for (const Vec2& p : scene.triangulation->points) box.extend(p);
    else
        for (const Vec2& p : scene.mesh->uvs) box.extend(p);
    return box;
}

}  // namespace render_detail

}  // namespace ctmap
