#version 450 core
// Bitmap build, pass 1. Each entry sets its brick's bit at the brick level
// and its ancestors' bits above, counting each new bit in its block; the
// thread that sets a bit goes on up, so one that finds its bit set stops.
// The last workgroup to finish then ranks the blocks (their exclusive prefix
// sums), sets each level's start, the node and brick counts and the root:
// one dispatch, so the build waits on the GPU twice, not once per level.
layout(local_size_x = 256) in;
#include "octree_common.glsl"
#define SVO_BLOCKS_COHERENCE coherent // the last group reads every group's counts
#include "octree_bitmap.glsl"

layout(std430, binding = SVO_BIND_LIST_COUNTER) readonly restrict buffer ListCounter { uint listCounter; };
uniform uint uCountFromList; // 1: min(list counter, uEntryCapacity) entries; 0: uEntryCapacity
uniform uint uEntryCapacity;

const uint kThreads = 256u;
shared uint partial[kThreads];
shared uint levelBefore[SVO_BUILD_BITMAP_MAX_LEVEL + 2]; // occupied nodes before each level's first block
shared bool lastGroup;

void mark()
{
    uint count = uCountFromList != 0u ? min(listCounter, uEntryCapacity) : uEntryCapacity;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += strideOf()) {
        uint m = mortonOf(brickOfVoxelKey(entries[i]));
        for (int level = int(uBrickLevel); level >= 0; --level, m >>= 3u) {
            uint word = bitWord(uint(level), m), bit = 1u << (m & 31u);
            // Most entries share their brick with others: reading first spares the atomic.
            if ((bitmap[word] & bit) != 0u) break;
            if ((atomicOr(bitmap[word], bit) & bit) != 0u) break;
            atomicAdd(blocks[uLevelBlock[level] + (m >> kBitmapBlockShift)], 1u);
        }
    }
}

void rank()
{
    uint n = blockCount(uBrickLevel);
    uint t = gl_LocalInvocationID.x;
    uint per = (n + kThreads - 1u) / kThreads;
    uint begin = min(t * per, n), end = min(begin + per, n);
    uint sum = 0u;
    for (uint i = begin; i < end; ++i) sum += blocks[i];
    partial[t] = sum;
    barrier();
    for (uint offset = 1u; offset < kThreads; offset <<= 1u) { // inclusive scan of the threads' sums
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
        if (level <= uBrickLevel && uLevelBlock[level] == i) levelBefore[level++] = run;
        blocks[n + i] = run;
        run += blocks[i];
    }
    barrier();
    if (t != 0u) return;
    levelBefore[uBrickLevel + 1u] = partial[kThreads - 1u];
    state.levelStart[0] = 0u;
    state.levelStart[1] = 1u;
    for (uint l = 1u; l <= uBrickLevel; ++l)
        state.levelStart[l + 1u] = state.levelStart[l] + 8u * (levelBefore[l] - levelBefore[l - 1u]);
    state.nodeCount = state.levelStart[uBrickLevel + 1u];
    state.brickCount = levelBefore[uBrickLevel + 1u] - levelBefore[uBrickLevel];
    bool rootOccupied = levelBefore[1] != levelBefore[0];
    uint rootChildren = uBrickLevel == 0u ? 0u : atomicOr(bitmap[uLevelBlock[1] * kBitmapBlockWords], 0u) & 0xFFu;
    nodes[childOf(0u)] = rootOccupied && uBrickLevel > 0u ? 1u : 0u;
    nodes[maskOf(0u)] = !rootOccupied ? 0u : uBrickLevel == 0u ? 1u : rootChildren;
}

void main()
{
    mark();
    memoryBarrierBuffer(); // this group's bits and counts before its count of done groups
    barrier();
    if (gl_LocalInvocationIndex == 0u) lastGroup = atomicAdd(state.groupsDone, 1u) == gl_NumWorkGroups.x - 1u;
    barrier();
    if (lastGroup) rank();
}
