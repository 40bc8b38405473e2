// The bitmap build's occupancy bits (octree_builder.cpp, gpu_layout.h): level
// l's nodes one bit each in Morton order from block uLevelBlock[l]. After
// octree_scan.comp, a node's rank among the occupied nodes of its level is
// its block's prefix plus the bits before it in its block, which is what
// places it: the linear octree keeps each level in Morton order.
#include "gpu_layout.h"
#include "voxelize_layout.h"

layout(std430, binding = SVO_BIND_BUILD_BITMAP) restrict buffer Bitmap { uint bitmap[]; };
// Per block its set bits (first uBlockCount), then the exclusive prefix of those.
layout(std430, binding = SVO_BIND_BUILD_BLOCKS) restrict buffer Blocks { uint blocks[]; };

// First block of each level; [L + 1] is one past the last, the block count.
uniform uint uLevelBlock[SVO_BUILD_BITMAP_MAX_LEVEL + 2];

uint blockCount(uint brickLevel) { return uLevelBlock[brickLevel + 1u]; }

// Bits 0..9 of v to every third bit.
uint spreadBits3(uint v)
{
    v &= 0x3FFu;
    v = (v | (v << 16u)) & 0x030000FFu;
    v = (v | (v << 8u)) & 0x0300F00Fu;
    v = (v | (v << 4u)) & 0x030C30C3u;
    v = (v | (v << 2u)) & 0x09249249u;
    return v;
}
// Morton code of a brick: child index c = x + 2y + 4z at every level.
uint mortonOf(uvec3 b) { return spreadBits3(b.x) | (spreadBits3(b.y) << 1u) | (spreadBits3(b.z) << 2u); }

uint bitWord(uint level, uint m) { return uLevelBlock[level] * kBitmapBlockWords + (m >> 5u); }
// The 8 occupancy bits of node m's children (m at `level`, they at level + 1).
uint childBits(uint level, uint m)
{
    return (bitmap[uLevelBlock[level + 1u] * kBitmapBlockWords + (m >> 2u)] >> (8u * (m & 3u))) & 0xFFu;
}
// Occupied nodes of `level` before code m (valid after octree_scan.comp).
uint rankOf(uint level, uint m, uint brickLevel)
{
    uint n = blockCount(brickLevel);
    uint block = uLevelBlock[level] + (m >> kBitmapBlockShift);
    uint r = blocks[n + block] - blocks[n + uLevelBlock[level]];
    uint word = bitWord(level, m);
    for (uint w = block * kBitmapBlockWords; w < word; ++w) r += uint(bitCount(bitmap[w]));
    return r + uint(bitCount(bitmap[word] & ((1u << (m & 31u)) - 1u)));
}
