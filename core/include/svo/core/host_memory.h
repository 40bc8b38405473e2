#pragma once
/// @file host_memory.h
/// @brief How much host memory is free, for sizing work that must stay within it.
#include <cstdint>

namespace svo {

/// @brief The memory the kernel reports available for new allocations
/// without swapping (Linux: MemAvailable in /proc/meminfo). Throws nothing.
/// @return bytes; 0 when it cannot be read
uint64_t availableHostMemory();

} // namespace svo
