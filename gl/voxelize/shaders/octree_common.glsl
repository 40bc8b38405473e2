// Buffers and helpers shared by the octree build passes (octree_builder.cpp).
// Nodes are uint pairs (child, childMask), bricks 16 uints (8 little-endian
// uint64 words of an OpenVDB leaf mask); see core/octree.h. Layouts, binding
// slots and key helpers come from gpu_layout.h.
#include "gpu_layout.h"
#include "voxelize_layout.h"

layout(std430, binding = SVO_BIND_BUILD_STATE) restrict buffer BuildState { SVO_BUILD_STATE_FIELDS } state;
layout(std430, binding = SVO_BIND_NODES) restrict buffer Nodes { uint nodes[]; };
layout(std430, binding = SVO_BIND_BRICKS) restrict buffer Bricks { uint bricks[]; };
layout(std430, binding = SVO_BIND_ENTRIES) readonly restrict buffer Entries { uvec2 entries[]; };

uniform uint uBrickLevel;
uniform uint uLevel;

// Words of node n: child at kNodeWords * n, childMask after it.
uint childOf(uint node) { return kNodeWords * node; }
uint maskOf(uint node) { return kNodeWords * node + 1u; }

// Which of its 8 siblings (c = x + 2y + 4z) holds brick b, at the level whose
// children split brick coordinates at bit s.
uint childIndex(uvec3 b, uint s) { return ((b.x >> s) & 1u) | (((b.y >> s) & 1u) << 1u) | (((b.z >> s) & 1u) << 2u); }

// Index of the node at `level` on the path to brick b, or kNoChild when an
// ancestor's children could not be allocated.
uint descend(uvec3 b, uint level)
{
    uint node = 0u;
    for (uint d = 0u; d < level; ++d) {
        uint child = nodes[childOf(node)];
        if (child == kNoChild || child == 0u) return kNoChild;
        node = child + childIndex(b, uBrickLevel - 1u - d);
    }
    return node;
}

// The word of bricks[] that holds bit `bit` (0..511, leafBitOfVoxelKey) of a brick.
uint brickWord(uint brick, uint bit) { return kBrickWords * brick + (bit >> 5u); }

// Grid-stride loop bounds: threads of a dispatch capped at 65535 groups.
uint strideOf() { return gl_NumWorkGroups.x * gl_WorkGroupSize.x; }
