#version 450 core
// Sums each voxel-list entry's triangle values into its voxel's slot (the
// voxel's rank in voxel order), in 16.16 fixed point so the sums do not depend
// on the order of the atomics. Layout per voxel: gpu_layout.h (kSum*).
layout(local_size_x = 256) in;
#include "octree_common.glsl"

layout(std430, binding = SVO_BIND_ENTRY_TRIANGLES) readonly restrict buffer TriangleList { uint triangleOf[]; };
layout(std430, binding = SVO_BIND_BRICK_VOXEL_OFFSETS) readonly restrict buffer BrickOffsets { uint brickOffset[]; };
// Per triangle: normal xyz, colour rgb.
layout(std430, binding = SVO_BIND_TRIANGLE_VALUES) readonly restrict buffer TriangleValues { float values[]; };
layout(std430, binding = SVO_BIND_ATTRIBUTE_SUMS) restrict buffer Sums { uint sums[]; };

uniform uint uEntries;

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < uEntries; i += strideOf()) {
        uvec2 key = entries[i];
        uint node = descend(brickOfVoxelKey(key), uBrickLevel);
        if (node == kNoChild) continue;
        uint brick = nodes[childOf(node)];
        uint bit = leafBitOfVoxelKey(key);
        uint rank = uint(bitCount(bricks[brickWord(brick, bit)] & ((1u << (bit & 31u)) - 1u)));
        for (uint w = 0u; w < (bit >> 5u); ++w) rank += uint(bitCount(bricks[kBrickWords * brick + w]));
        uint s = kSumWords * (brickOffset[brick] + rank);
        uint t = triangleOf[i];
        atomicMax(sums[s + kSumTriangle], ~t);
        for (uint k = 0u; k < 3u; ++k) {
            atomicAdd(sums[s + kSumNormal + k], uint(toFixed(values[6u * t + k])));
            atomicAdd(sums[s + kSumColor + k], uint(toFixed(values[6u * t + 3u + k])));
        }
        atomicAdd(sums[s + kSumCount], 1u);
    }
}
