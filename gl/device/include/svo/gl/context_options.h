#pragma once
/// @file context_options.h
/// @brief svo::gl::ContextOptions: how a Context (context.h) finds or makes
/// its OpenGL context.
#include <string>

namespace svo::gl {

/// @brief How a Context finds or makes its OpenGL context.
struct ContextOptions {
    std::string device;  ///< "" = $SVO_EGL_DEVICE or "auto"
    bool debug = false;  ///< GL debug output to stderr (always on in debug builds)
    /// Folder of cached program binaries: "" = $SVO_PROGRAM_CACHE when set
    /// (empty or "off": no cache), else $XDG_CACHE_HOME/svo/programs, else
    /// ~/.cache/svo/programs; "off" = no cache; or a folder.
    std::string programCache;
    /// Wrap the context current on the calling thread instead of creating one
    /// (`device` is then ignored). It must be OpenGL 4.5 core.
    bool adoptCurrent = false;
};

} // namespace svo::gl
