// nano_common.glsl: the GPU grid builder's buffers and the sort keys' meaning
// (nano_layout.h). Each pass declares what it reads and writes here; the
// unused ones cost nothing.
#include "gpu_layout.h"
#include "nano_layout.h"

layout(std430, binding = SVO_BIND_NANO_ORIGINS) readonly buffer Origins { int origins[]; };
layout(std430, binding = SVO_BIND_NANO_MASKS) readonly buffer Masks { uint masks[]; };
layout(std430, binding = SVO_BIND_NANO_VALUES) readonly buffer Values { uint values[]; };
layout(std430, binding = SVO_BIND_NANO_SORT) buffer Sort { uint sortKeys[]; };
layout(std430, binding = SVO_BIND_NANO_RANKS) buffer Ranks { uint ranks[]; };
layout(std430, binding = SVO_BIND_NANO_STATS) buffer Stats { uint stats[]; };
layout(std430, binding = SVO_BIND_NANO_COUNTERS) buffer Counters { uint counters[]; };
layout(std430, binding = SVO_BIND_NANO_GRID) buffer Grid { uint grid[]; };
layout(std430, binding = SVO_BIND_NANO_TILES) readonly buffer Tiles { uint tiles[]; };

uniform uint uLeafCount;  // leaves
uniform uint uEntryCount; // leaves and 8^3 tiles: the sort's real entries

// A work group's index in a 2D dispatch (x up to 65535 groups).
uint groupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

uint sortWord(uint entry, uint word) { return sortKeys[entry * kNanoSortWords + word]; }
uint inputLeaf(uint sorted) { return sortWord(sorted, 4u); } // a tile's: uLeafCount + its index
bool isTile(uint sorted) { return inputLeaf(sorted) >= uLeafCount; }
uint lowerIndexOf(uint sorted) { return sortWord(sorted, 3u) >> 12u; } // in its upper node
uint leafIndexOf(uint sorted) { return sortWord(sorted, 3u) & 4095u; } // in its lower node

// The origin of a sorted leaf's upper node.
ivec3 upperOrigin(uint sorted)
{
    uvec3 k = uvec3(sortWord(sorted, 0u), sortWord(sorted, 1u), sortWord(sorted, 2u));
    return (ivec3(k) - ivec3(1 << 19)) << 12;
}

// Where the ranks buffer keeps each table (nano_layout.h, SVO_BIND_NANO_RANKS;
// 6 uEntryCount + 2 words). Leaves are laid out in sorted order, tiles left
// out: a leaf's rank counts the leaves before it.
uint lowerRankAt(uint sorted) { return sorted; }
uint upperRankAt(uint sorted) { return uEntryCount + sorted; }
uint lowerFirstEntryAt(uint lower) { return 2u * uEntryCount + lower; }
uint upperFirstLowerAt(uint upper) { return 3u * uEntryCount + 1u + upper; }
uint leafRankAt(uint sorted) { return 4u * uEntryCount + 2u + sorted; }
uint leafEntryAt(uint leaf) { return 5u * uEntryCount + 2u + leaf; }

// A 64-bit byte offset from word a to word b > a, as two words.
uvec2 byteOffset(uint a, uint b)
{
    uint d = b - a;
    return uvec2(d << 2u, d >> 30u);
}
