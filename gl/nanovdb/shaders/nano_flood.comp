#version 450 core
// The signed flood fill of a level set laid out as NanoVDB (Float), one invocation per node of one level, run bottom
// up (leaves, lower nodes, upper nodes): the bits svo::vdb::signedFloodFill gives on the host, as OpenVDB's
// tools::signedFloodFill defines them. In a node, an entry that is not an "end" (a leaf's active voxel, an internal
// node's child) takes the sign of the last end met along x, then y, then z, starting from the first end's; a node
// with none takes the sign of its first value. A child end's sign is its first value's (for the start) or its last
// value's. Magnitudes become the background's. One code path for both cases, so that the lanes of one SIMD vector
// run the same loops (the driver's loop limit, ContextInfo::loopLanes).
layout(local_size_x = 64) in;
#include "nano_common.glsl"

uniform uint uLevel;     // 0 leaves, 1 lower nodes, 2 upper nodes
uniform uint uNodeAt;    // the level's first node's word in the grid
uniform uint uNodeCount; // the level's nodes
uniform uint uOutside;   // |background|'s bits
uniform uint uMinus;     // -|background|'s bits

bool negative(uint bits) { return uintBitsToFloat(bits) < 0.0; }
bool isOn(uint maskAt, uint n) { return ((grid[maskAt + (n >> 5u)] >> (n & 31u)) & 1u) != 0u; }

uint tableAt(uint level) { return level == 1u ? kNanoLowerTable : kNanoUpperTable; }

// The word holding entry n's value: a leaf's voxel, an internal node's tile.
uint valueAt(uint node, uint level, uint n)
{
    return level == 0u ? node + kNanoLeafValues + n : node + tableAt(level) + 2u * n;
}

// The first word of the child of entry n of an internal node: the table's int64 byte offset from the node
// (children lie after their parents, and a grid within 16 GiB keeps word offsets in 32 bits).
uint childAt(uint node, uint level, uint n)
{
    uint entry = node + tableAt(level) + 2u * n;
    return node + ((grid[entry + 1u] << 30u) | (grid[entry] >> 2u));
}

// The first (or last) value of the child of entry n of an internal node: a leaf's voxel, or a lower node's first
// (last) entry, its leaf's first (last) voxel or its tile.
uint childEnd(uint node, uint level, uint n, bool last)
{
    uint child = childAt(node, level, n);
    uint voxel = last ? 511u : 0u;
    if (level == 1u) return grid[child + kNanoLeafValues + voxel];
    uint m = last ? 4095u : 0u;
    if (isOn(child + kNanoLowerChildMask, m)) return grid[childAt(child, 1u, m) + kNanoLeafValues + voxel];
    return grid[child + kNanoLowerTable + 2u * m];
}

// Whether end entry n is inside: a voxel's own value, a child's first (start) or last value.
bool endInside(uint node, uint level, uint n, bool start)
{
    return negative(level == 0u ? grid[node + kNanoLeafValues + n] : childEnd(node, level, n, !start));
}

void main()
{
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x;
    if (i >= uNodeCount) return;
    uint level = uLevel, log2Dim = 3u + level, size = 1u << (3u * log2Dim);
    uint node = uNodeAt + i * (level == 0u ? kNanoLeafWordsValue : level == 1u ? kNanoLowerWords : kNanoUpperWords);
    uint mask = node + (level == 0u ? kNanoLeafValueMask : level == 1u ? kNanoLowerChildMask : kNanoUpperChildMask);
    uint first = size;
    for (uint w = 0u; w < size / 32u && first == size; ++w)
        if (grid[mask + w] != 0u) first = 32u * w + uint(findLSB(grid[mask + w]));
    bool x = first < size ? endInside(node, level, first, true) : negative(grid[valueAt(node, level, 0u)]);
    uint side = 1u << log2Dim;
    for (uint a = 0u; a < side; ++a) {
        uint i00 = a << (2u * log2Dim);
        if (isOn(mask, i00)) x = endInside(node, level, i00, false);
        bool y = x;
        for (uint b = 0u; b < side; ++b) {
            uint ij0 = i00 + (b << log2Dim);
            if (isOn(mask, ij0)) y = endInside(node, level, ij0, false);
            bool z = y;
            for (uint c = 0u; c < side; ++c) {
                uint ijk = ij0 + c;
                if (isOn(mask, ijk)) z = endInside(node, level, ijk, false);
                else grid[valueAt(node, level, ijk)] = z ? uMinus : uOutside;
            }
        }
    }
}
