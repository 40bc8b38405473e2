#version 450 core
// Pass 2, many dispatches: one compare-exchange step (uK, uJ) of a bitonic
// sort of the entries by their four key words, ascending.
layout(local_size_x = 256) in;
#include "nano_common.glsl"

uniform uint uEntries; // a power of two
uniform uint uK;       // the size of the sequences being merged
uniform uint uJ;       // the distance compared

bool keyLess(uint a, uint b)
{
    for (uint w = 0u; w < 4u; ++w) {
        uint x = sortWord(a, w), y = sortWord(b, w);
        if (x != y) return x < y;
    }
    return false;
}

void main()
{
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 256u + gl_GlobalInvocationID.x;
    uint l = i ^ uJ;
    if (i >= uEntries || l <= i) return;
    bool ascending = (i & uK) == 0u;
    if (!(ascending ? keyLess(l, i) : keyLess(i, l))) return; // in order already
    for (uint w = 0u; w < kNanoSortWords; ++w) {
        uint t = sortKeys[i * kNanoSortWords + w];
        sortKeys[i * kNanoSortWords + w] = sortKeys[l * kNanoSortWords + w];
        sortKeys[l * kNanoSortWords + w] = t;
    }
}
