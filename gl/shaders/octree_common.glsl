// Buffers and helpers shared by the octree build passes (octree_builder.cpp).
// Nodes are uint pairs (child, childMask), bricks 16 uints (8 little-endian
// uint64 words of an OpenVDB leaf mask); see core/octree.h.

const uint kNoChild = 0xFFFFFFFFu;

layout(std430, binding = 0) restrict buffer BuildState {
    uint entryDispatch[3]; // indirect args over the input entries (byte offset 0)
    uint levelDispatch[3]; // indirect args over the current level's nodes (byte offset 12)
    uint entryCount;      // input entries to read
    uint nodeCount;       // node allocation counter (may pass capacity)
    uint brickCount;      // brick allocation counter (may pass capacity)
    uint pad;
    uint levelStart[24];  // first node of each level
} state;
layout(std430, binding = 1) restrict buffer Nodes { uint nodes[]; };
layout(std430, binding = 2) restrict buffer Bricks { uint bricks[]; };
layout(std430, binding = 3) readonly restrict buffer Entries { uvec2 entries[]; };

uniform uint uBrickLevel;
uniform uint uLevel;

// Brick coordinates of a voxel key (core/voxel_key.h, split low/high).
uvec3 brickOfEntry(uvec2 key)
{
    return uvec3((key.y >> 13u) & 0x3FFFFu, (key.x >> 27u) | ((key.y & 0x1FFFu) << 5u), (key.x >> 9u) & 0x3FFFFu);
}

// Index of the node at `level` on the path to brick b, or kNoChild when an
// ancestor's children could not be allocated.
uint descend(uvec3 b, uint level)
{
    uint node = 0u;
    for (uint d = 0u; d < level; ++d) {
        uint child = nodes[2u * node];
        if (child == kNoChild || child == 0u) return kNoChild;
        uint s = uBrickLevel - 1u - d;
        node = child + (((b.x >> s) & 1u) | (((b.y >> s) & 1u) << 1u) | (((b.z >> s) & 1u) << 2u));
    }
    return node;
}

// Grid-stride loop bounds: threads of a dispatch capped at 65535 groups.
uint strideOf() { return gl_NumWorkGroups.x * gl_WorkGroupSize.x; }
