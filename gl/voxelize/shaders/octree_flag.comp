#version 450 core
// Each entry marks, in its node at level uLevel, the child its brick lies in
// (or, at the brick level, the node itself).
layout(local_size_x = 256) in;
#include "octree_common.glsl"

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < state.entryCount; i += strideOf()) {
        uvec3 b = brickOfVoxelKey(entries[i]);
        uint node = descend(b, uLevel);
        if (node == kNoChild) continue;
        uint bit = 1u;
        if (uLevel < uBrickLevel) bit = 1u << childIndex(b, uBrickLevel - 1u - uLevel);
        // Most entries find their bit set already; reading first spares the atomic.
        if ((nodes[maskOf(node)] & bit) == 0u) atomicOr(nodes[maskOf(node)], bit);
    }
}
