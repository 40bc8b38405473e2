#pragma once
/// @file byte_size.h
/// @brief A byte count as people read it in messages (KiB, MiB, GiB).
#include <cstdint>
#include <string>

namespace svo {

/// @param bytes a count of bytes
/// @return e.g. "960.8 KiB", "1.5 MiB", "2.00 GiB" (binary units; under 1 MiB in KiB)
std::string byteSize(uint64_t bytes);

} // namespace svo
