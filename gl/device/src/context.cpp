#include "svo/gl/context.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <optional>

#include <epoxy/egl.h>

#include "program_cache.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/buffer.h"
#include "svo/gl/program.h"
#include "svo/core/error.h"
#include "svo/core/host_memory.h"

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

/// The device option, or SVO_EGL_DEVICE, or "auto".
std::string deviceWanted(const std::string& option)
{
    if (!option.empty()) return option;
    const char* env = std::getenv("SVO_EGL_DEVICE");
    return env && *env ? env : "auto";
}

/// The displays to try for a device option, in order: EGL's devices
/// (hardware before software for "auto"), then Mesa's surfaceless platform
/// and the default display. Creates no context.
std::vector<Candidate> candidatesFor(const std::string& want)
{
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
    return candidates;
}

/// Why libEGL or desktop GL cannot be loaded: "" when both load. epoxy
/// loads them itself on first use, but ends the process where it cannot, so
/// they are tried here first, and kept loaded. Asked once per process.
std::string librariesMissing()
{
    static const std::string why = [] {
        if (!dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL)) {
            const char* e = dlerror();
            return fmt::format("libEGL.so.1 cannot be loaded ({})", e ? e : "not found");
        }
        // epoxy takes desktop GL's core entry points from libOpenGL.so.0 (GLVND), else libGL.so.1.
        if (!dlopen("libOpenGL.so.0", RTLD_NOW | RTLD_LOCAL) && !dlopen("libGL.so.1", RTLD_NOW | RTLD_LOCAL))
            return std::string("neither libOpenGL.so.0 nor libGL.so.1 can be loaded");
        if (!epoxy_has_egl()) return std::string("libepoxy cannot load libEGL.so.1");
        return std::string();
    }();
    return why;
}

std::string eglErrorName(EGLint e) { return fmt::format("EGL error 0x{:04x}", unsigned(e)); }

/// EGL displays are per device and per process: every Context on a device
/// shares one, and eglTerminate would pull it from under the others. Count
/// the users and terminate with the last.
std::mutex displayMutex;
std::map<EGLDisplay, int> displayUsers;

void retainDisplay(EGLDisplay d)
{
    std::lock_guard<std::mutex> lock(displayMutex);
    ++displayUsers[d];
}

void releaseDisplay(EGLDisplay d)
{
    std::lock_guard<std::mutex> lock(displayMutex);
    if (--displayUsers[d] > 0) return;
    displayUsers.erase(d);
    eglTerminate(d);
}

/// Terminates a display that a failed attempt initialized, unless a Context uses it.
void dropUnusedDisplay(EGLDisplay d)
{
    std::lock_guard<std::mutex> lock(displayMutex);
    if (!displayUsers.count(d)) eglTerminate(d);
}

/// GLX entry points, found only when the host process already loaded libGLX
/// (a GLFW or Qt window on X11); svo itself never links GLX.
struct Glx {
    using GetContext = void* (*)();
    using GetDisplay = void* (*)();
    using GetDrawable = unsigned long (*)();
    using MakeContextCurrent = int (*)(void*, unsigned long, unsigned long, void*);
    GetContext getContext = nullptr;
    GetDisplay getDisplay = nullptr;
    GetDrawable getDrawable = nullptr, getReadDrawable = nullptr;
    MakeContextCurrent makeContextCurrent = nullptr;

    /// GLX's entry points when GLX is loaded: linked in, or loaded by a
    /// windowing library such as GLFW, which dlopens it privately (so
    /// RTLD_DEFAULT misses it). Looked up again until found, since the
    /// window may be opened after svo's first GL call.
    static Glx get()
    {
        static std::mutex mutex;
        static Glx found;
        const std::lock_guard<std::mutex> lock(mutex);
        if (found.getContext) return found;
        void* from = RTLD_DEFAULT; // a null handle in glibc: the global scope
        if (!dlsym(RTLD_DEFAULT, "glXGetCurrentContext")) {
            from = nullptr;
            for (const char* name : {"libGLX.so.0", "libGL.so.1", "libGL.so"})
                if ((from = dlopen(name, RTLD_LAZY | RTLD_NOLOAD))) break; // a reference only if already loaded
            if (!from) return {};
        }
        Glx g;
        g.getContext = reinterpret_cast<GetContext>(dlsym(from, "glXGetCurrentContext"));
        g.getDisplay = reinterpret_cast<GetDisplay>(dlsym(from, "glXGetCurrentDisplay"));
        g.getDrawable = reinterpret_cast<GetDrawable>(dlsym(from, "glXGetCurrentDrawable"));
        g.getReadDrawable = reinterpret_cast<GetDrawable>(dlsym(from, "glXGetCurrentReadDrawable"));
        g.makeContextCurrent = reinterpret_cast<MakeContextCurrent>(dlsym(from, "glXMakeContextCurrent"));
        if (!g.getContext || !g.getDisplay || !g.getDrawable || !g.getReadDrawable || !g.makeContextCurrent)
            return {};
        found = g;
        return found;
    }
};

} // namespace

/// What the thread had current before a Scope: EGL (for the OpenGL API, and
/// the bound API) and GLX.
struct Context::Scope::Saved {
    EGLenum api = EGL_OPENGL_ES_API;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLSurface draw = EGL_NO_SURFACE, read = EGL_NO_SURFACE;
    EGLContext context = EGL_NO_CONTEXT;
    void* glxDisplay = nullptr;
    unsigned long glxDraw = 0, glxRead = 0;
    void* glxContext = nullptr;

    /// Records what is current now.
    void record()
    {
        api = eglQueryAPI();
        display = eglGetCurrentDisplay();
        draw = eglGetCurrentSurface(EGL_DRAW);
        read = eglGetCurrentSurface(EGL_READ);
        context = eglGetCurrentContext();
        const Glx& glx = Glx::get();
        if (glx.getContext && (glxContext = glx.getContext())) {
            glxDisplay = glx.getDisplay();
            glxDraw = glx.getDrawable();
            glxRead = glx.getReadDrawable();
        }
    }

    /// Records what is current now and releases a GLX context, which cannot
    /// stay current beside an EGL one.
    void capture()
    {
        record();
        if (glxContext) Glx::get().makeContextCurrent(glxDisplay, 0, 0, nullptr);
    }

    /// Whether the recorded EGL (OpenGL API) or GLX context is current now.
    bool isCurrent() const
    {
        if (glxContext) return Glx::get().getContext() == glxContext;
        const EGLenum bound = eglQueryAPI();
        eglBindAPI(api);
        const bool same = context != EGL_NO_CONTEXT && eglGetCurrentContext() == context;
        eglBindAPI(bound);
        return same;
    }

    /// Puts back what record() found; false when the context could not be
    /// made current. Never throws: it runs while unwinding.
    bool restore() const
    {
        bool ok = true;
        if (context != EGL_NO_CONTEXT) {
            eglBindAPI(api);
            ok = eglMakeCurrent(display, draw, read, context);
        } else {
            eglBindAPI(EGL_OPENGL_API);
            const EGLDisplay current = eglGetCurrentDisplay();
            if (current != EGL_NO_DISPLAY) eglMakeCurrent(current, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglBindAPI(api);
        }
        if (glxContext) ok = Glx::get().makeContextCurrent(glxDisplay, glxDraw, glxRead, glxContext) && ok;
        return ok;
    }
};

struct Context::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::optional<Scope::Saved> host; ///< the adopted context (ContextOptions::adoptCurrent)
    ContextInfo info;
    // GL objects live in the context; they are deleted (inside a Scope) before it.
    mutable std::map<std::string, std::unique_ptr<Program>> programs;
    mutable std::optional<ProgramCache> programCache; // set once the GL strings are known
    mutable ProgramStats programStats;
    mutable std::map<std::string, Buffer> scratch;

    ~Impl()
    {
        if (context != EGL_NO_CONTEXT) {
            eglDestroyContext(display, context); // deferred by EGL while current elsewhere: never, by Scope
            releaseDisplay(display);
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
            dropUnusedDisplay(d);
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
            dropUnusedDisplay(d);
            return "no OpenGL 4.5 core context (" + eglErrorName(err) + ")";
        }
        if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
            const EGLint err = eglGetError();
            eglDestroyContext(d, ctx);
            dropUnusedDisplay(d);
            return "cannot make the context current without a surface (" + eglErrorName(err) + ")";
        }
        retainDisplay(d);
        display = d;
        context = ctx;
        info.eglDevice = c.name;
        return {};
    }

    /// Fills `info` from the context current now (the new or adopted one) and
    /// sets up debug output and the program cache.
    void query(const ContextOptions& options, bool debug)
    {
        auto str = [](GLenum e) {
            const GLubyte* s = glGetString(e);
            return std::string(s ? reinterpret_cast<const char*>(s) : "?");
        };
        info.vendor = str(GL_VENDOR);
        info.renderer = str(GL_RENDERER);
        info.version = str(GL_VERSION);
        info.software = info.renderer.find("llvmpipe") != std::string::npos ||
                        info.renderer.find("softpipe") != std::string::npos;
        if (info.software) {
            info.loopLimit = 65535; // gallivm's LP_MAX_TGSI_LOOP_ITERATIONS
            // llvmpipe names its vector width: "llvmpipe (LLVM 15.0.6, 256 bits)"; assume the widest otherwise.
            const size_t bits = info.renderer.find(" bits)");
            const size_t comma = info.renderer.rfind(", ", bits);
            int width = 512;
            if (bits != std::string::npos && comma != std::string::npos)
                width = std::atoi(info.renderer.c_str() + comma + 2);
            info.loopLanes = uint32_t(std::clamp(width, 32, 512) / 32);
            // SVO_LOOP_LIMIT, a smaller budget than the driver's, makes the
            // passes split their work into many dispatches on small scenes:
            // the tests use it to check that the split gives the same result.
            if (const char* env = std::getenv("SVO_LOOP_LIMIT"))
                if (const long long n = std::atoll(env); n > 64 && uint64_t(n) < info.loopLimit)
                    info.loopLimit = uint64_t(n);
        }
        GLint major = 0, minor = 0;
        glGetIntegerv(GL_MAJOR_VERSION, &major);
        glGetIntegerv(GL_MINOR_VERSION, &minor);
        if (major * 10 + minor < 45)
            throw DeviceError(fmt::format("{} ({}) offers OpenGL {}.{}; svo needs 4.5 core", info.renderer, info.eglDevice,
                                          major, minor));
        GLint n = 0;
        glGetIntegerv(GL_NUM_EXTENSIONS, &n);
        for (GLint i = 0; i < n; ++i) {
            const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
            if (e && std::strcmp(e, "GL_NV_conservative_raster") == 0) info.conservativeRasterNV = true;
            if (e && std::strcmp(e, "GL_NVX_gpu_memory_info") == 0) info.memoryInfoNVX = true;
        }
        GLint vp[2] = {0, 0}, fw = 0, fh = 0;
        glGetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
        glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &fw);
        glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &fh);
        info.maxViewport = std::min({vp[0], vp[1], fw, fh});
        GLint64 block = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
        info.maxStorageBlock = uint64_t(std::max<GLint64>(block, 0));
        if (debug || options.debug) {
            glEnable(GL_DEBUG_OUTPUT);
            glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
            glDebugMessageCallback(debugCallback, nullptr);
            info.extensionsUsed.push_back("GL_KHR_debug");
        }
        // No binary formats (Mesa without its disk cache, some drivers): no program cache.
        glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &info.programBinaryFormats);
        info.programCache = info.programBinaryFormats > 0 ? programCacheFolder(options.programCache) : std::string();
        programCache.emplace(info.programCache, info.vendor + '\0' + info.renderer + '\0' + info.version);
        checkGl("context creation");
    }
};

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>())
{
    const auto start = std::chrono::steady_clock::now();
#ifndef NDEBUG
    const bool debug = true;
#else
    const bool debug = options.debug;
#endif
    if (const std::string why = openGlMissing(); !why.empty())
        throw DeviceError("OpenGL is not available: " + why +
                          "; svo's GPU work needs EGL and an OpenGL 4.5 driver (the CPU backend needs neither)");
    if (options.adoptCurrent) {
        Scope::Saved host;
        host.record();
        if (!host.glxContext && (host.context == EGL_NO_CONTEXT || host.api != EGL_OPENGL_API))
            throw DeviceError("no desktop OpenGL context is current on this thread to adopt");
        impl_->host = host;
        impl_->info.adopted = true;
        impl_->info.eglDevice = host.glxContext ? "the host's GLX context" : "the host's EGL context";
        impl_->query(options, debug);
        impl_->info.setupMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return;
    }

    // Creation makes the new context current to query it; the caller's comes back on every path out.
    Scope::Saved previous;
    previous.capture();
    struct Restore {
        const Scope::Saved& saved;
        ~Restore() { saved.restore(); }
    } restore{previous};

    const std::string want = deviceWanted(options.device);
    const std::vector<Candidate> candidates = candidatesFor(want);
    if (candidates.empty())
        throw DeviceError(fmt::format("no EGL device matches '{}' (use auto, hardware, software or a device index)", want));

    std::string reasons;
    for (const auto& c : candidates) {
        const std::string why = impl_->tryCandidate(c, debug);
        if (why.empty()) break;
        reasons += fmt::format("{}{}: {}", reasons.empty() ? "" : "; ", c.name, why);
    }
    if (impl_->context == EGL_NO_CONTEXT)
        throw DeviceError("cannot create a headless OpenGL 4.5 core context through EGL: " + reasons);

    impl_->query(options, debug);
    impl_->info.setupMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Context::~Context()
{
    if (!impl_ || (impl_->context == EGL_NO_CONTEXT && !impl_->host)) return;
    try {
        const Scope scope(*this);
        impl_->programs.clear();
        impl_->scratch.clear();
    } catch (const std::exception&) {
        // The context cannot be made current: its objects go with it.
    }
}

const ContextInfo& Context::info() const { return impl_->info; }

std::string openGlMissing() { return librariesMissing(); }

bool softwareDevice(const std::string& device)
{
    if (!librariesMissing().empty()) return false;
    const std::vector<Candidate> candidates = candidatesFor(deviceWanted(device));
    // Only an EGL device says what it is; the fallbacks are known once tried.
    return !candidates.empty() && candidates.front().platform == EGL_PLATFORM_DEVICE_EXT &&
           candidates.front().software;
}

Context::Scope::Scope(const Context& c)
{
    if (const auto& host = c.impl_->host) {
        if (host->isCurrent()) return;
        auto saved = std::make_unique<Saved>();
        saved->capture();
        if (!host->restore()) {
            saved->restore();
            throw DeviceError("cannot make the host's OpenGL context current again on this thread; is it current on another?");
        }
        saved_ = std::move(saved);
        return;
    }
    const EGLenum api = eglQueryAPI();
    eglBindAPI(EGL_OPENGL_API);
    if (eglGetCurrentContext() == c.impl_->context) {
        eglBindAPI(api);
        return; // nested: already ours
    }
    eglBindAPI(api);
    auto saved = std::make_unique<Saved>();
    saved->capture();
    eglBindAPI(EGL_OPENGL_API);
    if (!eglMakeCurrent(c.impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c.impl_->context)) {
        const EGLint err = eglGetError();
        saved->restore();
        throw DeviceError(fmt::format("cannot make svo's OpenGL context current on this thread ({}); is it current on "
                                      "another thread?",
                                      eglErrorName(err)));
    }
    saved_ = std::move(saved);
}

Context::Scope::~Scope()
{
    if (saved_) saved_->restore();
}

const Program& Context::program(const ShaderFiles& library, std::initializer_list<const char*> files) const
{
    std::string key;
    for (const char* f : files) key += std::string(f) + ";";
    auto& slot = impl_->programs[key];
    if (!slot) {
        const Scope scope(*this);
        const auto start = std::chrono::steady_clock::now();
        ProgramStats& stats = impl_->programStats;
        ProgramCache& cache = *impl_->programCache;
        const ProgramSource source = programSource(files, library);
        ProgramCache::Lookup how = ProgramCache::Lookup::Absent;
        std::optional<Program> p = cache.load(source, how);
        if (p) {
            ++stats.loaded;
        } else {
            stats.refused += how == ProgramCache::Lookup::Refused;
            p.emplace(source, cache.enabled());
            ++stats.compiled;
            if (std::string warning = cache.store(source, *p); !warning.empty())
                stats.warnings.push_back(std::move(warning));
        }
        slot = std::make_unique<Program>(std::move(*p));
        stats.ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    return *slot;
}

const ProgramStats& Context::programStats() const { return impl_->programStats; }

namespace {

/// A new scratch buffer of at least @a bytes, in whole 64 KiB grains so that
/// slightly larger requests later reuse it.
Buffer newScratch(const char* what, uint64_t bytes)
{
    const uint64_t grain = uint64_t(1) << 16;
    return Buffer(what, std::max<uint64_t>((bytes + grain - 1) / grain * grain, grain));
}

} // namespace

const Buffer& Context::scratch(const char* what, uint64_t bytes) const
{
    Buffer& b = impl_->scratch[what];
    if (b.bytes() >= bytes && b.bytes() > 0) return b;
    const Scope scope(*this);
    b = Buffer(); // free the old buffer before the larger one is allocated
    b = newScratch(what, bytes);
    return b;
}

Buffer Context::lendScratch(const char* what, uint64_t bytes) const
{
    const Scope scope(*this);
    const auto held = impl_->scratch.find(what);
    if (held != impl_->scratch.end()) {
        Buffer b = std::move(held->second);
        impl_->scratch.erase(held);
        if (b.bytes() >= bytes && b.bytes() > 0) return b;
    } // a smaller one is freed before the new one is made
    return newScratch(what, bytes);
}

void Context::returnScratch(const char* what, Buffer&& buffer) const
{
    const Scope scope(*this);
    Buffer& held = impl_->scratch[what];
    if (buffer.bytes() > held.bytes()) held = std::move(buffer);
    else buffer = Buffer();
}

void Context::releaseScratch() const
{
    const Scope scope(*this);
    impl_->scratch.clear();
}

uint64_t Context::availableMemory() const
{
    if (impl_->info.software) return availableHostMemory();
    if (!impl_->info.memoryInfoNVX) return 0;
    const Scope scope(*this);
    constexpr GLenum kCurrentAvailableVidmemNVX = 0x9049; // GL_NVX_gpu_memory_info, in KiB
    GLint kib = 0;
    glGetIntegerv(kCurrentAvailableVidmemNVX, &kib);
    checkGl("querying free GPU memory");
    return uint64_t(std::max(kib, 0)) * 1024;
}

uint64_t Context::shaderBufferLimit() const
{
    uint64_t limit = impl_->info.software ? 0 : impl_->info.maxStorageBlock;
    // SVO_GL_MAX_STORAGE_BLOCK (bytes): a smaller limit, for the tests of the
    // paths past it on drivers without one (llvmpipe). Read each call: tests
    // set it around one call.
    if (const char* v = std::getenv("SVO_GL_MAX_STORAGE_BLOCK")) {
        const uint64_t asked = std::strtoull(v, nullptr, 10);
        if (asked && (!limit || asked < limit)) limit = asked;
    }
    return limit;
}

void Context::releaseScratch(const char* what) const
{
    const Scope scope(*this);
    impl_->scratch.erase(what);
}

uint64_t Context::scratchBytes() const
{
    uint64_t n = 0;
    for (const auto& [name, b] : impl_->scratch) n += b.bytes();
    return n;
}

} // namespace svo::gl
