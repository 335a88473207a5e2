/// \file gl_resources.h
/// OpenGL objects of the renderer (render_map.h): owning handles, the compiled shader programs
/// (mesh, lines, points), textures uploaded from images, and the error check. OpenGL 3.3 core;
/// every call needs the current context of a GlSession (gl_context.h).
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <cstdint>

#include "ctmap/io/image.h"

namespace ctmap {

/// An OpenGL object name, deleted with the handle.
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
inline void delete_program(GLsizei, const GLuint* id) { glDeleteProgram(*id); }
using Buffer = GlHandle<glDeleteBuffers>;
using VertexArray = GlHandle<glDeleteVertexArrays>;
using Texture = GlHandle<glDeleteTextures>;
using Renderbuffer = GlHandle<glDeleteRenderbuffers>;
using Framebuffer = GlHandle<glDeleteFramebuffers>;
using Program = GlHandle<delete_program>;

/// Throws InternalError naming `where` when OpenGL has recorded an error.
void check_gl(const char* where);

/// The compiled programs, kept with the (process-lifetime) context: compiling them costs more
/// than drawing a small mesh.
struct Programs {
    std::uint64_t context = 0;
    GLuint mesh = 0, line = 0, point = 0;
};

/// The programs for the context `context_id` (GlSession::context_id), compiled on first use.
/// \pre the session's lock is held.
const Programs& programs(std::uint64_t context_id);

/// Uploads `img` as a mipmapped texture into `tex` (a new texture name) with trilinear (and,
/// where offered, anisotropic) filtering; `repeat` tiles it. Throws BadInput naming the image
/// when it is larger than the context's texture limit.
void upload_texture(Texture& tex, const Image& img, bool repeat);

}  // namespace ctmap
