// EGL surfaceless context creation (see gl_context.h). Kept apart so that EGL's headers and the
// platform choice stay out of the drawing code.
#include "ctmap/render/gl_context.h"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <cstring>
#include <memory>
#include <sstream>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

constexpr const char* kPackages =
    " (Debian: libegl1 and libopengl0 with Mesa's libegl-mesa0 and libgl1-mesa-dri, whose llvmpipe "
    "renders without a GPU or a display)";

std::string egl_error(const char* what) {
    std::ostringstream os;
    os << "off-screen OpenGL: " << what << " failed (EGL error 0x" << std::hex << eglGetError() << ")" << kPackages;
    return os.str();
}

bool has_extension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

/// The EGL display: Mesa's surfaceless platform (no window system at all), else the first EGL
/// device (a GPU driver without Mesa's extension), else the default display.
EGLDisplay open_display() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
    }
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (get_platform_display && query_devices && has_extension(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[8];
        EGLint n = 0;
        if (query_devices(8, devices, &n) && n > 0) {
            EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
            if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
        }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
    throw InternalError(egl_error("opening an EGL display (surfaceless, device or default)"));
}

/// The process-wide context; destroyed at exit, before Mesa's own exit handlers (it registers
/// them during eglInitialize, which runs inside this object's construction).
struct Context {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::uint64_t id = 0;
    std::string renderer;

    Context() {
        static std::uint64_t next_id = 0;
        display = open_display();
        if (!eglBindAPI(EGL_OPENGL_API)) {
            eglTerminate(display);
            throw InternalError(egl_error("binding the desktop OpenGL API"));
        }
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
            // Drawing goes to framebuffer objects only, so any config that renders desktop GL will do.
            const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
            EGLint n = 0;
            if (!eglChooseConfig(display, want, &config, 1, &n) || n < 1) {
                eglTerminate(display);
                throw InternalError(egl_error("choosing an EGL config for desktop OpenGL"));
            }
        }
        context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
        if (context == EGL_NO_CONTEXT) {
            eglTerminate(display);
            throw InternalError(egl_error("creating an OpenGL 3.3 core context"));
        }
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            eglDestroyContext(display, context);
            eglTerminate(display);
            throw InternalError(egl_error("making the OpenGL context current without a surface"));
        }
        renderer = std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ", " +
                   reinterpret_cast<const char*>(glGetString(GL_VERSION));
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        id = ++next_id;
    }
    ~Context() {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        eglTerminate(display);
        eglReleaseThread();
    }
};

std::mutex& context_mutex() {
    static std::mutex m;
    return m;
}

}  // namespace

GlSession::GlSession() : lock_(context_mutex()) {
    // Built under the lock. A constructor that throws leaves the static uninitialised, so a later
    // call tries again; a successful one registers the destructor after Mesa's exit handlers, so
    // it runs before them.
    static const std::unique_ptr<Context> context = std::make_unique<Context>();
    if (!eglMakeCurrent(context->display, EGL_NO_SURFACE, EGL_NO_SURFACE, context->context))
        throw InternalError(egl_error("making the OpenGL context current"));
    context_id_ = context->id;
    renderer_ = context->renderer;
}

GlSession::~GlSession() {
    // Release the context so that another thread's session can make it current.
    eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace ctmap
