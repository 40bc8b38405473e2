#pragma once
/// @file triangle_distance.h
/// @brief The distance from a voxel centre to a triangle in double precision,
/// and the tests that skip centres beyond a band (a triangle's plane slab,
/// its box), compiled from the same text as the band distance shaders
/// (triangle_distance.glsl): the CPU backend's distances are the GPU's, bit
/// for bit. A file that includes this header must be compiled without
/// floating-point contraction (-ffp-contract=off), as the shaders round each
/// operation.
#include <algorithm>
#include <cmath>

#include "svo/core/vec3.h"

namespace svo::triangle_distance {
// triangle_distance.glsl's GLSL spelling in C++: the std functions its
// abs, ceil, floor, max, min and sqrt resolve to, its vector and literals.
using std::abs;
using std::ceil;
using std::floor;
using std::max;
using std::min;
using std::sqrt;
using svo_dvec3 = Vec3d;
#define SVO_FN inline
#define SVO_INOUT(T) T&
#define SVO_DOUBLE(x) x
#include "svo/core/triangle_distance.glsl"
#undef SVO_DOUBLE
#undef SVO_INOUT
#undef SVO_FN
} // namespace svo::triangle_distance
