// OpenGL objects of the renderer: shaders, programs, textures (gl_resources.h).
#include "ctmap/render/gl_resources.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "ctmap/errors.h"

namespace ctmap {

void check_gl(const char* where) {
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(e));
        throw InternalError(std::string("OpenGL error ") + code + " while " + where);
    }
}

namespace {

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

/// Throws InternalError with OpenGL's log when the shader's or program's `status` is false
/// (deleting the object first).
void require_status(GLuint id, GLenum status, void (*get)(GLuint, GLenum, GLint*),
                    void (*get_log)(GLuint, GLsizei, GLsizei*, GLchar*), void (*remove)(GLuint), const char* what) {
    GLint ok = 0;
    get(id, status, &ok);
    if (ok) return;
    char log[2048] = {0};
    get_log(id, sizeof log, nullptr, log);
    remove(id);
    throw InternalError(std::string("OpenGL ") + what + " failed: " + log);
}

GLuint compile(GLenum type, const char* source) {
    const GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &source, nullptr);
    glCompileShader(s);
    require_status(s, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader, "shader compilation");
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
    require_status(p, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram, "program link");
    return p;
}

bool has_gl_extension(const char* name) {
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
        if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))), name) == 0) return true;
    return false;
}

}  // namespace

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

}  // namespace ctmap
