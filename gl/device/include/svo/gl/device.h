#pragma once
/// @file device.h
/// @brief svo::gl::Device: the GL context a pipeline runs on, created on first
/// use, and the start-up work each call paid for.
///
/// A CPU-only caller never creates a context; the first GPU call does (or
/// start(), to overlap it with other work). The Device reports start-up once:
/// takeStartup() hands over what was paid since the previous report.
///
/// Without GL (no libEGL or libOpenGL to load, or no EGL display that makes
/// an OpenGL 4.5 context) context() throws svo::DeviceError, and withoutGl()
/// tells the pipelines to run Backend::Auto on the CPU instead.
#include <memory>
#include <string>
#include <vector>

#include "svo/core/option_info.h"
#include "svo/gl/context.h"

namespace svo {

/// @brief Which GPU a Device (and so a Voxelizer) uses.
struct DeviceOptions {
    /// "" ($SVO_EGL_DEVICE, else "auto"), "auto" (hardware first, then
    /// Mesa's software renderer), "hardware", "software", or an EGL device index.
    std::string device;
    bool glDebug = false; ///< print GL debug messages to stderr
    /// Folder of cached GL program binaries, so that a new Device (in this
    /// process or a later one) loads its programs instead of compiling them:
    /// "" ($SVO_PROGRAM_CACHE when set, where empty or "off" means none; else
    /// $XDG_CACHE_HOME/svo/programs, else ~/.cache/svo/programs), "off", or a
    /// folder. Entries are keyed by the GL driver and the programs' full
    /// source; one the driver refuses is compiled again and replaced. A folder
    /// that cannot be written never fails a call (one warning in the call's
    /// statistics). Drivers with no program binary formats have no cache.
    std::string programCache;
};

/// @brief Each option of DeviceOptions, declared once for every front end
/// (svo/core/option_info.h).
template <typename Visit>
void forEachOption(DeviceOptions& o, Visit&& visit)
{
    visit(OptionInfo{"DeviceOptions::device", "device",
                     "EGL device: auto, hardware, software or an index (default: $SVO_EGL_DEVICE, else auto)"},
          o.device);
    visit(OptionInfo{"DeviceOptions::glDebug", "gl_debug", "Print GL debug messages"}, o.glDebug);
    visit(OptionInfo{"DeviceOptions::programCache", "program_cache",
                     "Folder of cached GL program binaries; off for none (default: $SVO_PROGRAM_CACHE, else "
                     "$XDG_CACHE_HOME/svo/programs)"},
          o.programCache);
}

/// @brief Start-up work a call paid for: the GL context and the programs it
/// made. All zero on a warm Device whose programs are made.
struct StartupStats {
    double eglMs = 0;          ///< creating the EGL display and GL context (the first GPU use)
    double programMs = 0;      ///< making programs: loading them from the cache or compiling them
    int programsCompiled = 0;  ///< compiled from source (those the cache refused included)
    int programsLoaded = 0;    ///< loaded from the program cache
    int programsRefused = 0;   ///< cache entries damaged or refused by the driver: compiled again, replaced
    std::string programCache;  ///< the program cache folder, "" when off
};

namespace gl {

/// @brief The GL context a pipeline runs on, created on first use, and the
/// start-up it has not yet reported. Movable, not copyable.
class Device {
public:
    /// @brief A Device that creates no context yet. Throws nothing.
    explicit Device(const DeviceOptions& options = {});
    ~Device();
    Device(Device&&) noexcept;
    Device& operator=(Device&&) noexcept;

    /// @brief The GL context, created on first use.
    /// @throw svo::DeviceError when no usable GPU or driver is found; a Device
    ///        that failed once keeps the reason and throws it again without
    ///        trying again.
    Context& context();
    /// @brief Whether this Device's work has no GL to run on, so that
    /// Backend::Auto runs on the CPU: the device option (or SVO_EGL_DEVICE)
    /// leaves the choice to svo ("" or "auto") and no GL library can be loaded
    /// or, with @a create, no context can be made (it is made now, as
    /// context() would). A device named by the caller is never given up for
    /// the CPU: its failure is the call's. Throws nothing.
    /// @param create with false and no context yet, only the GL libraries are
    ///        tried (a display is known only once tried)
    bool withoutGl(bool create = true);
    /// @brief Whether the caller named the device (the device option, else
    /// SVO_EGL_DEVICE, is neither "" nor "auto"): then the GL work runs there
    /// or fails, and Backend::Auto does not trade it for the CPU. Throws nothing.
    bool named() const;
    /// @brief Creates the context now (see context()).
    /// @throw as context()
    void start() { context(); }
    /// @brief Whether the context exists.
    bool started() const { return context_ != nullptr; }
    /// @brief Whether the device is a software rasterizer (llvmpipe).
    /// @param create with false and no context yet, EGL is asked about its
    ///        first device without creating one
    /// @throw as context() when @a create makes the context
    bool software(bool create = true);
    /// @brief "vendor | renderer | version (EGL device, extensions used)";
    /// creates the context if needed.
    /// @throw as context()
    std::string describe();
    /// @brief The start-up paid since the last call to this: the context's
    /// creation if not yet reported, and the programs made since.
    /// @param warnings receives the program cache's new warnings
    StartupStats takeStartup(std::vector<std::string>& warnings);
    /// @brief Frees the context's scratch buffers (nothing when there is no context).
    void releaseScratch();

private:
    DeviceOptions options_;
    std::unique_ptr<Context> context_;
    double unreportedEglMs_ = 0; // the context's creation, until takeStartup reports it
    ProgramStats reported_;      // the programs' statistics already reported
    std::string failed_;         // why the context could not be made; "" until a failure
};

} // namespace gl
} // namespace svo
