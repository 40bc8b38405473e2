#pragma once
/// @file context.h
/// A headless OpenGL 4.5 core context through EGL, with no window system.
///
/// Device choice: EGL_EXT_platform_device devices are enumerated; hardware
/// devices are tried before software ones (Mesa llvmpipe), then Mesa's
/// surfaceless platform and the default display. `device` (or the environment
/// variable SVO_EGL_DEVICE when the option is empty) narrows the choice:
/// "auto", "hardware", "software", or a device index as listed by
/// `svo glinfo`.
#include <memory>
#include <string>
#include <vector>

namespace svo::gl {

struct ContextOptions {
    std::string device;  ///< "" = $SVO_EGL_DEVICE or "auto"
    bool debug = false;  ///< GL debug output to stderr (always on in debug builds)
};

struct ContextInfo {
    std::string vendor, renderer, version, eglDevice;
    bool conservativeRasterNV = false; ///< GL_NV_conservative_raster present
    int maxViewport = 0;               ///< largest framebuffer width/height usable
    std::vector<std::string> extensionsUsed;
};

/// Owns an EGL display and context, current on the creating thread for its
/// whole lifetime. Not copyable; one per thread.
class Context {
public:
    /// Throws svo::Error with a one-line reason when no GL 4.5 core context can be had.
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const ContextInfo& info() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace svo::gl
