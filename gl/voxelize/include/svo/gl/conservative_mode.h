#pragma once
/// @file conservative_mode.h
/// @brief svo::gl::ConservativeMode: how the raster pipeline (raster_voxelizer.h)
/// dilates triangles.

namespace svo::gl {

/// @brief How the raster pipeline dilates triangles. Auto: Hardware where
/// available, else Shader. CentroidPush is the seed report's vertex push,
/// kept only as a baseline for benchmarks: it misses voxels.
enum class ConservativeMode { Auto, Hardware, Shader, CentroidPush };

} // namespace svo::gl
