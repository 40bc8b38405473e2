#pragma once
/// @file column_crossing.h
/// @brief Where a triangle crosses a voxel column along z, with simulation of
/// simplicity for ties, compiled from the same text as the parity shader
/// (column_crossing.glsl): the CPU backend's crossings are the GPU's, bit for
/// bit. A file that includes this header must be compiled without
/// floating-point contraction (-ffp-contract=off), as the shader's precise
/// operations round each step.
#include "svo/core/vec3.h"

namespace svo::column_crossing {
// column_crossing.glsl's GLSL spelling in C++.
using svo_dvec3 = Vec3d;
#define SVO_FN inline
#define SVO_INOUT(T) T&
#define SVO_DOUBLE(x) x
#define SVO_PRECISE
#include "svo/core/column_crossing.glsl"
#undef SVO_PRECISE
#undef SVO_DOUBLE
#undef SVO_INOUT
#undef SVO_FN
} // namespace svo::column_crossing
