#include "svo/gl/context.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>

#define EGL_EGLEXT_PROTOTYPES 0
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "gl_api.h"
#include "svo/core/error.h"

namespace svo::gl {
namespace {

void APIENTRY debugCallback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                              const void*)
{
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    fmt::print(stderr, "GL debug [{}]: {}\n", type == GL_DEBUG_TYPE_ERROR ? "error" : "note", message);
}

struct Candidate {
    EGLenum platform;
    void* native;
    std::string name;
    bool software;
};

std::string eglErrorName(EGLint e) { return fmt::format("EGL error 0x{:04x}", unsigned(e)); }

} // namespace

struct Context::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    ContextInfo info;

    ~Impl()
    {
        if (display != EGL_NO_DISPLAY) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
            eglTerminate(display);
        }
    }

    /// Tries one display; returns an empty string on success, else why not.
    std::string tryCandidate(const Candidate& c, bool debug)
    {
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        EGLDisplay d = EGL_NO_DISPLAY;
        if (c.platform == 0) d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        else if (getPlatformDisplay) d = getPlatformDisplay(c.platform, c.native, nullptr);
        if (d == EGL_NO_DISPLAY) return "no display";
        EGLint major = 0, minor = 0;
        if (!eglInitialize(d, &major, &minor)) return "eglInitialize failed: " + eglErrorName(eglGetError());
        if (!eglBindAPI(EGL_OPENGL_API)) {
            eglTerminate(d);
            return "no desktop OpenGL API";
        }
        const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        if (!eglChooseConfig(d, configAttribs, &config, 1, &count) || count == 0) config = nullptr; // EGL_KHR_no_config_context
        const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
        EGLContext ctx = eglCreateContext(d, config, EGL_NO_CONTEXT, ctxAttribs);
        if (ctx == EGL_NO_CONTEXT) {
            const EGLint err = eglGetError();
            eglTerminate(d);
            return "no OpenGL 4.5 core context (" + eglErrorName(err) + ")";
        }
        if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
            const EGLint err = eglGetError();
            eglDestroyContext(d, ctx);
            eglTerminate(d);
            return "cannot make the context current without a surface (" + eglErrorName(err) + ")";
        }
        display = d;
        context = ctx;
        info.eglDevice = c.name;
        return {};
    }
};

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>())
{
    std::string want = options.device;
    if (want.empty()) {
        const char* env = std::getenv("SVO_EGL_DEVICE");
        want = env && *env ? env : "auto";
    }
#ifndef NDEBUG
    const bool debug = true;
#else
    const bool debug = options.debug;
#endif

    std::vector<Candidate> candidates;
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (queryDevices && queryDeviceString) {
        EGLDeviceEXT devices[32];
        EGLint n = 0;
        if (queryDevices(32, devices, &n)) {
            std::vector<Candidate> hardware, software;
            for (EGLint i = 0; i < n; ++i) {
                const char* ext = queryDeviceString(devices[i], EGL_EXTENSIONS);
                const bool sw = ext && std::strstr(ext, "EGL_MESA_device_software");
                const char* drm = ext && std::strstr(ext, "EGL_EXT_device_drm")
                                      ? queryDeviceString(devices[i], EGL_DRM_DEVICE_FILE_EXT)
                                      : nullptr;
                Candidate c{EGL_PLATFORM_DEVICE_EXT, devices[i],
                            fmt::format("EGL device {}{}", i, sw ? " (software)" : drm ? fmt::format(" ({})", drm) : ""),
                            sw};
                if (want == std::to_string(i)) candidates.push_back(c);
                (sw ? software : hardware).push_back(c);
            }
            if (want == "auto" || want == "hardware") candidates.insert(candidates.end(), hardware.begin(), hardware.end());
            if (want == "auto" || want == "software") candidates.insert(candidates.end(), software.begin(), software.end());
        }
    }
    if (want == "auto" || want == "software") {
        candidates.push_back({EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, "Mesa surfaceless platform", true});
        candidates.push_back({0, nullptr, "default EGL display", false});
    }
    if (candidates.empty())
        throw Error(fmt::format("no EGL device matches '{}' (use auto, hardware, software or a device index)", want));

    std::string reasons;
    for (const auto& c : candidates) {
        const std::string why = impl_->tryCandidate(c, debug || options.debug);
        if (why.empty()) break;
        reasons += fmt::format("{}{}: {}", reasons.empty() ? "" : "; ", c.name, why);
    }
    if (impl_->context == EGL_NO_CONTEXT)
        throw Error("cannot create a headless OpenGL 4.5 core context through EGL: " + reasons);

    ContextInfo& info = impl_->info;
    auto str = [](GLenum e) {
        const GLubyte* s = glGetString(e);
        return std::string(s ? reinterpret_cast<const char*>(s) : "?");
    };
    info.vendor = str(GL_VENDOR);
    info.renderer = str(GL_RENDERER);
    info.version = str(GL_VERSION);
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw Error(fmt::format("{} ({}) offers OpenGL {}.{}; svo needs 4.5 core", info.renderer, info.eglDevice,
                                major, minor));
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i) {
        const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && std::strcmp(e, "GL_NV_conservative_raster") == 0) info.conservativeRasterNV = true;
    }
    GLint vp[2] = {0, 0}, fw = 0, fh = 0;
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &fw);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &fh);
    info.maxViewport = std::min({vp[0], vp[1], fw, fh});
    if (debug || options.debug) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, nullptr);
        info.extensionsUsed.push_back("GL_KHR_debug");
    }
    checkGl("context creation");
}

Context::~Context() = default;

const ContextInfo& Context::info() const { return impl_->info; }

} // namespace svo::gl
