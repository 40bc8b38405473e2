#pragma once
/// @file cpu_voxelizer.h
/// @brief The double-precision reference voxelizer.
///
/// Method: for each triangle, along its dominant normal axis, walk the columns
/// of its 2D bounding box; in each column take the range of the triangle's
/// plane over the column (clamped to the triangle's extent along the axis) and
/// run the shared overlap test (overlap.glsl) on every voxel in it. Work runs
/// in parallel with TBB, in items of at most a few thousand columns: a
/// triangle with more is cut into slabs of rows, so one large triangle does
/// not hold up the rest on one core.
///
/// Guarantee: the result is every voxel whose closed cube, grown by `guard`
/// voxels (shrunk when negative), meets a triangle, up to double rounding.
/// guard = 0 is the conservative voxelization (docs/design.md).
///
/// Thin mode tests the voxel's three axis-aligned centre segments instead of
/// its cube: the result is every voxel one of whose segments, lengthened by
/// `guard` at each end and thickened by max(guard, 0) across (shortened when
/// guard is negative), meets a triangle. guard = 0 is the thin voxelization.
#include <functional>

#include "svo/core/mesh.h"
#include "svo/core/voxel_box.h"
#include "svo/core/voxel_mode.h"
#include "svo/core/voxelization.h"

namespace svo {

/// @brief The voxels of @a mesh on @a grid, in double precision on the CPU.
/// @param mesh   a mesh already checked (validateMesh): indices must be valid
/// @param grid   a grid already checked (checkGrid)
/// @param guard  voxels to grow (> 0) or shrink (< 0) what is tested by
/// @param mode   the cube (Conservative) or the centre segments (Thin)
/// @param poll   when set, called on the calling thread between batches of
///        work (about 2^20 columns each) with the fraction done; it may
///        throw (svo::Interrupted) to cancel, which leaves nothing behind
/// @param report when set, receives the run's stage ("voxelize (cpu)") and
///        its list entries (voxels written, duplicates included)
/// @return the grid and its voxels as sorted, unique keys
/// @throw what @a poll throws (svo::Interrupted, typically), and std::bad_alloc
Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, double guard = 0.0,
                         VoxelMode mode = VoxelMode::Conservative,
                         const std::function<void(double)>& poll = nullptr, RunStats* report = nullptr);

/// @brief The voxels of @a mesh on @a grid inside @a box: exactly the
/// whole-grid result's voxels there; triangles that cannot reach the box are
/// skipped. Parameters, return and throws as the whole-grid call.
Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, const VoxelBox& box, double guard,
                         VoxelMode mode, const std::function<void(double)>& poll = nullptr,
                         RunStats* report = nullptr);

} // namespace svo
