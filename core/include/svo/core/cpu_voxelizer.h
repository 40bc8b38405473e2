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
#include "svo/core/mesh.h"
#include "svo/core/voxelization.h"

namespace svo {

Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, double guard = 0.0);

} // namespace svo
