#version 450 core
// Bitmap build, pass 1: each entry sets its brick's bit at the brick level
// and its ancestors' bits above, counting each new bit in its block. The
// thread that sets a bit goes on up, so one that finds its bit set stops.
layout(local_size_x = 256) in;
#include "octree_common.glsl"
#include "octree_bitmap.glsl"

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < state.entryCount; i += strideOf()) {
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
