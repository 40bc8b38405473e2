#version 450 core
// Bitmap build, pass 3: every occupied node above the brick level writes its
// block of 8 children, occupied or not, so the node buffer needs no clearing.
// A child above the brick level points to its own block at its rank; at the
// brick level, to its brick at its rank.
layout(local_size_x = 256) in;
#include "octree_common.glsl"
#include "octree_bitmap.glsl"

uniform uint uNodeCapacity;
uniform uint uBrickCapacity;

void main()
{
    if (state.nodeCount > uNodeCapacity || state.brickCount > uBrickCapacity) return; // sized again and rebuilt
    uint words = uLevelBlock[uBrickLevel] * kBitmapBlockWords;
    for (uint w = gl_GlobalInvocationID.x; w < words; w += strideOf()) {
        uint bits = bitmap[w];
        if (bits == 0u) continue;
        uint level = 0u;
        while (uLevelBlock[level + 1u] * kBitmapBlockWords <= w) ++level;
        uint m = (w - uLevelBlock[level] * kBitmapBlockWords) << 5u;
        uint rank = rankOf(level, m, uBrickLevel);
        for (; bits != 0u; bits &= bits - 1u, ++rank) {
            uint node = m + uint(findLSB(bits));
            uint first = state.levelStart[level + 1u] + 8u * rank;
            uint occupied = childBits(level, node);
            uint childRank = occupied != 0u ? rankOf(level + 1u, node << 3u, uBrickLevel) : 0u;
            for (uint c = 0u; c < 8u; ++c) {
                uint child = 0u, mask = 0u;
                if ((occupied >> c & 1u) != 0u) {
                    uint code = (node << 3u) | c;
                    if (level + 1u == uBrickLevel) {
                        child = childRank, mask = 1u;
                    } else {
                        child = state.levelStart[level + 2u] + 8u * childRank;
                        mask = childBits(level + 1u, code);
                    }
                    ++childRank;
                }
                nodes[childOf(first + c)] = child;
                nodes[maskOf(first + c)] = mask;
            }
        }
    }
}
