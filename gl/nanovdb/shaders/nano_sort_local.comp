#version 450 core
// Pass 2, the bitonic sort's steps whose pairs lie in one block of
// uBlock entries (distance j < uBlock), in shared memory, one work group a
// block: with uK = 0 every step of sequences up to uBlock (the blocks
// sorted, alternately ascending and descending as the global sort has
// them); else the steps j = uBlock / 2 ... 1 of merging sequences of uK.
// Each step is nano_sort.comp's (uK, uJ) on the same entries, so the order
// is the same; only the dispatches and their barriers are fewer.
layout(local_size_x = 512) in;
#include "nano_common.glsl"

uniform uint uBlock; // a power of two, at most 1024, at most the sort's size
uniform uint uK;     // 0: sort the blocks; else the size of the sequences being merged

shared uint block[1024 * kNanoSortWords];

bool keyLess(uint a, uint b)
{
    for (uint w = 0u; w < 4u; ++w) {
        uint x = block[a * kNanoSortWords + w], y = block[b * kNanoSortWords + w];
        if (x != y) return x < y;
    }
    return false;
}

// One compare-exchange step (k, j) over the block, thread t taking the pair
// whose lower entry has bit j clear.
void step(uint base, uint t, uint k, uint j)
{
    if (t < uBlock / 2u) {
        uint i = ((t & ~(j - 1u)) << 1u) | (t & (j - 1u)), l = i + j;
        bool ascending = ((base + i) & k) == 0u;
        if (ascending ? keyLess(l, i) : keyLess(i, l))
            for (uint w = 0u; w < kNanoSortWords; ++w) {
                uint a = i * kNanoSortWords + w, b = l * kNanoSortWords + w, x = block[a];
                block[a] = block[b];
                block[b] = x;
            }
    }
    memoryBarrierShared();
    barrier();
}

void main()
{
    uint t = gl_LocalInvocationID.x, base = groupIndex() * uBlock;
    uint words = uBlock * kNanoSortWords;
    for (uint w = t; w < words; w += 512u) block[w] = sortKeys[base * kNanoSortWords + w];
    memoryBarrierShared();
    barrier();
    if (uK == 0u) {
        for (uint k = 2u; k <= uBlock; k <<= 1u)
            for (uint j = k >> 1u; j > 0u; j >>= 1u) step(base, t, k, j);
    } else {
        for (uint j = uBlock >> 1u; j > 0u; j >>= 1u) step(base, t, uK, j);
    }
    for (uint w = t; w < words; w += 512u) sortKeys[base * kNanoSortWords + w] = block[w];
}
