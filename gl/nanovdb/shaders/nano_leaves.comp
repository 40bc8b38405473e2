#version 450 core
// Pass 4, a work group per leaf in its laid-out order (sorted, tiles left
// out: leafEntryAt), 8 voxels an invocation: the leaf's
// origin, bounding box, flags, value mask and statistics, folded over its
// active voxels in bit order as the CPU builder folds them (an invocation
// folds its 8, the group merges them in order: nano_stats.glsl); its
// statistics for its parent; the active voxel count. (The values
// themselves: nano_values.comp.) A group a leaf, not an invocation a leaf:
// an invocation's loop over a whole leaf ran 8x slower on an H200 when the
// leaves came in the band's hash order (each invocation of a warp reading
// its own 2 KB, far from the others').
#define NANO_GROUP 64
layout(local_size_x = NANO_GROUP) in;
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
    uint i = groupIndex();
    if (i >= uLeafCount) return; // the whole group: no barrier is left waiting
    uint t = gl_LocalInvocationIndex, leaf = inputLeaf(ranks[leafEntryAt(i)]), at = uLeafAt + i * uLeafWords;
    ivec3 origin = ivec3(origins[3u * leaf], origins[3u * leaf + 1u], origins[3u * leaf + 2u]);
    uint word = masks[leaf * 16u + (t >> 2u)];
    if ((t & 3u) == 0u) grid[at + kNanoLeafValueMask + (t >> 2u)] = word;
    NodeStats s = emptyStats();
    uint n = valueWords();
    for (uint bits = (word >> (8u * (t & 3u))) & 0xFFu; bits != 0u; bits &= bits - 1u) {
        uint v = 8u * t + uint(findLSB(bits));
        uvec3 value = uvec3(uHasActive != 0u ? uActive : uBackground);
        if (uHasValues != 0u)
            for (uint c = 0u; c < n; ++c) value[c] = values[(leaf * 512u + v) * n + c];
        if (n == 1u) value.yz = uvec2(0u);
        ivec3 c = origin + ivec3(v >> 6u, (v >> 3u) & 7u, v & 7u);
        s = merge(s, NodeStats(c, c, value, value));
    }
    s = reduceGroup(s);
    if (t != 0u) return;
    uint count = 0u;
    for (uint w = 0u; w < 16u; ++w) count += bitCount(masks[leaf * 16u + w]);
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
    writeExtrema(at + kNanoLeafMinimum, s);
}
