#version 450 core
// Bitmap build, pass 2, one workgroup: the blocks' exclusive prefix sums,
// then (one thread) each level's start and the node and brick counts from
// the occupied nodes per level, and the root.
layout(local_size_x = 1024) in;
#include "octree_common.glsl"
#include "octree_bitmap.glsl"

shared uint partial[1024];

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
    uint run = partial[t] - sum;
    for (uint i = begin; i < end; ++i) {
        blocks[n + i] = run;
        run += blocks[i];
    }
    if (t != 0u) return;
    // The prefix at a level's first block, from the counts (other threads' writes are not visible here).
    uint total = partial[1023];
    uint before[SVO_BUILD_BITMAP_MAX_LEVEL + 2];
    for (uint l = 0u; l <= uBrickLevel + 1u; ++l) {
        uint b = uLevelBlock[l];
        if (b >= n) {
            before[l] = total;
            continue;
        }
        uint owner = b / per;
        uint p = owner == 0u ? 0u : partial[owner - 1u];
        for (uint i = owner * per; i < b; ++i) p += blocks[i];
        before[l] = p;
    }
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
