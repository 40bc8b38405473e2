#version 450 core
// Node origins for the outlines: the nodes store none, so each occupied node
// of level uLevel writes its children's origins (its own plus child bits
// times the child's size). Run level by level from the root, whose origin is 0.
layout(local_size_x = 256) in;
#include "gpu_layout.h"
#include "view_layout.h"

layout(std430, binding = SVO_BIND_VIEW_NODES) readonly restrict buffer Nodes { uint nodes[]; };
layout(std430, binding = SVO_BIND_VIEW_ORIGINS) restrict buffer Origins { uvec4 origins[]; };

uniform uint uFirst;     // first node of the level
uniform uint uCount;     // nodes in the level
uniform uint uChildSize; // a child's edge in voxels

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uCount) return;
    uint node = uFirst + i;
    uint mask = nodes[kNodeWords * node + 1u];
    if (mask == 0u) return;
    uint first = nodes[kNodeWords * node];
    uvec3 origin = origins[node].xyz;
    for (uint c = 0u; c < 8u; ++c)
        if ((mask & (1u << c)) != 0u)
            origins[first + c] = uvec4(origin + uvec3(c & 1u, (c >> 1u) & 1u, c >> 2u) * uChildSize, 0u);
}
