#pragma once
/// @file wait_for_gpu.h
/// Waiting for the GPU without blocking a caller's progress checks.
#include <functional>

namespace svo::gl {

/// Waits until the GPU has finished the commands issued so far, in slices of
/// 20 ms, calling `poll` between slices (it may throw to stop waiting).
void waitForGpu(const std::function<void()>& poll);

} // namespace svo::gl
