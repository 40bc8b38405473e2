#version 450 core
// Sums each voxel-list entry's triangle values into its voxel's slot (the
// voxel's rank in voxel order), in 16.16 fixed point so the sums do not depend
// on the order of the atomics. Layout per voxel: core/voxel_attributes.h.
layout(local_size_x = 256) in;
#include "octree_common.glsl"

layout(std430, binding = 4) readonly restrict buffer TriangleList { uint triangleOf[]; };
layout(std430, binding = 5) readonly restrict buffer BrickOffsets { uint brickOffset[]; };
layout(std430, binding = 6) readonly restrict buffer TriangleValues { float values[]; }; // normal xyz, colour rgb
layout(std430, binding = 7) restrict buffer Sums { uint sums[]; };

uniform uint uEntries;

uint fixedPoint(float v) { return uint(int(roundEven(v * 65536.0))); }

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < uEntries; i += strideOf()) {
        uvec2 key = entries[i];
        uint node = descend(brickOfEntry(key), uBrickLevel);
        if (node == kNoChild) continue;
        uint brick = nodes[2u * node];
        uint bit = key.x & 511u;
        uint rank = uint(bitCount(bricks[16u * brick + (bit >> 5u)] & ((1u << (bit & 31u)) - 1u)));
        for (uint w = 0u; w < (bit >> 5u); ++w) rank += uint(bitCount(bricks[16u * brick + w]));
        uint s = 8u * (brickOffset[brick] + rank);
        uint t = triangleOf[i];
        atomicMax(sums[s], ~t);
        for (uint k = 0u; k < 6u; ++k) atomicAdd(sums[s + 1u + k], fixedPoint(values[6u * t + k]));
        atomicAdd(sums[s + 7u], 1u);
    }
}
