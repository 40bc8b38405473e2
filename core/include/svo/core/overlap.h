#pragma once
/// @file overlap.h
/// @brief Triangle / voxel overlap tests (the cube, and the thin mode's centre
/// segments), compiled from the same text as the shaders
/// (overlap.glsl). See that file for the method and its guarantees.
#include <algorithm>
#include <cmath>

#include "svo/core/vec3.h"

namespace svo {
/// The std functions overlap.glsl's GLSL spelling (abs, max, min) resolves to.
namespace overlap_detail {
using std::abs;
using std::max;
using std::min;
} // namespace overlap_detail

/// @brief Double precision: the reference used by the CPU voxelizer.
namespace overlap_double {
using namespace overlap_detail;
using svo_real = double;
using svo_vec3 = Vec3<double>;
#define SVO_FN inline
#include "svo/core/overlap.glsl"
#undef SVO_FN
} // namespace overlap_double

/// @brief Single precision: what the GPU computes, for studying the guard band on the CPU.
namespace overlap_float {
using namespace overlap_detail;
using svo_real = float;
using svo_vec3 = Vec3<float>;
#define SVO_FN inline
#include "svo/core/overlap.glsl"
#undef SVO_FN
} // namespace overlap_float

/// @brief Whether triangle (a, b, c) meets the closed cube of half side
/// @a half centred at @a centre (all in index space); in double precision,
/// and in float (the GPU's arithmetic) below.
inline bool triangleBoxOverlap(Vec3d a, Vec3d b, Vec3d c, Vec3d centre, double half)
{
    return overlap_double::svo_triangle_box_overlap(a, b, c, centre, half);
}
inline bool triangleBoxOverlap(Vec3f a, Vec3f b, Vec3f c, Vec3f centre, float half)
{
    return overlap_float::svo_triangle_box_overlap(a, b, c, centre, half);
}

/// @brief Whether triangle (a, b, c) meets one of the three axis-aligned
/// segments through @a centre, each thickened to a box across its axis: the
/// thin mode's test (docs/precision.md); in double precision, and in float below.
/// @param halfLength each segment's half length (0.5 for the exact voxel)
/// @param thickness  the boxes' half width across the axis, >= 0 (0 for the exact voxel)
inline bool triangleThinOverlap(Vec3d a, Vec3d b, Vec3d c, Vec3d centre, double halfLength, double thickness)
{
    return overlap_double::svo_triangle_thin_overlap(a, b, c, centre, halfLength, thickness);
}
inline bool triangleThinOverlap(Vec3f a, Vec3f b, Vec3f c, Vec3f centre, float halfLength, float thickness)
{
    return overlap_float::svo_triangle_thin_overlap(a, b, c, centre, halfLength, thickness);
}

} // namespace svo
