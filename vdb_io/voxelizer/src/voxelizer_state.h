#pragma once
// What the Voxelizer's source files share (voxelizer.cpp, level_set.cpp):
// the state behind svo::Voxelizer, and the call bracket for interrupters.
#include <chrono>
#include <fmt/format.h>
#include <memory>
#include <string>
#include <utility>

#include "svo/core/interrupt.h"
#include "svo/gl/context.h"
#include "svo/voxelizer.h"

namespace svo {
namespace detail {

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// Brackets a call with the interrupter's start() and end(), on every path
/// out, and turns it into the checkpoint svo's stages poll.
class InterruptScope {
public:
    InterruptScope(openvdb::util::NullInterrupter* interrupter, const char* what) : interrupter_(interrupter)
    {
        if (interrupter_) interrupter_->start(what);
    }
    ~InterruptScope()
    {
        if (interrupter_) interrupter_->end();
    }
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;

    Checkpoint checkpoint() const
    {
        if (!interrupter_) return {};
        auto* i = interrupter_;
        return Checkpoint([i](int percent) { return i->wasInterrupted(percent); });
    }

private:
    openvdb::util::NullInterrupter* interrupter_;
};

} // namespace detail

struct Voxelizer::Impl {
    DeviceOptions device;
    std::unique_ptr<gl::Context> context;
    double unreportedEglMs = 0;  // the context's creation, until a call's statistics take it
    gl::ProgramStats reported;   // the context's program statistics already handed to a call

    /// The GL context, created on first use: a CPU-only user never needs one.
    gl::Context& gl()
    {
        if (!context) {
            context = std::make_unique<gl::Context>(
                gl::ContextOptions{device.device, device.glDebug, device.programCache});
            unreportedEglMs = context->info().setupMs;
        }
        return *context;
    }

    /// Start-up work since the last call that reported it; new program cache
    /// warnings go to `warnings`.
    StartupStats takeStartup(std::vector<std::string>& warnings)
    {
        StartupStats s;
        s.eglMs = std::exchange(unreportedEglMs, 0.0);
        if (!context) return s;
        const gl::ProgramStats& now = context->programStats();
        s.programMs = now.ms - reported.ms;
        s.programsCompiled = now.compiled - reported.compiled;
        s.programsLoaded = now.loaded - reported.loaded;
        s.programsRefused = now.refused - reported.refused;
        s.programCache = context->info().programCache;
        warnings.insert(warnings.end(), now.warnings.begin() + std::ptrdiff_t(reported.warnings.size()),
                        now.warnings.end());
        reported = now;
        return s;
    }

    /// Backend::Auto's choice, measured (bench/results/nvidia-h100/compute.md):
    /// on an H100 the compute backend's voxelize stage is 7-70 times faster
    /// than rasterization; on llvmpipe the two are within a factor of 2 either
    /// way, and the raster backend, validated longest, stays. With `create`
    /// false and no context yet, EGL tells a software device without creating
    /// one (its first device; a context may still fall back to another).
    Backend autoBackend(bool create = true)
    {
        const bool software =
            context || create ? gl().info().software : gl::softwareDevice(device.device);
        return software ? Backend::Raster : Backend::Compute;
    }

    /// Where a call runs, in the statistics: the GPU's names, or the CPU reference.
    void describeBackend(VoxelizeStats& stats, Backend backend)
    {
        const bool cpu = backend == Backend::Cpu;
        stats.backend = cpu ? "cpu" : backend == Backend::Compute ? "compute" : "raster";
        stats.device = cpu ? "cpu" : describe();
        stats.renderer = cpu ? "cpu" : gl().info().renderer;
    }

    std::string describe()
    {
        const auto& i = gl().info();
        std::string exts;
        for (const auto& e : i.extensionsUsed) exts += ", " + e;
        return fmt::format("{} | {} | {} ({}{})", i.vendor, i.renderer, i.version, i.eglDevice, exts);
    }
};

} // namespace svo
