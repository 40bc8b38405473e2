#version 450 core
// Pass 4, an invocation per sorted leaf: the leaf's origin, bounding box,
// flags, value mask and statistics, folded over its active voxels in bit
// order as the CPU builder folds them; its statistics for its parent; the
// active voxel count. (The values themselves: nano_values.comp.)
layout(local_size_x = 64) in;
#include "nano_common.glsl"
#include "nano_stats.glsl"

uniform uint uLeafAt;     // the first leaf's word in the grid
uniform uint uLeafWords;  // words per leaf
uniform uint uHasValues;  // 1: values[] holds 512 words per leaf
uniform uint uBackground; // the background's bits
uniform uint uHasActive;  // 1 (without values): active voxels hold uActive
uniform uint uActive;     // their value's bits

void main()
{
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x;
    if (i >= uLeafCount) return;
    uint leaf = inputLeaf(i), at = uLeafAt + i * uLeafWords, count = 0u;
    ivec3 origin = ivec3(origins[3u * leaf], origins[3u * leaf + 1u], origins[3u * leaf + 2u]);
    NodeStats s = emptyStats();
    for (uint w = 0u; w < 16u; ++w) {
        uint word = masks[leaf * 16u + w];
        grid[at + kNanoLeafValueMask + w] = word;
        count += bitCount(word);
        for (uint bits = word; bits != 0u; bits &= bits - 1u) {
            uint v = 32u * w + uint(findLSB(bits));
            uint value = uHasValues != 0u ? values[leaf * 512u + v] : uHasActive != 0u ? uActive : uBackground;
            ivec3 c = origin + ivec3(v >> 6u, (v >> 3u) & 7u, v & 7u);
            s = merge(s, NodeStats(c, c, value, value));
        }
    }
    storeStats(i, s);
    uint before = atomicAdd(counters[kNanoCountVoxelsLow], count);
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
