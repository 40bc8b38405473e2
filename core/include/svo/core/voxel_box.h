#pragma once
/// @file voxel_box.h
/// @brief A box of a grid's local voxels: what a tile or a region covers.
#include <array>
#include <cstdint>

namespace svo {

/// @brief Voxels [lo, hi) of a grid's local range (GridSpec::dims): the whole
/// grid, a tile, or a region. Boxes that start on multiples of 8 share no brick.
struct VoxelBox {
    std::array<uint32_t, 3> lo{}, hi{};
    /// @brief Voxels in the box (0 when it is empty).
    uint64_t volume() const
    {
        return empty() ? 0 : uint64_t(hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    }
    /// @brief Whether the box holds no voxel.
    bool empty() const { return lo[0] >= hi[0] || lo[1] >= hi[1] || lo[2] >= hi[2]; }
    /// @brief Whether local voxel (x, y, z) lies in the box.
    bool contains(uint32_t x, uint32_t y, uint32_t z) const
    {
        return x >= lo[0] && x < hi[0] && y >= lo[1] && y < hi[1] && z >= lo[2] && z < hi[2];
    }
};

/// @brief Bricks b of a grid with lo <= b < hi on each axis (brick
/// coordinates: local voxel / 8).
struct BrickBox {
    std::array<uint32_t, 3> lo{}, hi{};
};

} // namespace svo
