#version 450 core
// Pass 1: each leaf's and tile's sort entry (nano_layout.h), padding entries
// up to the sort's power of two, and the check that origins are multiples of 8.
layout(local_size_x = 256) in;
#include "nano_common.glsl"

uniform uint uEntries; // the sort's size, a power of two

void main()
{
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 256u + gl_GlobalInvocationID.x;
    if (i >= uEntries) return;
    uint at = i * kNanoSortWords;
    if (i >= uEntryCount) {
        for (uint w = 0u; w < 5u; ++w) sortKeys[at + w] = 0xFFFFFFFFu;
        return;
    }
    uint tile = (i - uLeafCount) * kNanoTileWords;
    ivec3 o = i < uLeafCount ? ivec3(origins[3u * i], origins[3u * i + 1u], origins[3u * i + 2u])
                             : ivec3(tiles[tile], tiles[tile + 1u], tiles[tile + 2u]);
    if (((o.x | o.y | o.z) & 7) != 0) atomicMax(counters[kNanoCountMisaligned], i + 1u);
    uvec3 upper = uvec3((o >> 12) + ivec3(1 << 19));
    uvec3 lower = uvec3((o & 4095) >> 7), leaf = uvec3((o & 127) >> 3);
    sortKeys[at] = upper.x;
    sortKeys[at + 1u] = upper.y;
    sortKeys[at + 2u] = upper.z;
    sortKeys[at + 3u] = (lower.x << 10u | lower.y << 5u | lower.z) << 12u | (leaf.x << 8u | leaf.y << 4u | leaf.z);
    sortKeys[at + 4u] = i;
}
