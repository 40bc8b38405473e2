#pragma once
/// @file grid_builder.h
/// Voxel keys -> OpenVDB trees by copying brick masks into leaves.
///
/// Method: sorted keys are brick-major (voxel_key.h), so each run of keys with
/// one brick is one LeafNode<T,3>; its 9 low bits are the leaf's bit index.
/// Runs are found in one scan, leaves are filled in parallel (TBB), and then
/// inserted with addLeaf. Cost is O(voxels) with no per-voxel tree descent.
#include <openvdb/openvdb.h>

#include "svo/core/voxelization.h"

namespace svo::vdb {

/// The linear transform of a grid: voxelSize scaling, then its translation.
openvdb::math::Transform::Ptr makeTransform(const GridSpec& grid);

openvdb::MaskGrid::Ptr buildMaskGrid(const Voxelization& voxels);

/// Fog volume: 1 on every voxel, background 0.
openvdb::FloatGrid::Ptr buildFogGrid(const Voxelization& voxels);

} // namespace svo::vdb
