#version 450 core
// Pass 4, a work group per sorted leaf: the leaf's origin, bounding box,
// flags, value mask, values and statistics; its statistics for its parent;
// the active voxel count.
#define NANO_GROUP 128
layout(local_size_x = NANO_GROUP) in;
#include "nano_common.glsl"
#include "nano_stats.glsl"

uniform uint uLeafAt;     // the first leaf's word in the grid
uniform uint uLeafWords;  // words per leaf
uniform uint uHasValues;  // 1: values[] holds 512 words per leaf
uniform uint uBackground; // the background's bits

shared uint activeCount;

bool voxelOn(uint leaf, uint v) { return ((masks[leaf * 16u + (v >> 5u)] >> (v & 31u)) & 1u) != 0u; }

// This invocation's 4 voxels: values (or bits) written, their statistics folded in order.
NodeStats fillVoxels(uint leaf, uint at, ivec3 origin)
{
    NodeStats s = emptyStats();
    for (uint v = 4u * gl_LocalInvocationIndex; v < 4u * gl_LocalInvocationIndex + 4u; ++v) {
        uint value = uHasValues != 0u ? values[leaf * 512u + v] : uBackground;
        bool on = voxelOn(leaf, v);
        if (hasValues()) grid[at + kNanoLeafValues + v] = value;
        if (uType == kNanoTypeBool && (uHasValues != 0u ? value != 0u : on))
            atomicOr(grid[at + kNanoLeafBoolValues + (v >> 5u)], 1u << (v & 31u));
        if (!on) continue;
        ivec3 c = origin + ivec3(v >> 6u, (v >> 3u) & 7u, v & 7u);
        s = merge(s, NodeStats(c, c, value, value));
    }
    return s;
}

void main()
{
    uint i = groupIndex();
    if (i >= uLeafCount) return;
    uint t = gl_LocalInvocationIndex, leaf = inputLeaf(i);
    uint at = uLeafAt + i * uLeafWords;
    ivec3 origin = ivec3(origins[3u * leaf], origins[3u * leaf + 1u], origins[3u * leaf + 2u]);
    if (t == 0u) activeCount = 0u;
    memoryBarrierShared();
    barrier();
    if (t < 16u) {
        uint word = masks[leaf * 16u + t];
        grid[at + kNanoLeafValueMask + t] = word;
        atomicAdd(activeCount, bitCount(word));
    }
    NodeStats s = reduceGroup(fillVoxels(leaf, at, origin));
    if (t != 0u) return;
    storeStats(i, s);
    uint count = activeCount, before = atomicAdd(counters[kNanoCountVoxelsLow], count);
    if (before + count < before) atomicAdd(counters[kNanoCountVoxelsHigh], 1u);
    if (!hasActive(s)) { // no bounding box: the origin, flags 0
        grid[at] = uint(origin.x), grid[at + 1u] = uint(origin.y), grid[at + 2u] = uint(origin.z);
        return;
    }
    uvec3 dif = uvec3(s.hi - s.lo);
    grid[at] = uint(s.lo.x), grid[at + 1u] = uint(s.lo.y), grid[at + 2u] = uint(s.lo.z);
    grid[at + kNanoLeafDifFlags] = dif.x | dif.y << 8u | dif.z << 16u | 2u << 24u;
    if (!hasValues()) return;
    grid[at + kNanoLeafMinimum] = s.mn;
    grid[at + kNanoLeafMinimum + 1u] = s.mx;
}
