#version 450 core
// One thread: turns counters into indirect dispatch arguments, so the CPU
// never waits between passes.
//   uMode 0: entries = min(voxel-list counter, list capacity)
//   uMode 1: records where level uLevel ends and sizes the dispatch over it
layout(local_size_x = 1) in;
#include "octree_common.glsl"

layout(std430, binding = SVO_BIND_LIST_COUNTER) readonly restrict buffer ListCounter { uint listCounter; };
uniform uint uMode;
uniform uint uEntryCapacity;
uniform uint uNodeCapacity;
const uint kGroup = 256u;

uint groupsFor(uint n) { return clamp((n + kGroup - 1u) / kGroup, 1u, 65535u); }

void main()
{
    if (uMode == 0u) {
        state.entryCount = min(listCounter, uEntryCapacity);
        state.entryDispatch[0] = groupsFor(state.entryCount);
        state.entryDispatch[1] = 1u;
        state.entryDispatch[2] = 1u;
    } else {
        state.levelStart[uLevel + 1u] = min(state.nodeCount, uNodeCapacity);
        state.levelDispatch[0] = groupsFor(state.levelStart[uLevel + 1u] - state.levelStart[uLevel]);
        state.levelDispatch[1] = 1u;
        state.levelDispatch[2] = 1u;
    }
}
