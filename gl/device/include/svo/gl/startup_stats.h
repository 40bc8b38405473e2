#pragma once
/// @file startup_stats.h
/// @brief svo::StartupStats: the start-up work a call paid for (the GL
/// context and its programs), as Device::takeStartup (device.h) reports it.
#include <string>

namespace svo {

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

} // namespace svo
