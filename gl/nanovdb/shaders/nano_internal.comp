#version 450 core
// Passes 5 and 6, a work group per lower (then upper) node: child masks and
// offsets, a lower node's 8^3 tiles (their values, and the value mask of
// the active ones), the background in every other table entry, the
// bounding box, flags and statistics merged from the active tiles, then
// the children, each in index order (as the CPU builder folds them); an
// upper node also writes its root tile.
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
shared uint tileMask[128];   // a lower node's tiles, active or not
shared uint valueMask[128];  // its active tiles

uint log2Dim() { return uUpper != 0u ? kNanoUpperLog2 : kNanoLowerLog2; }
uint nodeWords()
{
    bool isVec3 = uType == kNanoTypeVec3f;
    return uUpper != 0u ? (isVec3 ? kNanoUpperWordsVec3f : kNanoUpperWords) : (isVec3 ? kNanoLowerWordsVec3f : kNanoLowerWords);
}
uint entryWords() { return uType == kNanoTypeVec3f ? 4u : 2u; } // a table entry: a value or an int64 child offset
uint rootBytes() { return uType == kNanoTypeVec3f ? kNanoRootBytesVec3f : kNanoRootBytes; }
uint tableAt() { return uUpper != 0u ? kNanoUpperTable : kNanoLowerTable; }
// A node's children: sorted entries (leaves and tiles) of a lower node, lower nodes of an upper one.
uint firstChild(uint node) { return ranks[uUpper != 0u ? upperFirstLowerAt(node) : lowerFirstEntryAt(node)]; }
uint firstEntryOfLower(uint lower) { return ranks[lowerFirstEntryAt(lower)]; }
uint indexInParent(uint child) { return uUpper != 0u ? lowerIndexOf(firstEntryOfLower(child)) : leafIndexOf(child); }

// A tile's value word as the table holds it (a bool's byte for Bool and Mask).
uint tileWord(uint value) { return hasValues() ? value : uint(value != 0u); }

// Tile entry c of a lower node at word `at`, index n: its table value and
// mask bits; its statistics when active.
NodeStats linkTile(uint at, uint c, uint n)
{
    uint tile = (inputLeaf(c) - uLeafCount) * kNanoTileWords;
    uint value = tileWord(tiles[tile + 3u]); // scalar kinds only (the host refuses Vec3f tiles)
    grid[at + tableAt() + 2u * n] = value;
    atomicOr(tileMask[n >> 5u], 1u << (n & 31u));
    if (tiles[tile + 4u] == 0u) return emptyStats();
    atomicOr(valueMask[n >> 5u], 1u << (n & 31u));
    atomicAdd(counters[kNanoCountActiveTiles], 1u);
    uint before = atomicAdd(counters[kNanoCountVoxelsLow], 512u);
    if (before + 512u < before) atomicAdd(counters[kNanoCountVoxelsHigh], 1u);
    ivec3 o = ivec3(tiles[tile], tiles[tile + 1u], tiles[tile + 2u]);
    return NodeStats(o, o + ivec3(7), uvec3(value, 0u, 0u), uvec3(value, 0u, 0u));
}

// Children [begin, end), a contiguous run per invocation (so the reduction
// keeps their order): mask bits, table offsets, statistics; tiles' apart.
void linkChildren(uint at, uint begin, uint end, out NodeStats fromTiles, out NodeStats fromChildren)
{
    uint per = (end - begin + uint(NANO_GROUP) - 1u) / uint(NANO_GROUP);
    uint from = min(begin + gl_LocalInvocationIndex * per, end), to = min(from + per, end);
    fromTiles = emptyStats();
    fromChildren = emptyStats();
    for (uint c = from; c < to; ++c) {
        uint n = indexInParent(c);
        if (uUpper == 0u && isTile(c)) {
            fromTiles = merge(fromTiles, linkTile(at, c, n));
            continue;
        }
        uint child = uUpper != 0u ? c : ranks[leafRankAt(c)]; // its place in its level
        atomicOr(childMask[n >> 5u], 1u << (n & 31u));
        uvec2 offset = byteOffset(at, uChildAt + child * uChildWords);
        uint e = at + tableAt() + entryWords() * n;
        grid[e] = offset.x;
        grid[e + 1u] = offset.y;
        // The CPU sets every entry's value, then a child's offset over its
        // first 8 bytes: a Vec3f's third word stays the background's.
        if (valueWords() == 3u) grid[e + 2u] = uBackground;
        fromChildren = merge(fromChildren, loadStats(uChildStatsAt + child));
    }
}

void writeRootTile(uint node, uint at, ivec3 origin)
{
    uint tile = uRootAt + rootBytes() / 4u + node * (kNanoTileBytes / 4u);
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
    for (uint w = t; w < 128u; w += uint(NANO_GROUP)) tileMask[w] = valueMask[w] = 0u;
    memoryBarrierShared();
    barrier();
    uint begin = firstChild(node), end = firstChild(node + 1u);
    NodeStats fromTiles, fromChildren;
    linkChildren(at, begin, end, fromTiles, fromChildren);
    // nanovdb::GridStats folds the active tiles first, then the children.
    // The reductions' barriers order the mask bits too.
    NodeStats s = reduceGroup(fromTiles);
    barrier(); // every invocation has read the first result before the second reuses its memory
    s = merge(s, reduceGroup(fromChildren));
    uint maskAt = at + (uUpper != 0u ? kNanoUpperChildMask : kNanoLowerChildMask);
    for (uint w = t; w < maskWords; w += uint(NANO_GROUP)) {
        grid[maskAt + w] = childMask[w];
        if (uUpper == 0u) grid[at + kNanoNodeValueMask + w] = valueMask[w];
    }
    for (uint n = t; n < entries; n += uint(NANO_GROUP)) {
        bool taken = (childMask[n >> 5u] & (1u << (n & 31u))) != 0u ||
                     (uUpper == 0u && (tileMask[n >> 5u] & (1u << (n & 31u))) != 0u);
        if (!taken)
            for (uint c = 0u; c < valueWords(); ++c) grid[at + tableAt() + entryWords() * n + c] = uBackground;
    }
    if (t != 0u) return;
    storeStats(uStatsAt + node, s);
    if (uUpper != 0u) writeRootTile(node, at, upperOrigin(firstEntryOfLower(begin)));
    bool any = hasActive(s);
    ivec3 lo = any ? s.lo : ivec3(0x7FFFFFFF), hi = any ? s.hi : ivec3(-0x7FFFFFFF - 1); // empty: nanovdb's empty box
    grid[at] = uint(lo.x), grid[at + 1u] = uint(lo.y), grid[at + 2u] = uint(lo.z);
    grid[at + 3u] = uint(hi.x), grid[at + 4u] = uint(hi.y), grid[at + 5u] = uint(hi.z);
    grid[at + kNanoNodeFlags] = any ? 2u : 1u;
    if (!any || !hasValues()) return;
    writeExtrema(at + (uUpper != 0u ? kNanoUpperMinimum : kNanoLowerMinimum), s);
}
