#pragma once
/// @file voxel_key.h
/// A voxel as one 64-bit key in local grid coordinates, ordered brick-major.
///
///   bit 63      : 0
///   bits 62..45 : brick x  (local x >> 3, 18 bits)
///   bits 44..27 : brick y
///   bits 26..9  : brick z
///   bits 8..0   : (x&7)<<6 | (y&7)<<3 | (z&7)  -- OpenVDB LeafNode<T,3> bit order
///
/// Sorting keys therefore groups each 8^3 brick, and the low 9 bits are the
/// leaf's bit index, so a run of keys becomes an OpenVDB leaf mask directly.
/// The shaders pack the same layout (raster.frag).
#include <array>
#include <cstdint>

namespace svo {

constexpr uint64_t packVoxelKey(uint32_t x, uint32_t y, uint32_t z)
{
    return (uint64_t(x >> 3) << 45) | (uint64_t(y >> 3) << 27) | (uint64_t(z >> 3) << 9) |
           (uint64_t(x & 7) << 6) | (uint64_t(y & 7) << 3) | uint64_t(z & 7);
}

constexpr std::array<uint32_t, 3> unpackVoxelKey(uint64_t k)
{
    constexpr uint64_t m18 = (1u << 18) - 1;
    return {uint32_t(((k >> 45) & m18) << 3 | ((k >> 6) & 7)), uint32_t(((k >> 27) & m18) << 3 | ((k >> 3) & 7)),
            uint32_t(((k >> 9) & m18) << 3 | (k & 7))};
}

/// The brick part of a key (its low 9 bits cleared).
constexpr uint64_t brickOfKey(uint64_t k) { return k & ~uint64_t(511); }

static_assert(unpackVoxelKey(packVoxelKey(2097151, 5, 1234567))[0] == 2097151);
static_assert(unpackVoxelKey(packVoxelKey(2097151, 5, 1234567))[2] == 1234567);
static_assert(packVoxelKey(1, 2, 3) == ((1u << 6) | (2u << 3) | 3u));

} // namespace svo
