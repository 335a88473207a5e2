// Pictures of a texture map with OpenGL 3.3 core, off-screen (render_map.h). The context comes
// from gl_context.cpp; this file builds vertex buffers, draws into a multisampled framebuffer
// object and reads the resolved pixels back.
#include "ctmap/render/render_map.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>

#include "ctmap/errors.h"
#include "ctmap/render/gl_context.h"

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
}  // namespace

RenderView parse_render_view(const std::string& name) { return parse_name(kViews, name, "view"); }
RenderMode parse_render_mode(const std::string& name) { return parse_name(kModes, name, "mode"); }
std::string to_string(RenderView view) { return name_of(kViews, view); }
std::string to_string(RenderMode mode) { return name_of(kModes, mode); }

std::array<std::uint8_t, 3> feature_colour(int i) {
    // The golden angle spreads any number of hues evenly without knowing the count.
    return hsv(0.02 + 0.6180339887498949 * i, 0.85, 0.95);
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

/// Bounding box of the map's UVs (all of them, or those of the triangulation's points).
Eigen::AlignedBox2d uv_box(const RenderScene& scene, RenderMode mode) {
    Eigen::AlignedBox2d box;
    if (mode == RenderMode::triangulation)
        for (const Vec2& p : scene.triangulation->points) box.extend(p);
    else
        for (const Vec2& p : scene.mesh->uvs) box.extend(p);
    return box;
}

}  // namespace

Eigen::AlignedBox2d image_plane_region(const RenderScene& scene, const RenderOptions& options) {
    check_inputs(scene, options);
    const double a = double(scene.image->width) / scene.image->height;
    Eigen::AlignedBox2d whole(Vec2(0, 0), Vec2(a, 1));
    Eigen::AlignedBox2d r = whole;
    if (!options.whole_image) {
        const Eigen::AlignedBox2d uv = uv_box(scene, options.mode);
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

// ---------------------------------------------------------------------------------------------
// OpenGL
// ---------------------------------------------------------------------------------------------

namespace {

template <void (*Delete)(GLsizei, const GLuint*)>
struct GlHandle {
    GLuint id = 0;
    GlHandle() = default;
    GlHandle(const GlHandle&) = delete;
    GlHandle& operator=(const GlHandle&) = delete;
    ~GlHandle() {
        if (id) Delete(1, &id);
    }
};
void delete_program(GLsizei, const GLuint* id) { glDeleteProgram(*id); }
using Buffer = GlHandle<glDeleteBuffers>;
using VertexArray = GlHandle<glDeleteVertexArrays>;
using Texture = GlHandle<glDeleteTextures>;
using Renderbuffer = GlHandle<glDeleteRenderbuffers>;
using Framebuffer = GlHandle<glDeleteFramebuffers>;
using Program = GlHandle<delete_program>;

void check_gl(const char* where) {
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(e));
        throw InternalError(std::string("OpenGL error ") + code + " while " + where);
    }
}

constexpr const char* kMeshVS = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec3 a_colour;
uniform mat4 u_view;
uniform mat4 u_proj;
out vec3 v_pos;
out vec3 v_normal;
out vec2 v_uv;
out vec3 v_colour;
void main() {
    vec4 p = u_view * vec4(a_pos, 1.0);
    v_pos = p.xyz;
    v_normal = mat3(u_view) * a_normal;
    v_uv = a_uv;
    v_colour = a_colour;
    gl_Position = u_proj * p;
})";

// Texture rows are uploaded top row first, so t = 0 is the image's top and v (up) becomes 1 - v.
// Headlight: a light at the eye, diffuse plus ambient, both sides lit (a disc shows its back).
constexpr const char* kMeshFS = R"(#version 330 core
in vec3 v_pos;
in vec3 v_normal;
in vec2 v_uv;
in vec3 v_colour;
uniform sampler2D u_texture;
uniform int u_textured;
uniform int u_shading;
uniform vec4 u_uv_transform;  // texture coordinate = uv * xy + zw (the checker's tiling)
out vec4 o_colour;
void main() {
    vec2 t = v_uv * u_uv_transform.xy + u_uv_transform.zw;
    vec3 c = u_textured != 0 ? texture(u_texture, vec2(t.x, 1.0 - t.y)).rgb : v_colour;
    if (u_shading != 0) {
        vec3 n = normalize(v_normal);
        if (!gl_FrontFacing) n = -n;
        float d = max(dot(n, normalize(-v_pos)), 0.0);
        c *= 0.3 + 0.7 * d;
    }
    o_colour = vec4(c, 1.0);
})";

// Lines and markers: positions pulled towards the eye by u_pull (world units) so that marks on
// the surface win the depth test against it.
constexpr const char* kMarkVS = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec4 a_colour;
uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_pull;
out vec4 g_colour;
void main() {
    vec4 p = u_view * vec4(a_pos, 1.0);
    float d = length(p.xyz);
    if (u_pull > 0.0 && d > 0.0) p.xyz *= max(d - u_pull, 0.5 * d) / d;
    g_colour = a_colour;
    gl_Position = u_proj * p;
})";

// A segment widened in screen space to u_width pixels, with square caps so chains join.
constexpr const char* kLineGS = R"(#version 330 core
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
in vec4 g_colour[];
out vec4 f_colour;
uniform vec2 u_viewport;
uniform float u_width;
void main() {
    vec4 p0 = gl_in[0].gl_Position, p1 = gl_in[1].gl_Position;
    if (p0.w <= 0.0 || p1.w <= 0.0) return;
    vec2 half_vp = 0.5 * u_viewport;
    vec2 d = p1.xy / p1.w * half_vp - p0.xy / p0.w * half_vp;
    float len = length(d);
    d = len > 1e-6 ? d / len : vec2(1.0, 0.0);
    vec2 n = vec2(-d.y, d.x) * (0.5 * u_width) / half_vp;
    vec2 e = d * (0.5 * u_width) / half_vp;
    f_colour = g_colour[0];
    gl_Position = vec4(p0.xy + (n - e) * p0.w, p0.zw); EmitVertex();
    gl_Position = vec4(p0.xy + (-n - e) * p0.w, p0.zw); EmitVertex();
    f_colour = g_colour[1];
    gl_Position = vec4(p1.xy + (n + e) * p1.w, p1.zw); EmitVertex();
    gl_Position = vec4(p1.xy + (-n + e) * p1.w, p1.zw); EmitVertex();
    EndPrimitive();
})";

constexpr const char* kLineFS = R"(#version 330 core
in vec4 f_colour;
out vec4 o_colour;
void main() { o_colour = f_colour; })";

// A marker: a disc of u_radius pixels facing the camera, dark rim, the feature's colour inside.
constexpr const char* kPointGS = R"(#version 330 core
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
in vec4 g_colour[];
out vec4 f_colour;
out vec2 f_local;
uniform vec2 u_viewport;
uniform float u_radius;
void main() {
    vec4 p = gl_in[0].gl_Position;
    if (p.w <= 0.0) return;
    vec2 r = vec2(u_radius) / (0.5 * u_viewport) * p.w;
    f_colour = g_colour[0];
    f_local = vec2(-1.0, -1.0); gl_Position = vec4(p.xy + vec2(-r.x, -r.y), p.zw); EmitVertex();
    f_local = vec2(1.0, -1.0);  gl_Position = vec4(p.xy + vec2(r.x, -r.y), p.zw); EmitVertex();
    f_local = vec2(-1.0, 1.0);  gl_Position = vec4(p.xy + vec2(-r.x, r.y), p.zw); EmitVertex();
    f_local = vec2(1.0, 1.0);   gl_Position = vec4(p.xy + vec2(r.x, r.y), p.zw); EmitVertex();
    EndPrimitive();
})";

constexpr const char* kPointFS = R"(#version 330 core
in vec4 f_colour;
in vec2 f_local;
out vec4 o_colour;
void main() {
    float d = length(f_local);
    if (d > 1.0) discard;
    o_colour = d > 0.72 ? vec4(0.06, 0.06, 0.06, 1.0) : f_colour;
})";

GLuint compile(GLenum type, const char* source) {
    const GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &source, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {0};
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        throw InternalError(std::string("OpenGL shader compilation failed: ") + log);
    }
    return s;
}

GLuint link(const char* vs, const char* gs, const char* fs) {
    const GLuint p = glCreateProgram();
    GLuint shaders[3] = {compile(GL_VERTEX_SHADER, vs), gs ? compile(GL_GEOMETRY_SHADER, gs) : 0,
                         compile(GL_FRAGMENT_SHADER, fs)};
    for (GLuint s : shaders)
        if (s) glAttachShader(p, s);
    glLinkProgram(p);
    for (GLuint s : shaders)
        if (s) glDeleteShader(s);  // flagged; freed with the program
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {0};
        glGetProgramInfoLog(p, sizeof log, nullptr, log);
        glDeleteProgram(p);
        throw InternalError(std::string("OpenGL program link failed: ") + log);
    }
    return p;
}

/// The compiled programs, kept with the (process-lifetime) context: compiling them costs more
/// than drawing a small mesh.
struct Programs {
    std::uint64_t context = 0;
    GLuint mesh = 0, line = 0, point = 0;
};

const Programs& programs(std::uint64_t context_id) {
    static Programs p;  // guarded by the GlSession lock
    if (p.context != context_id) {
        p = Programs{};
        p.mesh = link(kMeshVS, nullptr, kMeshFS);
        p.line = link(kMarkVS, kLineGS, kLineFS);
        p.point = link(kMarkVS, kPointGS, kPointFS);
        p.context = context_id;
    }
    return p;
}

bool has_gl_extension(const char* name) {
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
        if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))), name) == 0) return true;
    return false;
}

/// Uploads `img` as a mipmapped texture with trilinear (and, where offered, anisotropic) filtering.
void upload_texture(Texture& tex, const Image& img, bool repeat) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (img.width > max_size || img.height > max_size)
        throw BadInput(img.path, "image of " + std::to_string(img.width) + " x " + std::to_string(img.height) +
                                     " pixels is larger than the renderer's texture limit (" +
                                     std::to_string(max_size) + " per side)");
    std::vector<std::uint8_t> rgba;
    const std::uint8_t* data = img.pixels.data();
    if (img.channels != 4) {
        rgba.resize(std::size_t(img.width) * img.height * 4);
        for (std::size_t i = 0, n = std::size_t(img.width) * img.height; i < n; ++i) {
            const std::uint8_t* p = &img.pixels[i * img.channels];
            const bool grey = img.channels < 3;
            rgba[i * 4 + 0] = p[0];
            rgba[i * 4 + 1] = grey ? p[0] : p[1];
            rgba[i * 4 + 2] = grey ? p[0] : p[2];
            rgba[i * 4 + 3] = img.channels == 2 ? p[1] : 255;
        }
        data = rgba.data();
    }
    glGenTextures(1, &tex.id);
    glBindTexture(GL_TEXTURE_2D, tex.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, data);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    const GLint wrap = repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
    if (has_gl_extension("GL_ARB_texture_filter_anisotropic") || has_gl_extension("GL_EXT_texture_filter_anisotropic")) {
        GLfloat max_aniso = 1;
        glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &max_aniso);
        glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY, std::min(8.0f, max_aniso));
    }
    check_gl("uploading the texture");
}

// Vertex layouts.
struct MeshVertex {
    float pos[3], normal[3], uv[2], colour[3];
};
struct MarkVertex {
    float pos[3], colour[4];
};

void set_attribute(GLuint index, int count, std::size_t stride, std::size_t offset) {
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, count, GL_FLOAT, GL_FALSE, GLsizei(stride), reinterpret_cast<const void*>(offset));
}

/// A vertex array with its buffer, filled once.
struct Geometry {
    VertexArray vao;
    Buffer vbo;
    GLsizei count = 0;
};

void fill(Geometry& g, const std::vector<MeshVertex>& v) {
    glGenVertexArrays(1, &g.vao.id);
    glBindVertexArray(g.vao.id);
    glGenBuffers(1, &g.vbo.id);
    glBindBuffer(GL_ARRAY_BUFFER, g.vbo.id);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(MeshVertex)), v.data(), GL_STATIC_DRAW);
    set_attribute(0, 3, sizeof(MeshVertex), offsetof(MeshVertex, pos));
    set_attribute(1, 3, sizeof(MeshVertex), offsetof(MeshVertex, normal));
    set_attribute(2, 2, sizeof(MeshVertex), offsetof(MeshVertex, uv));
    set_attribute(3, 3, sizeof(MeshVertex), offsetof(MeshVertex, colour));
    g.count = GLsizei(v.size());
}

void fill(Geometry& g, const std::vector<MarkVertex>& v) {
    glGenVertexArrays(1, &g.vao.id);
    glBindVertexArray(g.vao.id);
    glGenBuffers(1, &g.vbo.id);
    glBindBuffer(GL_ARRAY_BUFFER, g.vbo.id);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(MarkVertex)), v.data(), GL_STATIC_DRAW);
    set_attribute(0, 3, sizeof(MarkVertex), offsetof(MarkVertex, pos));
    set_attribute(1, 4, sizeof(MarkVertex), offsetof(MarkVertex, colour));
    g.count = GLsizei(v.size());
}

void set_matrix(GLuint program, const char* name, const Eigen::Matrix4d& m) {
    const Eigen::Matrix4f f = m.cast<float>();  // column-major, as OpenGL wants it
    glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, f.data());
}

using Rgba = std::array<float, 4>;
Rgba rgba(const std::array<std::uint8_t, 3>& c, float alpha = 1) { return {c[0] / 255.f, c[1] / 255.f, c[2] / 255.f, alpha}; }

void add_segment(std::vector<MarkVertex>& out, const Vec3& a, const Vec3& b, const Rgba& c) {
    out.push_back({{float(a.x()), float(a.y()), float(a.z())}, {c[0], c[1], c[2], c[3]}});
    out.push_back({{float(b.x()), float(b.y()), float(b.z())}, {c[0], c[1], c[2], c[3]}});
}

/// Per face edge (face f, corner k: the edge from corner k to k+1): kInner, kPath (between two
/// patches: a cut path) or kBorder (the mesh border), for the uv and paths pictures.
enum EdgeKind : char { kInner = 0, kPath = 1, kBorder = 2 };
std::vector<std::array<char, 3>> edge_kinds(const TexturedMesh& m) {
    std::unordered_map<std::uint64_t, std::vector<int>> edge_faces;
    auto key = [](int a, int b) { return (std::uint64_t(std::min(a, b)) << 32) | std::uint32_t(std::max(a, b)); };
    const auto& faces = m.mesh.faces;
    for (int f = 0; f < int(faces.size()); ++f)
        for (int k = 0; k < 3; ++k) edge_faces[key(faces[f][k], faces[f][(k + 1) % 3])].push_back(f);
    std::vector<std::array<char, 3>> kind(faces.size(), {kInner, kInner, kInner});
    for (int f = 0; f < int(faces.size()); ++f)
        for (int k = 0; k < 3; ++k) {
            const std::vector<int>& fs = edge_faces[key(faces[f][k], faces[f][(k + 1) % 3])];
            if (fs.size() != 2) kind[f][k] = kBorder;
            else if (!m.patch.empty() && m.patch[fs[0]] != m.patch[fs[1]]) kind[f][k] = kPath;
        }
    return kind;
}

std::vector<Vec3> vertex_normals(const TriMesh& m) {
    std::vector<Vec3> n(m.positions.size(), Vec3::Zero());
    for (const Tri& t : m.faces) {
        const Vec3 a = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
        for (int v : t) n[v] += a;  // area-weighted
    }
    for (Vec3& v : n) v = v.norm() > 0 ? Vec3(v.normalized()) : Vec3(0, 0, 1);
    return n;
}

/// One vertex per face corner: UVs and normals may differ per corner (seams, several charts).
std::vector<MeshVertex> mesh_vertices(const TexturedMesh& m, bool patch_colours) {
    const std::vector<Vec3> normals = vertex_normals(m.mesh);
    const bool has_uv = !m.uvs.empty() && m.uv_faces.size() == m.mesh.faces.size();
    std::vector<MeshVertex> out;
    out.reserve(m.mesh.faces.size() * 3);
    for (std::size_t f = 0; f < m.mesh.faces.size(); ++f) {
        std::array<std::uint8_t, 3> c{225, 225, 225};
        if (patch_colours && f < m.patch.size()) c = hsv(0.13 + 0.6180339887498949 * m.patch[f], 0.22, 0.97);
        for (int k = 0; k < 3; ++k) {
            const Vec3& p = m.mesh.positions[m.mesh.faces[f][k]];
            const Vec3& n = normals[m.mesh.faces[f][k]];
            const Vec2 uv = has_uv ? m.uvs[m.uv_faces[f][k]] : Vec2(0, 0);
            out.push_back({{float(p.x()), float(p.y()), float(p.z())},
                           {float(n.x()), float(n.y()), float(n.z())},
                           {float(uv.x()), float(uv.y())},
                           {c[0] / 255.f, c[1] / 255.f, c[2] / 255.f}});
        }
    }
    return out;
}

/// Multisampled colour + depth target, resolved into a plain one for reading back.
struct Target {
    Framebuffer fbo, resolve_fbo;
    Renderbuffer colour, depth, resolve_colour;
    int width = 0, height = 0;

    Target(int w, int h, int samples) : width(w), height(h) {
        GLint max_samples = 1, max_rb = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
        if (w > max_rb || h > max_rb)
            throw BadInput("", "picture size " + std::to_string(w) + " x " + std::to_string(h) +
                                   " is larger than the renderer allows (" + std::to_string(max_rb) + " per side)");
        samples = std::clamp(samples, 1, std::max(1, int(max_samples)));
        glGenRenderbuffers(1, &colour.id);
        glBindRenderbuffer(GL_RENDERBUFFER, colour.id);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
        glGenRenderbuffers(1, &depth.id);
        glBindRenderbuffer(GL_RENDERBUFFER, depth.id);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
        glGenFramebuffers(1, &fbo.id);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.id);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw InternalError("OpenGL: the multisampled framebuffer is incomplete");
        glGenRenderbuffers(1, &resolve_colour.id);
        glBindRenderbuffer(GL_RENDERBUFFER, resolve_colour.id);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
        glGenFramebuffers(1, &resolve_fbo.id);
        glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo.id);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_colour.id);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw InternalError("OpenGL: the resolve framebuffer is incomplete");
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id);
        check_gl("creating the framebuffers");
    }

    Image read() {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo.id);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo.id);
        glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo.id);
        Image img;
        img.width = width;
        img.height = height;
        img.channels = 4;
        img.pixels.resize(std::size_t(width) * height * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
        check_gl("reading the picture back");
        // OpenGL's first row is the bottom one; the picture's is the top one.
        const std::size_t row = std::size_t(width) * 4;
        std::vector<std::uint8_t> tmp(row);
        for (int y = 0; y < height / 2; ++y) {
            std::uint8_t* a = &img.pixels[y * row];
            std::uint8_t* b = &img.pixels[(height - 1 - y) * row];
            std::memcpy(tmp.data(), a, row);
            std::memcpy(a, b, row);
            std::memcpy(b, tmp.data(), row);
        }
        return img;
    }
};

struct Style {
    double line = 1, marker = 1;
};
const Rgba kPathColour{0.86f, 0.10f, 0.10f, 1};
const Rgba kMeshBorderColour{0.15f, 0.15f, 0.15f, 1};

}  // namespace

Image render_map(const RenderScene& scene, const RenderOptions& options) {
    const Camera cam = render_camera(scene, options);  // checks the inputs
    const RenderMode mode = options.mode;
    const bool three_d = is_3d(mode);
    const double size = std::min(options.width, options.height);
    Style style;
    style.line = options.line_width > 0 ? options.line_width : std::max(1.0, 2.5 * size / 1024);
    style.marker = options.marker_radius > 0 ? options.marker_radius : std::max(3.0, 9.0 * size / 1024);

    GlSession session;
    const Programs& prog = programs(session.context_id());
    Target target(options.width, options.height, options.samples);
    glViewport(0, 0, options.width, options.height);
    const auto& bg = options.background;
    glClearColor(bg[0] / 255.f, bg[1] / 255.f, bg[2] / 255.f, bg[3] / 255.f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_BLEND);
    // Colour blends over what is there; alpha accumulates coverage, so a transparent background
    // stays transparent only where nothing was drawn.
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

    // Surfaces: the mesh in 3D, the image rectangle in the image plane.
    Geometry surface;
    Texture texture;
    std::vector<std::unique_ptr<Texture>> chart_textures;  // GL handles do not move
    bool textured = false;
    Eigen::Vector4d uv_transform(1, 1, 0, 0);
    if (three_d) {
        fill(surface, mesh_vertices(*scene.mesh, mode == RenderMode::paths));
        if (mode == RenderMode::textured && !scene.chart_images.empty()) {
            // Several charts (issue 13): each chart's faces with its own image.
            for (int c : scene.mesh->chart)
                if (c < 0 || c >= int(scene.chart_images.size()) || !scene.chart_images[std::size_t(c)])
                    throw BadInput("", "chart " + std::to_string(c) + " has no image to draw it with");
            for (const Image* img : scene.chart_images) {
                chart_textures.push_back(std::make_unique<Texture>());
                upload_texture(*chart_textures.back(), *img, false);
            }
            textured = true;
        } else if (mode == RenderMode::textured) {
            upload_texture(texture, *scene.image, false);
            textured = true;
        } else if (mode == RenderMode::checker) {
            // Squares in image pixels: a square of the image is (c / W) x (c / H) in UV.
            const double w = scene.image ? scene.image->width : 1, h = scene.image ? scene.image->height : 1;
            const Eigen::AlignedBox2d box = uv_box(scene, mode);
            const double extent = std::max(box.sizes().x() * w, box.sizes().y() * h);
            const double cell = (extent > 0 ? extent : std::max(w, h)) / std::max(1, options.checker_cells);
            // The texture is a 2 x 2 tile repeated: two cells per unit of texture coordinate.
            uv_transform = Eigen::Vector4d(w / (2 * cell), h / (2 * cell), 0, 0);
            uv_transform.z() = -box.min().x() * uv_transform.x();
            uv_transform.w() = -box.min().y() * uv_transform.y();
            upload_texture(texture, checker_texture(2, 2, 64), true);
            textured = true;
        }
    } else {
        const float a = float(cam.uv_aspect);
        std::vector<MeshVertex> quad;
        for (const auto& c : {std::array<float, 2>{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
            quad.push_back({{c[0] * a, c[1], 0}, {0, 0, 1}, {c[0], c[1]}, {1, 1, 1}});
        fill(surface, quad);
        upload_texture(texture, *scene.image, false);
        textured = true;
    }
    glUseProgram(prog.mesh);
    set_matrix(prog.mesh, "u_view", cam.view);
    set_matrix(prog.mesh, "u_proj", cam.projection);
    glUniform1i(glGetUniformLocation(prog.mesh, "u_texture"), 0);
    glUniform1i(glGetUniformLocation(prog.mesh, "u_textured"), textured ? 1 : 0);
    glUniform4f(glGetUniformLocation(prog.mesh, "u_uv_transform"), float(uv_transform[0]), float(uv_transform[1]),
                float(uv_transform[2]), float(uv_transform[3]));
    glUniform1i(glGetUniformLocation(prog.mesh, "u_shading"), three_d && options.shading ? 1 : 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture.id);
    if (three_d) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
        // Pushes the surface back by about a line's width of slope, so marks drawn on it show.
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(float(std::max(1.0, style.line)), 4.0f);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glBindVertexArray(surface.vao.id);
    if (chart_textures.empty()) {
        glDrawArrays(GL_TRIANGLES, 0, surface.count);
    } else {  // runs of faces of one chart, each with its chart's texture
        const std::vector<int>& chart = scene.mesh->chart;
        for (std::size_t f = 0; f < chart.size();) {
            std::size_t g = f;
            while (g < chart.size() && chart[g] == chart[f]) ++g;
            glBindTexture(GL_TEXTURE_2D, chart_textures[std::size_t(chart[f])]->id);
            glDrawArrays(GL_TRIANGLES, GLint(3 * f), GLsizei(3 * (g - f)));
            f = g;
        }
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    check_gl("drawing the surface");

    // Marks: lines, then feature markers.
    std::vector<MarkVertex> thin, thick, points;
    auto uv_point = [&](const Vec2& uv) { return Vec3(uv.x() * cam.uv_aspect, uv.y(), 0); };
    if (mode == RenderMode::uv || mode == RenderMode::paths) {
        const TexturedMesh& m = *scene.mesh;
        const auto kind = edge_kinds(m);
        std::map<std::pair<int, int>, bool> drawn;  // inner UV edges once (two faces share them)
        for (std::size_t f = 0; f < m.mesh.faces.size(); ++f)
            for (int k = 0; k < 3; ++k) {
                const int k1 = (k + 1) % 3;
                const Rgba& colour = kind[f][k] == kBorder ? kMeshBorderColour : kPathColour;
                if (mode == RenderMode::uv) {
                    const int a = m.uv_faces[f][k], b = m.uv_faces[f][k1];
                    const Vec3 pa = uv_point(m.uvs[a]), pb = uv_point(m.uvs[b]);
                    if (kind[f][k] != kInner) add_segment(thick, pa, pb, colour);
                    else if (drawn.emplace(std::minmax(a, b), true).second) add_segment(thin, pa, pb, {1, 1, 1, 1});
                } else if (kind[f][k] != kInner) {
                    add_segment(thick, m.mesh.positions[m.mesh.faces[f][k]], m.mesh.positions[m.mesh.faces[f][k1]], colour);
                }
            }
    }
    if (!thin.empty()) {
        // A dense mesh would hide the image under white: the wire fades as its edges get shorter
        // on screen (fully 0.55 opaque from 12 pixels, 0.08 at 2 pixels and below).
        double length = 0;
        for (std::size_t i = 0; i < thin.size(); i += 2) {
            const Vec3 a = cam.project(Vec3(thin[i].pos[0], thin[i].pos[1], thin[i].pos[2]));
            const Vec3 b = cam.project(Vec3(thin[i + 1].pos[0], thin[i + 1].pos[1], thin[i + 1].pos[2]));
            length += (a - b).head<2>().norm();
        }
        const float alpha = float(0.55 * std::clamp(length / (thin.size() / 2) / 12.0, 0.15, 1.0));
        for (MarkVertex& v : thin) v.colour[3] = alpha;
    }
    if (mode == RenderMode::triangulation) {
        const FeatureTriangulation& t = *scene.triangulation;
        for (std::size_t e = 0; e < t.edges.size(); ++e) {
            const bool on_border = e < t.edge_on_border.size() && t.edge_on_border[e];
            add_segment(thick, uv_point(t.points[t.edges[e][0]]), uv_point(t.points[t.edges[e][1]]),
                        on_border ? kMeshBorderColour : kPathColour);
        }
    }
    if (!three_d) {  // the image's frame
        const Vec3 c[4] = {uv_point({0, 0}), uv_point({1, 0}), uv_point({1, 1}), uv_point({0, 1})};
        for (int k = 0; k < 4; ++k) add_segment(thin, c[k], c[(k + 1) % 4], {0.3f, 0.3f, 0.3f, 1});
    }
    if (mode == RenderMode::paths)
        for (std::size_t i = 0; i < scene.feature_vertex.size(); ++i) {
            const Vec3& p = scene.mesh->mesh.positions[scene.feature_vertex[i]];
            points.push_back({{float(p.x()), float(p.y()), float(p.z())}, {}});
            const Rgba c = rgba(feature_colour(int(i)));
            std::copy(c.begin(), c.end(), points.back().colour);
        }
    if (mode == RenderMode::uv || mode == RenderMode::triangulation) {
        const std::vector<Vec2>& uvs = !scene.feature_uv.empty() || !scene.triangulation ? scene.feature_uv
                                                                                          : scene.triangulation->points;
        for (std::size_t i = 0; i < uvs.size(); ++i) {
            const Vec3 p = uv_point(uvs[i]);
            const Rgba c = rgba(feature_colour(int(i)));
            points.push_back({{float(p.x()), float(p.y()), float(p.z())}, {c[0], c[1], c[2], c[3]}});
        }
    }

    // Marks are pulled towards the eye by a few pixels' worth of world length at the mesh's
    // distance, so a marker disc is not cut by the curved surface it sits on, yet stays hidden
    // behind the surface in front of it.
    double pixel_world = 0;
    if (three_d) pixel_world = 2 * (cam.eye - cam.target).norm() * std::tan(cam.fovy / 2) / options.height;
    const float line_pull = float(1.0 * pixel_world), marker_pull = float(style.marker * pixel_world);

    auto draw_marks = [&](GLuint program, const std::vector<MarkVertex>& v, GLenum prim, const char* size_name,
                          double size_px, float pull_world) {
        if (v.empty()) return;
        Geometry g;
        fill(g, v);
        glUseProgram(program);
        set_matrix(program, "u_view", cam.view);
        set_matrix(program, "u_proj", cam.projection);
        glUniform1f(glGetUniformLocation(program, "u_pull"), pull_world);
        glUniform2f(glGetUniformLocation(program, "u_viewport"), float(options.width), float(options.height));
        glUniform1f(glGetUniformLocation(program, size_name), float(size_px));
        glDrawArrays(prim, 0, g.count);
    };
    draw_marks(prog.line, thin, GL_LINES, "u_width", std::max(1.0, 0.45 * style.line), line_pull);
    draw_marks(prog.line, thick, GL_LINES, "u_width", style.line, line_pull);
    draw_marks(prog.point, points, GL_POINTS, "u_radius", style.marker, marker_pull);
    check_gl("drawing the marks");
    return target.read();
}

std::string render_backend() {
    GlSession session;
    return session.renderer();
}

}  // namespace ctmap
