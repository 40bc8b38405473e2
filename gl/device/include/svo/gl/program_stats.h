#pragma once
/// @file program_stats.h
/// @brief svo::gl::ProgramStats: what making programs (loading them from the
/// program cache or compiling them) has cost a Context so far.
#include <string>
#include <vector>

namespace svo::gl {

/// @brief What making programs has cost a Context so far (cumulative).
struct ProgramStats {
    int compiled = 0;  ///< programs compiled from source (refused ones included)
    int loaded = 0;    ///< programs loaded from the program cache
    int refused = 0;   ///< cache entries damaged or refused by the driver, compiled again and replaced
    double ms = 0;     ///< wall ms spent making programs: expanding, compiling or loading, cache files
    std::vector<std::string> warnings; ///< the program cache's (at most one: a folder that cannot be written)
};

} // namespace svo::gl
