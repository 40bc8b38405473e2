#pragma once
/// @file dispatch_looping.h
/// Compute dispatches of looping work, cut to stay under a driver's loop limit.
#include <cstdint>

namespace svo::gl {

class Program;

/// Runs compute `program` as `groups` workgroups (along x) that loop over
/// units [0, count): the shader takes units [uniform `first`, uniform `end`),
/// group g the units first + g, first + g + groups, and so on. Where the
/// driver silently ends an invocation's loops after `loopLimit` iterations in
/// all (ContextInfo::loopLimit; 0: no limit), the units are cut into as many
/// dispatches as keep each invocation under it, given at most
/// `iterationsPerUnit` loop iterations a unit (the loop's own included);
/// otherwise one dispatch. A storage barrier follows each dispatch.
void dispatchLooping(const Program& program, uint64_t count, uint32_t groups, uint64_t loopLimit,
                     uint64_t iterationsPerUnit, const char* first, const char* end);

} // namespace svo::gl
