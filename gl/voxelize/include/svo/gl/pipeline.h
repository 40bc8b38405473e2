#pragma once
/// @file pipeline.h
/// @brief svo::gl::Pipeline: how raster_voxelizer.h fills the voxel list,
/// with raster draws or compute dispatches.

namespace svo::gl {

/// @brief How the voxel list is filled. Both walk the same columns with the same
/// test (column_walk.glsl), so they keep the same voxels.
enum class Pipeline {
    Raster,  ///< one fragment per column: the triangle rasterized along its dominant axis
    Compute, ///< triangle-parallel compute shaders; large triangles spread over workgroups
};

} // namespace svo::gl
