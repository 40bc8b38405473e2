#version 450 core
// Packs the band as band_compact.comp does (the same masks, offsets and
// packed values), on a CPU rasterizer: a thread a brick, with no shared
// memory and no barriers. llvmpipe runs a workgroup's SIMD vectors one after
// another and switches between them at every barrier, which cost more than
// the packing itself; here eight bricks fill its eight lanes.
layout(local_size_x = 8) in;
#include "gpu_layout.h"
#include "field_layout.h"

layout(std430, binding = SVO_BIND_FIELD_DISTANCES) readonly restrict buffer Distances { float distances[]; };
layout(std430, binding = SVO_BIND_FIELD_CLOSEST) readonly restrict buffer Closest { uint closest[]; };
layout(std430, binding = SVO_BIND_FIELD_COUNTERS) restrict buffer Counters { uint counters[]; };
layout(std430, binding = SVO_BIND_COMPACT_MASKS) writeonly restrict buffer Masks { uint masks[]; };
layout(std430, binding = SVO_BIND_COMPACT_OFFSETS) writeonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = SVO_BIND_COMPACT_DISTANCES) writeonly restrict buffer Packed { float packedDistances[]; };
layout(std430, binding = SVO_BIND_COMPACT_CLOSEST) writeonly restrict buffer PackedClosest { uint packedClosest[]; };

uniform uint uBrickFirst; // this dispatch's bricks: [uBrickFirst, uBricks)
uniform uint uBricks;
uniform float uBand;     // a voxel is kept when its distance is less
uniform uint uClosest;   // 1: closest triangles were computed

void main()
{
    uint threads = gl_WorkGroupSize.x * gl_NumWorkGroups.x;
    for (uint brick = uBrickFirst + gl_WorkGroupSize.x * gl_WorkGroupID.x + gl_LocalInvocationID.x; brick < uBricks;
         brick += threads) {
        // Voxel v of the brick (LeafNode order) is bit v & 31 of word v >> 5.
        uint first = 512u * brick, total = 0u;
        uint words[16];
        for (uint w = 0u; w < 16u; ++w) {
            uint bits = 0u;
            for (uint b = 0u; b < 32u; ++b)
                if (distances[first + 32u * w + b] < uBand) bits |= 1u << b;
            words[w] = bits;
            masks[16u * brick + w] = bits;
            total += uint(bitCount(bits));
        }
        uint at = atomicAdd(counters[1], total);
        offsets[brick] = at;
        for (uint w = 0u; w < 16u; ++w) {
            uint bits = words[w];
            while (bits != 0u) {
                uint v = first + 32u * w + uint(findLSB(bits));
                packedDistances[at] = distances[v];
                if (uClosest != 0u) packedClosest[at] = closest[v];
                ++at;
                bits &= bits - 1u;
            }
        }
    }
}
