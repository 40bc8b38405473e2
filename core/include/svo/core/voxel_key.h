#pragma once
/// @file voxel_key.h
/// @brief A voxel as one 64-bit key in local grid coordinates, ordered brick-major.
///
///   bit 63      : 0
///   bits 62..45 : brick x  (local x >> 3, 18 bits)
///   bits 44..27 : brick y
///   bits 26..9  : brick z
///   bits 8..0   : (x&7)<<6 | (y&7)<<3 | (z&7)  -- OpenVDB LeafNode<T,3> bit order
///
/// Sorting keys therefore groups each 8^3 brick, and the low 9 bits are the
/// leaf's bit index, so a run of keys becomes an OpenVDB leaf mask directly.
/// The bit positions come from gpu_layout.h, which the shaders pack from too.
#include <array>
#include <cstdint>

#include "svo/core/gpu_layout.h"

namespace svo {

/// @brief The key of local voxel (x, y, z); each coordinate below kMaxGridDim (unchecked).
constexpr uint64_t packVoxelKey(uint32_t x, uint32_t y, uint32_t z)
{
    using namespace gpu;
    return (uint64_t(x >> kBrickLog2) << kKeyBrickXShift) | (uint64_t(y >> kBrickLog2) << kKeyBrickYShift) |
           (uint64_t(z >> kBrickLog2) << kKeyBrickZShift) | (uint64_t(x & kBrickMask) << kKeyLeafXShift) |
           (uint64_t(y & kBrickMask) << kKeyLeafYShift) | (uint64_t(z & kBrickMask) << kKeyLeafZShift);
}

/// @brief The local coordinates (x, y, z) of a key.
constexpr std::array<uint32_t, 3> unpackVoxelKey(uint64_t k)
{
    using namespace gpu;
    auto axis = [k](uint32_t brickShift, uint32_t leafShift) {
        return uint32_t((k >> brickShift) & kKeyBrickMask) << kBrickLog2 | uint32_t((k >> leafShift) & kBrickMask);
    };
    return {axis(kKeyBrickXShift, kKeyLeafXShift), axis(kKeyBrickYShift, kKeyLeafYShift),
            axis(kKeyBrickZShift, kKeyLeafZShift)};
}

/// @brief The brick part of a key (its low 9 bits cleared): its brick origin's key.
constexpr uint64_t brickOfKey(uint64_t k) { return k & ~uint64_t(gpu::kKeyLeafMask); }

static_assert(unpackVoxelKey(packVoxelKey(2097151, 5, 1234567))[0] == 2097151);
static_assert(unpackVoxelKey(packVoxelKey(2097151, 5, 1234567))[2] == 1234567);
static_assert(packVoxelKey(1, 2, 3) == ((1u << 6) | (2u << 3) | 3u));
static_assert(packVoxelKey(8, 0, 0) == uint64_t(1) << 45 && packVoxelKey(0, 8, 0) == uint64_t(1) << 27 &&
              packVoxelKey(0, 0, 8) == uint64_t(1) << 9);
static_assert(packVoxelKey(2097151, 2097151, 2097151) == (uint64_t(1) << 63) - 1); // bit 63 stays clear
static_assert(brickOfKey(packVoxelKey(13, 21, 7)) == packVoxelKey(8, 16, 0));

} // namespace svo
