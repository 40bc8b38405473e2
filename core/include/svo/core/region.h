#pragma once
/// @file region.h
/// @brief The part of a grid a call computes: a box of whole leaves in
/// OpenVDB index space. A call given a region returns exactly what the
/// whole-grid call gives inside it (docs/design.md, "Regions").
#include <array>
#include <cstdint>

#include "svo/core/grid.h"
#include "svo/core/voxel_box.h"

namespace svo {

/// @brief Voxels [lo, hi) per axis in a grid's OpenVDB index coordinates,
/// each bound a multiple of 8 (whole leaves: regions that meet share none).
struct IndexBox {
    std::array<int64_t, 3> lo{}, hi{};
};

/// @brief The rule of a region: lo < hi on each axis, every bound a multiple of 8.
/// @throw svo::InvalidInput naming VoxelizeOptions::region
void checkRegion(const IndexBox& region);

/// @brief The local voxels of @a grid inside @a region (empty when they do not meet).
VoxelBox localBox(const GridSpec& grid, const IndexBox& region);

/// @brief The whole local range of @a grid.
VoxelBox wholeBox(const GridSpec& grid);

} // namespace svo
