#pragma once
/// @file voxel_mode.h
/// @brief Which voxels a triangle covers: the two voxelizations svo computes
/// (docs/design.md, "What a voxelization is").
#include "svo/core/enum_names.h"

namespace svo {

/// @brief Which voxels a triangle covers.
enum class VoxelMode {
    /// Every voxel whose closed cube [i-1/2, i+1/2]^3 meets a triangle: a
    /// closed mesh gives a shell that no 26-connected path crosses.
    Conservative,
    /// Every voxel one of whose three axis-aligned centre segments (closed,
    /// one voxel long: centre +- 1/2 along x, y or z) meets a triangle: a
    /// subset of the conservative voxels that no 6-connected path crosses.
    Thin,
};

inline constexpr EnumName<VoxelMode> kVoxelModeNames[] = {{VoxelMode::Conservative, "conservative"},
                                                          {VoxelMode::Thin, "thin"}};
constexpr const auto& enumNames(VoxelMode) { return kVoxelModeNames; }

/// @brief "conservative" or "thin" (the names above, as a C string).
inline const char* voxelModeName(VoxelMode mode) { return nameOf(mode).data(); }

/// @brief The flood-fill connectivity that must not cross a voxelization of a
/// closed surface in this mode.
/// @return 26 for conservative, 6 for thin
int separatingConnectivity(VoxelMode mode);

} // namespace svo
