#pragma once
/// @file field_work.h
/// @brief svo::gl::FieldWork: how the distance pass (distance_field.h) cuts
/// its work between workgroups and threads.

namespace svo::gl {

/// @brief How the distance pass cuts its work (both give the same field). A GPU
/// runs fastest with a workgroup per brick of each triangle's box grown by
/// the band; a CPU rasterizer, whose SIMD lanes are a workgroup's threads,
/// with a thread per triangle whose grown box fits in a brick (most of a
/// dense mesh's) and a workgroup per brick for the rest.
enum class FieldWork {
    Auto,          ///< by the renderer: SmallTriangles on a CPU rasterizer, else Bricks
    Bricks,        ///< a workgroup per brick of every triangle's grown box
    SmallTriangles ///< a thread per triangle whose grown box fits a brick, a workgroup per brick for the others
};

} // namespace svo::gl
