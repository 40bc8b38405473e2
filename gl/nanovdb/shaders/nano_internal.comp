#version 450 core
// Passes 5 and 6, a work group per lower (then upper) node: child masks and
// offsets, the background in every other table entry, the bounding box,
// flags and statistics merged from the children in index order; an upper
// node also writes its root tile.
#define NANO_GROUP 256
layout(local_size_x = NANO_GROUP) in;
#include "nano_common.glsl"
#include "nano_stats.glsl"

uniform uint uUpper;       // 0: lower nodes (children are leaves), 1: upper nodes (children are lower nodes)
uniform uint uNodeCount;   // nodes of this level
uniform uint uNodeAt;      // the first node's word in the grid
uniform uint uChildAt;     // the first child's word
uniform uint uChildWords;  // words per child
uniform uint uStatsAt;     // the first node's statistics slot
uniform uint uChildStatsAt;
uniform uint uRootAt;      // the root's word (upper nodes: their tiles follow it)
uniform uint uBackground;  // the background's bits

shared uint childMask[1024]; // 32768 bits: an upper node's; a lower node uses 128 words

uint log2Dim() { return uUpper != 0u ? kNanoUpperLog2 : kNanoLowerLog2; }
uint nodeWords() { return uUpper != 0u ? kNanoUpperWords : kNanoLowerWords; }
uint tableAt() { return uUpper != 0u ? kNanoUpperTable : kNanoLowerTable; }
uint firstChild(uint node) { return ranks[uUpper != 0u ? upperFirstLowerAt(node) : lowerFirstLeafAt(node)]; }
uint firstLeafOfLower(uint lower) { return ranks[lowerFirstLeafAt(lower)]; }
uint indexInParent(uint child) { return uUpper != 0u ? lowerIndexOf(firstLeafOfLower(child)) : leafIndexOf(child); }

// Children [begin, end), a contiguous run per invocation (so the reduction
// keeps their order): mask bits, table offsets, statistics.
NodeStats linkChildren(uint at, uint begin, uint end)
{
    uint per = (end - begin + uint(NANO_GROUP) - 1u) / uint(NANO_GROUP);
    uint from = min(begin + gl_LocalInvocationIndex * per, end), to = min(from + per, end);
    NodeStats s = emptyStats();
    for (uint c = from; c < to; ++c) {
        uint n = indexInParent(c);
        atomicOr(childMask[n >> 5u], 1u << (n & 31u));
        uvec2 offset = byteOffset(at, uChildAt + c * uChildWords);
        grid[at + tableAt() + 2u * n] = offset.x;
        grid[at + tableAt() + 2u * n + 1u] = offset.y;
        s = merge(s, loadStats(uChildStatsAt + c));
    }
    return s;
}

void writeRootTile(uint node, uint at, ivec3 origin)
{
    uint tile = uRootAt + kNanoRootBytes / 4u + node * (kNanoTileBytes / 4u);
    uvec3 k = uvec3(origin) >> 12u; // nanovdb's 21 bits per axis
    grid[tile] = k.z | k.y << 21u;
    grid[tile + 1u] = k.y >> 11u | k.x << 10u;
    uvec2 offset = byteOffset(uRootAt, at);
    grid[tile + 2u] = offset.x;
    grid[tile + 3u] = offset.y;
}

void main()
{
    uint node = groupIndex();
    if (node >= uNodeCount) return;
    uint t = gl_LocalInvocationIndex, at = uNodeAt + node * nodeWords();
    uint entries = 1u << (3u * log2Dim()), maskWords = entries >> 5u;
    for (uint w = t; w < maskWords; w += uint(NANO_GROUP)) childMask[w] = 0u;
    memoryBarrierShared();
    barrier();
    uint begin = firstChild(node), end = firstChild(node + 1u);
    NodeStats s = reduceGroup(linkChildren(at, begin, end)); // its barriers order the mask bits too
    uint maskAt = at + (uUpper != 0u ? kNanoUpperChildMask : kNanoLowerChildMask);
    for (uint w = t; w < maskWords; w += uint(NANO_GROUP)) grid[maskAt + w] = childMask[w];
    for (uint n = t; n < entries; n += uint(NANO_GROUP))
        if ((childMask[n >> 5u] & (1u << (n & 31u))) == 0u) grid[at + tableAt() + 2u * n] = uBackground;
    if (t != 0u) return;
    storeStats(uStatsAt + node, s);
    if (uUpper != 0u) writeRootTile(node, at, upperOrigin(firstLeafOfLower(begin)));
    bool any = hasActive(s);
    ivec3 lo = any ? s.lo : ivec3(0x7FFFFFFF), hi = any ? s.hi : ivec3(-0x7FFFFFFF - 1); // empty: nanovdb's empty box
    grid[at] = uint(lo.x), grid[at + 1u] = uint(lo.y), grid[at + 2u] = uint(lo.z);
    grid[at + 3u] = uint(hi.x), grid[at + 4u] = uint(hi.y), grid[at + 5u] = uint(hi.z);
    grid[at + kNanoNodeFlags] = any ? 2u : 1u;
    if (!any || !hasValues()) return;
    uint minAt = at + (uUpper != 0u ? kNanoUpperMinimum : kNanoLowerMinimum);
    grid[minAt] = s.mn;
    grid[minAt + 1u] = s.mx;
}
