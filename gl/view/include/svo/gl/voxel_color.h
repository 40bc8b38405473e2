#pragma once
/// @file voxel_color.h
/// @brief How the octree view colours voxels (ViewLayers::voxelColor), and the names front ends give it.
#include "svo/core/enum_names.h"

namespace svo::gl {

/// @brief How voxels are coloured: flat green, or by an attribute channel of the
/// octree (VoxelAttributes): the normal as 0.5 + 0.5 n, the colour, or a
/// colour hashed from the triangle id.
enum class VoxelColor { Flat, Normal, Color, Triangle };
inline constexpr EnumName<VoxelColor> kVoxelColorNames[] = {{VoxelColor::Flat, "flat"},
                                                             {VoxelColor::Normal, "normal"},
                                                             {VoxelColor::Color, "color"},
                                                             {VoxelColor::Triangle, "triangle"}};
constexpr const auto& enumNames(VoxelColor) { return kVoxelColorNames; }

} // namespace svo::gl
