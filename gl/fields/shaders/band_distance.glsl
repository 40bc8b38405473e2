// What the two band distance passes share (band_distance.comp for GPUs,
// band_distance_columns.comp for CPU rasterizers): the output, and the
// distance from a voxel centre to a triangle in double precision
// (triangle_distance.glsl, core's). Pass 0
// keeps the least distance of each voxel with atomicMin on its float bits
// (non-negative floats order as their bits do); pass 1, when asked for,
// records the smallest index of the triangles at that distance, so the
// result does not depend on the order of the threads.
#include "field_common.glsl"

layout(std430, binding = SVO_BIND_FIELD_DISTANCES) restrict buffer Distances { uint distances[]; };
layout(std430, binding = SVO_BIND_FIELD_CLOSEST) restrict buffer Closest { uint closest[]; };

uniform uint uPass;
uniform float uBand; // distances beyond it are not kept
// A band's topology only (FieldRequest::bandOnly): a voxel whose kept
// distance is already less than this is in the band, whatever its other
// triangles give, so they are not computed there; 0 computes every one
// (and reads no kept distance: every level set and unsigned field).
uniform float uKnownBelow;

bool knownInBand(uint i) { return uKnownBelow > 0.0 && uintBitsToFloat(distances[i]) < uKnownBelow; }

// The distance to a triangle and the slab and box tests, one text with the
// CPU backend's (core/src/band_distances.cpp).
#include "field_double.glsl"
#include "triangle_distance.glsl"
