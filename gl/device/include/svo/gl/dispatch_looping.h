#pragma once
/// @file dispatch_looping.h
/// @brief Compute dispatches of looping work, cut to stay under a driver's loop limit.
#include <cstdint>

namespace svo::gl {

class Program;

/// @brief Runs compute @a program over units [0, count) in as few dispatches
/// as the driver's loop limit allows.
///
/// The program runs as @a groups workgroups (along x) that loop over units:
/// the shader takes units [uniform @a first, uniform @a end), group g the
/// units first + g, first + g + groups, and so on. Where the driver silently
/// ends an invocation's loops after @a loopLimit iterations in all, the units
/// are cut into as many dispatches as keep each invocation under it;
/// otherwise one dispatch. A storage barrier follows each dispatch. Nothing
/// runs when @a count or @a groups is 0.
/// @param loopLimit         ContextInfo::loopLimit; 0: no limit
/// @param iterationsPerUnit the most loop iterations one unit takes (the
///                          loop's own included)
/// @param first, end        names of the shader's uint uniforms bounding the
///                          units of one dispatch
/// @throw svo::DeviceError when @a first or @a end is not an active uniform
///        (Program::set)
void dispatchLooping(const Program& program, uint64_t count, uint32_t groups, uint64_t loopLimit,
                     uint64_t iterationsPerUnit, const char* first, const char* end);

} // namespace svo::gl
