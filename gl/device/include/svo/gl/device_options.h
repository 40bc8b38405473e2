#pragma once
/// @file device_options.h
/// @brief svo::DeviceOptions: which GPU a Device (device.h), and so a
/// Voxelizer, uses; each option declared once for every front end.
#include <string>

#include "svo/core/option_info.h"

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

} // namespace svo
