#version 450 core
// Bitmap build, pass 2, one workgroup: the blocks' exclusive prefix sums,
// then (one thread) each level's start and the node and brick counts from
// the occupied nodes per level, and the root.
layout(local_size_x = 1024) in;
#include "octree_common.glsl"
#include "octree_bitmap.glsl"

shared uint partial[1024];
shared uint before[SVO_BUILD_BITMAP_MAX_LEVEL + 2]; // occupied nodes before each level's first block

void main()
{
    uint n = blockCount(uBrickLevel);
    uint t = gl_LocalInvocationID.x;
    uint per = (n + 1023u) / 1024u;
    uint begin = min(t * per, n), end = min(begin + per, n);
    uint sum = 0u;
    for (uint i = begin; i < end; ++i) sum += blocks[i];
    partial[t] = sum;
    barrier();
    for (uint offset = 1u; offset < 1024u; offset <<= 1u) { // inclusive scan of the threads' sums
        uint v = t >= offset ? partial[t - offset] : 0u;
        barrier();
        partial[t] += v;
        barrier();
    }
    // Each level's first block lies in one thread's range: that thread records the prefix there.
    uint level = 0u;
    while (level <= uBrickLevel && uLevelBlock[level] < begin) ++level;
    uint run = partial[t] - sum;
    for (uint i = begin; i < end; ++i) {
        if (level <= uBrickLevel && uLevelBlock[level] == i) before[level++] = run;
        blocks[n + i] = run;
        run += blocks[i];
    }
    barrier();
    if (t != 0u) return;
    before[uBrickLevel + 1u] = partial[1023];
    state.levelStart[0] = 0u;
    state.levelStart[1] = 1u;
    for (uint l = 1u; l <= uBrickLevel; ++l)
        state.levelStart[l + 1u] = state.levelStart[l] + 8u * (before[l] - before[l - 1u]);
    state.nodeCount = state.levelStart[uBrickLevel + 1u];
    state.brickCount = before[uBrickLevel + 1u] - before[uBrickLevel];
    bool rootOccupied = before[1] != before[0];
    nodes[childOf(0u)] = rootOccupied && uBrickLevel > 0u ? 1u : 0u;
    nodes[maskOf(0u)] = !rootOccupied ? 0u : uBrickLevel == 0u ? 1u : childBits(0u, 0u);
}
