#version 450 core
// Sets each entry's bits in its brick: one voxel (a voxel-list key) or a
// whole 512-bit mask (brick input, uBrickMasks = 1).
layout(local_size_x = 256) in;
#include "octree_common.glsl"

layout(std430, binding = 5) readonly restrict buffer Masks { uint masks[]; };
uniform uint uBrickMasks;

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < state.entryCount; i += strideOf()) {
        uvec2 key = entries[i];
        uint node = descend(brickOfEntry(key), uBrickLevel);
        if (node == kNoChild) continue;
        uint brick = nodes[2u * node];
        if (brick == kNoChild) continue;
        if (uBrickMasks == 0u) {
            uint bit = key.x & 511u;
            atomicOr(bricks[16u * brick + (bit >> 5u)], 1u << (bit & 31u));
        } else {
            for (uint w = 0u; w < 16u; ++w) {
                uint m = masks[16u * i + w];
                if (m != 0u) atomicOr(bricks[16u * brick + w], m);
            }
        }
    }
}
