#pragma once
/// @file context.h
/// @brief svo::gl::Context: a headless OpenGL 4.5 core context through EGL, with no window system.
///
/// Device choice: EGL_EXT_platform_device devices are enumerated; hardware
/// devices are tried before software ones (Mesa llvmpipe), then Mesa's
/// surfaceless platform and the default display. `device` (or the environment
/// variable SVO_EGL_DEVICE when the option is empty) narrows the choice:
/// "auto", "hardware", "software", or a device index as listed by
/// `svo glinfo`.
///
/// Adoption: with ContextOptions::adoptCurrent the Context wraps the OpenGL
/// context that is current on the calling thread (a host's window made by
/// GLFW, Qt, ...), through EGL or GLX. svo then draws and computes in the
/// host's context (into its framebuffers, with its objects) and neither
/// creates nor destroys it.
///
/// Currency: the context is current only inside a Scope. A Scope saves what
/// the thread had current (an EGL context of any display, or a GLX context,
/// such as a host application's window), makes this context current, and puts
/// the saved one back when it ends, on every path out. So svo can be called
/// from inside a host that renders with its own context.
///
/// The context also owns what repeated work reuses: linked programs (made on
/// first use, by their files) and scratch buffers (kept at their largest size
/// until releaseScratch()).
///
/// Program cache: a program is loaded from a binary that an earlier context
/// of the same driver stored in the cache folder (ContextOptions::programCache),
/// and compiled, then stored, only when there is none the driver takes. The
/// cache never fails a call: a damaged or refused entry is compiled again and
/// replaced, a folder that cannot be written gives one warning
/// (ProgramStats::warnings). A driver with no program binary formats has no cache.
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>

#include "svo/gl/context_info.h"
#include "svo/gl/context_options.h"
#include "svo/gl/program_stats.h"
#include "svo/gl/shader_files.h"

namespace svo::gl {

class Program;
class Buffer;

/// @brief Why no OpenGL can be loaded in this process: the library that is
/// missing (libEGL.so.1, or both libOpenGL.so.0 and libGL.so.1) and the
/// loader's words, or "" when they load. svo links no GL library (libepoxy
/// loads them on first use), so a program that never makes a Context runs
/// where there is none. Tries the libraries once per process; creates no
/// context; throws nothing.
/// @return the reason, or "" when the libraries load
std::string openGlMissing();

/// @brief Whether the EGL device a Context would try first is a software
/// rasterizer (EGL_MESA_device_software: llvmpipe), asked without creating a
/// context, which costs far less than making one. Throws nothing.
/// @param device as ContextOptions::device ("": SVO_EGL_DEVICE, else "auto")
/// @return false also when EGL lists no devices or cannot be loaded
bool softwareDevice(const std::string& device);

/// @brief Owns an EGL context on a display shared with other Contexts of the same
/// device (the display is terminated with its last Context). Not copyable.
/// One thread at a time may use a Context; different Contexts may be used
/// from different threads at once.
class Context {
public:
    /// @brief Creates (or, with ContextOptions::adoptCurrent, wraps) the
    /// context. Leaves the calling thread's current context as it was.
    /// @throw svo::DeviceError with a one-line reason when no GL 4.5 core
    ///        context can be had: no GL library to load (openGlMissing()), no
    ///        EGL display or device that makes one, or, adopting, none current
    ///        or one older than 4.5
    /// @throw svo::OutOfMemory when GL runs out of memory setting it up
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    /// @brief What the context is and offers, found at construction.
    const ContextInfo& info() const;

    /// @brief Makes the context current for the scope's lifetime, then restores
    /// the thread's previous context. Nested scopes of the same context are free.
    class Scope {
    public:
        /// @brief Makes @a context current, saving the thread's current one.
        /// @throw svo::DeviceError when it cannot be made current (current on
        ///        another thread, typically)
        explicit Scope(const Context& context);
        /// @brief Puts the saved context back; never throws.
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

        struct Saved; ///< the thread's previous current context

    private:
        std::unique_ptr<Saved> saved_; ///< null when the context was already current
    };

    /// @brief The linked program of these shader files, made on first use:
    /// loaded from the program cache, else compiled (and stored there).
    /// @param library the calling layer's embedded shaders (its svo_embed_files
    ///        function), looked up before the files core shares with every
    ///        shader (gpu_layout.h, overlap.glsl)
    /// @param files   the program's stages, by file name
    /// @return the program, owned by the context
    /// @throw svo::DeviceError when a file is unknown or a shader does not
    ///        compile or link; svo::OutOfMemory or svo::DeviceError on a GL
    ///        error. A program cache that fails never throws.
    const Program& program(const ShaderFiles& library, std::initializer_list<const char*> files) const;
    /// @brief What program() has cost so far.
    const ProgramStats& programStats() const;
    /// @brief A scratch buffer of at least @a bytes, reused across calls; a
    /// larger request frees the old one first. Contents are undefined.
    /// @param what names the buffer, and so which scratch buffer is meant
    /// @throw svo::OutOfMemory or svo::DeviceError as Buffer's constructor
    const Buffer& scratch(const char* what, uint64_t bytes) const;
    /// @brief The scratch buffer named @a what, taken out of the context for
    /// a result the caller owns for a while (a grid it reads back, or hands
    /// on): when it holds at least @a bytes it is reused, else a new buffer
    /// of @a bytes is made. Give it back with returnScratch(). Reused memory
    /// is what makes a warm call cheap: a driver may commit a new buffer's
    /// memory only when it is first written, at a cost per page.
    /// @param what  names the buffer, as for scratch()
    /// @param bytes the least size
    /// @return a buffer of at least @a bytes; contents undefined
    /// @throw svo::OutOfMemory or svo::DeviceError as Buffer's constructor
    Buffer lendScratch(const char* what, uint64_t bytes) const;
    /// @brief Keeps @a buffer as the scratch buffer named @a what when it is
    /// larger than the one held (or none is), else frees it.
    void returnScratch(const char* what, Buffer&& buffer) const;
    /// @brief Frees every scratch buffer (call inside a Scope, or it makes one).
    void releaseScratch() const;
    /// @brief Frees the scratch buffer named @a what, if there is one: a large
    /// buffer no longer needed, so that what the caller allocates next does
    /// not add to it (call inside a Scope, or it makes one).
    void releaseScratch(const char* what) const;
    /// @brief Bytes of scratch buffers held.
    uint64_t scratchBytes() const;
    /// @brief Bytes of memory the device has free now: video memory where the
    /// driver tells (GL_NVX_gpu_memory_info), host memory for a CPU rasterizer,
    /// whose buffers live there.
    /// @return the bytes; 0 when unknown
    /// @throw svo::OutOfMemory or svo::DeviceError on a GL error (checkGl)
    uint64_t availableMemory() const;
    /// @brief The most bytes of one buffer the shaders may address, which work
    /// must stay within (tile or refuse). A hardware driver's limit is real
    /// (past it, voxels are lost without an error), while Mesa's llvmpipe
    /// reports a small limit but addresses whole buffers (docs/design.md says
    /// what was measured).
    /// @return info().maxStorageBlock, or 0 (no limit but the buffer's) on a
    ///         CPU rasterizer; SVO_GL_MAX_STORAGE_BLOCK (bytes), where set,
    ///         lowers it (for tests)
    uint64_t shaderBufferLimit() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace svo::gl
