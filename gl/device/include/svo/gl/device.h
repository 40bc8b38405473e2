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

#include "svo/core/winding_tree_cache.h"
#include "svo/gl/context.h"
#include "svo/gl/device_options.h"
#include "svo/gl/program_stats.h"
#include "svo/gl/startup_stats.h"

namespace svo::gl {

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
    /// @brief Frees what the device keeps between calls: the context's
    /// scratch buffers (nothing when there is no context) and the winding tree.
    void releaseScratch();
    /// @brief The last winding tree built on this device's calls, kept for
    /// the next call over the same triangles (a level set's or solid's
    /// regions, a cluster worker's tiles), on the CPU paths too.
    WindingTreeCache& windingTrees() { return windingTrees_; }

private:
    DeviceOptions options_;
    std::unique_ptr<Context> context_;
    double unreportedEglMs_ = 0; // the context's creation, until takeStartup reports it
    ProgramStats reported_;      // the programs' statistics already reported
    std::string failed_;         // why the context could not be made; "" until a failure
    WindingTreeCache windingTrees_;
};

} // namespace svo::gl
