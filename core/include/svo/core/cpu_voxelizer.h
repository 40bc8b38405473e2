#pragma once
/// @file cpu_voxelizer.h
/// The double-precision reference voxelizer.
///
/// Method: for each triangle, along its dominant normal axis, walk the columns
/// of its 2D bounding box; in each column take the range of the triangle's
/// plane over the column (clamped to the triangle's extent along the axis) and
/// run the shared overlap test (overlap.glsl) on every voxel in it. Triangles
/// are processed in parallel with TBB.
///
/// Guarantee: the result is every voxel whose closed cube, grown by `guard`
/// voxels (shrunk when negative), meets a triangle, up to double rounding.
/// guard = 0 is the conservative voxelization (docs/design.md).
///
/// Thin mode tests the voxel's three axis-aligned centre segments instead of
/// its cube: the result is every voxel one of whose segments, lengthened by
/// `guard` at each end and thickened by max(guard, 0) across (shortened when
/// guard is negative), meets a triangle. guard = 0 is the thin voxelization.
#include "svo/core/mesh.h"
#include "svo/core/voxel_mode.h"
#include "svo/core/voxelization.h"

namespace svo {

/// @param guard voxels to grow (> 0) or shrink (< 0) what is tested by
/// @param mode  the cube (Conservative) or the centre segments (Thin)
/// @throw nothing beyond std::bad_alloc; the mesh's indices must be valid.
Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, double guard = 0.0,
                         VoxelMode mode = VoxelMode::Conservative);

} // namespace svo
