#version 450 core
// Sets each entry's bits in its brick: one voxel (a voxel-list key) or a
// whole 512-bit mask (brick input, uBrickMasks = 1). The brick is found by
// its rank in the brick level's bitmap (uBitmapBuild = 1) or by descending
// from the root.
layout(local_size_x = 256) in;
#include "octree_common.glsl"
#include "octree_bitmap.glsl"

layout(std430, binding = SVO_BIND_ENTRY_MASKS) readonly restrict buffer Masks { uint masks[]; };
uniform uint uBrickMasks;
uniform uint uBitmapBuild;
uniform uint uNodeCapacity;
uniform uint uBrickCapacity;

void main()
{
    if (uBitmapBuild != 0u && (state.nodeCount > uNodeCapacity || state.brickCount > uBrickCapacity)) return;
    for (uint i = gl_GlobalInvocationID.x; i < state.entryCount; i += strideOf()) {
        uvec2 key = entries[i];
        uint brick;
        if (uBitmapBuild != 0u) {
            brick = rankOf(uBrickLevel, mortonOf(brickOfVoxelKey(key)), uBrickLevel);
        } else {
            uint node = descend(brickOfVoxelKey(key), uBrickLevel);
            if (node == kNoChild) continue;
            brick = nodes[childOf(node)];
            if (brick == kNoChild) continue;
        }
        if (uBrickMasks == 0u) {
            uint bit = leafBitOfVoxelKey(key);
            atomicOr(bricks[brickWord(brick, bit)], 1u << (bit & 31u));
        } else {
            for (uint w = 0u; w < kBrickWords; ++w) {
                uint m = masks[kBrickWords * i + w];
                if (m != 0u) atomicOr(bricks[kBrickWords * brick + w], m);
            }
        }
    }
}
