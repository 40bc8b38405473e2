#pragma once
/// @file winding_work.h
/// @brief svo::gl::WindingWork: how the per-voxel winding evaluation
/// (winding_number.h) walks the tree.

namespace svo::gl {

/// @brief How the per-voxel evaluation walks the tree (both give the same bits). A
/// GPU runs fastest with a walk per voxel centre; a CPU rasterizer, whose
/// SIMD lanes are a workgroup's threads, with one walk per column of 8
/// centres that treats each centre as its own walk would.
enum class WindingWork {
    Auto,   ///< by the renderer: Columns on a CPU rasterizer, else Points
    Points, ///< a walk per voxel centre
    Columns ///< a walk per column of 8 voxel centres
};

} // namespace svo::gl
