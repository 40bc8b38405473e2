#pragma once
/// @file context_info.h
/// @brief svo::gl::ContextInfo: what a Context (context.h) found: the
/// driver, its extensions and its limits.
#include <cstdint>
#include <string>
#include <vector>

namespace svo::gl {

/// @brief What a Context found: the driver, its extensions and its limits.
struct ContextInfo {
    std::string vendor, renderer, version; ///< GL_VENDOR, GL_RENDERER, GL_VERSION
    std::string eglDevice;             ///< the EGL device used, or "the host's GLX context" (EGL) when adopted
    bool adopted = false;              ///< the context is the host's (ContextOptions::adoptCurrent)
    bool conservativeRasterNV = false; ///< GL_NV_conservative_raster present
    bool memoryInfoNVX = false;        ///< GL_NVX_gpu_memory_info present (free video memory can be asked)
    bool software = false;             ///< a CPU rasterizer (llvmpipe, softpipe, lavapipe-like)
    /// Loop iterations a shader may run in all, over all its loops, before the
    /// driver ends them silently: Mesa's gallivm (llvmpipe, softpipe) stops
    /// at 65,535. 0: no such limit. Passes whose invocations loop over work
    /// cut their dispatches to stay under it, or stop and report it. On such
    /// a driver the environment variable SVO_LOOP_LIMIT may lower it (not
    /// raise it), so that tests reach the split dispatches with small scenes.
    uint64_t loopLimit = 0;
    /// The invocations that share one loopLimit: gallivm runs loopLanes of them
    /// as one SIMD vector, whose loops iterate while any lane does, so lanes
    /// whose loops diverge spend the limit together (llvmpipe's "N bits" / 32).
    uint32_t loopLanes = 1;
    int maxViewport = 0;               ///< largest framebuffer width/height usable
    /// GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the most bytes of one buffer a shader
    /// can address; work whose buffers would pass it is tiled or refused.
    uint64_t maxStorageBlock = 0;
    std::vector<std::string> extensionsUsed; ///< the optional extensions svo found and uses
    double setupMs = 0;                ///< wall ms the constructor took: EGL display, context, queries
    int programBinaryFormats = 0;      ///< GL_NUM_PROGRAM_BINARY_FORMATS; 0 means no program cache
    std::string programCache;          ///< the program cache folder in use; "" when off
};

} // namespace svo::gl
