#version 450 core
// Each marked node of level uLevel gets a block of 8 zeroed children (the
// node buffer is cleared before the build) or, at the brick level, a brick.
layout(local_size_x = 256) in;
#include "octree_common.glsl"

uniform uint uNodeCapacity;
uniform uint uBrickCapacity;

void main()
{
    uint first = state.levelStart[uLevel];
    uint count = state.levelStart[uLevel + 1u] - first;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += strideOf()) {
        uint node = first + i;
        if (nodes[maskOf(node)] == 0u) continue;
        uint child;
        if (uLevel < uBrickLevel) {
            child = atomicAdd(state.nodeCount, 8u);
            if (child + 8u > uNodeCapacity) child = kNoChild;
        } else {
            child = atomicAdd(state.brickCount, 1u);
            if (child >= uBrickCapacity) child = kNoChild;
        }
        nodes[childOf(node)] = child;
    }
}
