#pragma once
/// \file gl_context.h
/// An off-screen OpenGL 3.3 core context through EGL with no window and no display server (EGL
/// surfaceless, Mesa's llvmpipe software rasterizer when there is no GPU). The only translation
/// unit that talks to EGL; the drawing code (render_map.cpp) sees a current GL context and nothing
/// else.
#include <cstdint>
#include <mutex>
#include <string>

namespace ctmap {

/// Makes the process's off-screen OpenGL context current on the calling thread for its
/// lifetime. The context is created on first use and kept until the process exits (creating one
/// costs tens of milliseconds); sessions are serialised by a mutex, since a context is current on
/// one thread at a time. Drawing goes into framebuffer objects: there is no default framebuffer.
/// \throw InternalError naming what is missing (EGL display, OpenGL 3.3 core context) and the
///        Debian packages that provide it (libegl-mesa0, libgl1-mesa-dri).
class GlSession {
public:
    GlSession();
    ~GlSession();
    GlSession(const GlSession&) = delete;
    GlSession& operator=(const GlSession&) = delete;

    /// Changes whenever a new context was created, so callers can cache GL objects (shaders)
    /// per context.
    std::uint64_t context_id() const { return context_id_; }
    /// GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
    const std::string& renderer() const { return renderer_; }

private:
    std::unique_lock<std::mutex> lock_;
    std::uint64_t context_id_ = 0;
    std::string renderer_;
};

}  // namespace ctmap
