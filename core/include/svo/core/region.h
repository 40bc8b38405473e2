#pragma once
/// @file region.h
/// @brief The part of a grid a call computes: a box of whole leaves in
/// OpenVDB index space. A call given a region returns exactly what the
/// whole-grid call gives inside it (docs/design.md, "Regions").
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "svo/core/grid.h"
#include "svo/core/voxel_box.h"

namespace svo {

/// @brief Voxels [lo, hi) per axis in a grid's OpenVDB index coordinates,
/// each bound a multiple of 8 (whole leaves: regions that meet share none).
struct IndexBox {
    std::array<int64_t, 3> lo{}, hi{};
};

/// @brief The rule of a region: lo < hi on each axis, every bound a multiple of 8.
/// @param name the region's name for the caller (argument() of the error)
/// @throw svo::InvalidInput naming @a name
void checkRegion(const IndexBox& region, const std::string& name = "VoxelizeOptions::region");

/// @brief The local voxels of @a grid inside @a region (empty when they do not meet).
VoxelBox localBox(const GridSpec& grid, const IndexBox& region);

/// @brief The whole local range of @a grid.
VoxelBox wholeBox(const GridSpec& grid);

/// @brief The bricks of @a grid's box (ceil(dims / 8) per axis) that meet
/// @a region, or all of them without one.
BrickBox bricksMeeting(const GridSpec& grid, const std::optional<IndexBox>& region);

/// @brief @a box cut to the bricks of @a grid's box (empty boxes keep lo <= hi).
BrickBox withinGrid(const GridSpec& grid, const BrickBox& box);

/// @brief An optional region as an option (svo/core/option_info.h): six
/// whole numbers, lo then hi, "x0,y0,z0,x1,y1,z1" on the command line and
/// ((x0, y0, z0), (x1, y1, z1)) in Python; None (the default) is the whole grid.
struct RegionOption {
    std::optional<IndexBox>& region; ///< the field
};

/// @brief A region from its six bounds, checked (checkRegion).
/// @param name the option's name for the caller (a flag, a keyword)
/// @throw svo::InvalidInput naming @a name
IndexBox regionFrom(const std::array<int64_t, 6>& bounds, const std::string& name);

} // namespace svo
