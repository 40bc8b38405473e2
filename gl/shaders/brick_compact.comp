#version 450 core
// The compute backend's brick table, compacted for the octree build: every
// occupied slot becomes one entry (its brick's origin key) with its mask.
layout(local_size_x = 256) in;
#include "gpu_layout.h"

layout(std430, binding = SVO_BIND_COMPUTE_TABLE) readonly restrict buffer Table { uint slots[]; };
layout(std430, binding = SVO_BIND_COMPUTE_TABLE_MASKS) readonly restrict buffer TableMasks { uint tableMasks[]; };
layout(std430, binding = SVO_BIND_COMPACT_KEYS) writeonly restrict buffer Keys { uvec2 keys[]; };
layout(std430, binding = SVO_BIND_COMPACT_MASKS) writeonly restrict buffer Masks { uint masks[]; };
layout(std430, binding = SVO_BIND_COMPACT_COUNT) restrict buffer Count { uint count; };
uniform uint uSlots;
const uint kEmpty = 0xFFFFFFFFu;

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < uSlots; i += gl_NumWorkGroups.x * 256u) {
        uint key = slots[i];
        if (key == kEmpty) continue;
        uint j = atomicAdd(count, 1u);
        uvec3 b = uvec3(key >> 20u, (key >> 10u) & 1023u, key & 1023u);
        keys[j] = packVoxelKey(b << 3u);
        for (uint w = 0u; w < kBrickWords; ++w) masks[kBrickWords * j + w] = tableMasks[kBrickWords * i + w];
    }
}
