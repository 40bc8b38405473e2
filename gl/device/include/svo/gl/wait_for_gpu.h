#pragma once
/// @file wait_for_gpu.h
/// @brief Waiting for the GPU without blocking a caller's progress checks.
#include <functional>

namespace svo::gl {

/// @brief Waits until the GPU has finished the commands issued so far, in
/// slices of 20 ms, calling @a poll between slices.
/// @param poll a progress or interrupt check; what it throws stops the wait
///        and passes through (svo::Interrupted, typically)
/// @throw svo::DeviceError when a fence cannot be made or the wait fails
void waitForGpu(const std::function<void()>& poll);

} // namespace svo::gl
