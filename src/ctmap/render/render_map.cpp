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
#include "ctmap/render/gl_resources.h"
#include "ctmap/render/render_view.h"

namespace ctmap {

// ---------------------------------------------------------------------------------------------
// OpenGL (handles, programs and textures: gl_resources.h)
// ---------------------------------------------------------------------------------------------

namespace {

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
        if (patch_colours && f < m.patch.size()) c = render_detail::hsv(0.13 + 0.6180339887498949 * m.patch[f], 0.22, 0.97);
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
            const Eigen::AlignedBox2d box = render_detail::uv_box(scene, mode);
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
