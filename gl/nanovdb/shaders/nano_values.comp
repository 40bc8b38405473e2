#version 450 core
// Pass 4b, 16 invocations per laid-out leaf (nano_leaves.comp), 32 voxels (Vec3f: 32 values' 96 words) each: Float and Int32
// leaves' values (given; else uActive where active, when set, and the background); Boolean leaves' value bits
// (given values that are not 0, else the active voxels).
layout(local_size_x = 256) in;
#include "nano_common.glsl"

uniform uint uType;       // kNanoType*
uniform uint uLeafAt;     // the first leaf's word in the grid
uniform uint uLeafWords;  // words per leaf
uniform uint uHasValues;  // 1: values[] holds 512 words per leaf
uniform uint uBackground; // the background's bits
uniform uint uHasActive;  // 1 (without values): active voxels hold uActive
uniform uint uActive;     // their value's bits

void main()
{
    uint g = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 256u + gl_GlobalInvocationID.x;
    uint i = g >> 4u, w = g & 15u;
    if (i >= uLeafCount) return;
    uint leaf = inputLeaf(ranks[leafEntryAt(i)]), at = uLeafAt + i * uLeafWords;
    if (uType == kNanoTypeBool) {
        uint bits = masks[leaf * 16u + w];
        if (uHasValues != 0u) {
            bits = 0u;
            for (uint b = 0u; b < 32u; ++b) bits |= values[leaf * 512u + 32u * w + b] != 0u ? 1u << b : 0u;
        }
        grid[at + kNanoLeafBoolValues + w] = bits;
        return;
    }
    // Word k = 16 b + w: the 16 invocations of a leaf read and write 16
    // consecutive words at each step (one run of 64 bytes, not 16 runs 128
    // bytes apart). Vec3f: 3 words a value, no active word (uHasActive 0).
    bool isVec3 = uType == kNanoTypeVec3f;
    uint words = isVec3 ? 1536u : 512u, first = isVec3 ? kNanoLeafValuesVec3f : kNanoLeafValues;
    for (uint b = 0u; b < words / 16u; ++b) {
        uint k = 16u * b + w;
        bool on = uHasActive != 0u && (masks[leaf * 16u + (k >> 5u)] & (1u << (k & 31u))) != 0u;
        grid[at + first + k] = uHasValues != 0u ? values[leaf * words + k] : on ? uActive : uBackground;
    }
}
