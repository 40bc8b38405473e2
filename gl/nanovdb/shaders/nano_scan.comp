#version 450 core
// Pass 3, over the sorted entries: which start a new upper or lower node
// and which are leaves; their ranks (exclusive prefix sums of those), each
// node's first child, each leaf's entry, the node counts, and a repeated
// entry (a leaf or tile given twice, or a tile on a leaf) if any. Three
// phases (uPhase), so that every SM takes part: 0 counts each chunk of
// kNanoScanChunk entries' starts, 1 (one work group) sums the chunks'
// counts, 2 ranks each chunk's entries from its chunk's sums. One work
// group walking every entry took 3.6 ms of an H100 at 312,898 leaves
// (bench/results/nvidia-h100/nanovdb/band-2026-12-05/passes).
layout(local_size_x = 256) in;
#include "nano_common.glsl"

layout(std430, binding = SVO_BIND_NANO_SCAN) buffer Chunks { uint chunks[]; };

uniform uint uPhase;

shared uvec3 sums[256];

bool sameWords(uint a, uint b, uint words)
{
    for (uint w = 0u; w < words; ++w)
        if (sortWord(a, w) != sortWord(b, w)) return false;
    return true;
}

bool startsUpper(uint i) { return i == 0u || !sameWords(i, i - 1u, 3u); }
bool startsLower(uint i) { return startsUpper(i) || lowerIndexOf(i) != lowerIndexOf(i - 1u); }

// Entry i's starts: (upper, lower, leaf), 0 past the entries.
uvec3 startsOf(uint i)
{
    if (i >= uEntryCount) return uvec3(0u);
    return uvec3(startsUpper(i) ? 1u : 0u, startsLower(i) ? 1u : 0u, isTile(i) ? 0u : 1u);
}

// The inclusive scan of sums[0, n) in place (Hillis-Steele), n threads of the group.
void scanShared(uint t, uint n)
{
    for (uint offset = 1u; offset < n; offset <<= 1u) {
        uvec3 add = t >= offset && t < n ? sums[t - offset] : uvec3(0u);
        barrier();
        if (t < n) sums[t] += add;
        barrier();
    }
}

void countChunk(uint first)
{
    uint t = gl_LocalInvocationID.x;
    uvec3 own = uvec3(0u);
    for (uint r = 0u; r < kNanoScanChunk / 256u; ++r) {
        uint i = first + 256u * r + t;
        own += startsOf(i);
        if (i < uEntryCount && i > 0u && sameWords(i, i - 1u, 4u))
            atomicMax(counters[kNanoCountRepeated], inputLeaf(i) + 1u);
    }
    sums[t] = own;
    barrier();
    scanShared(t, 256u);
    if (t == 255u) {
        uint chunk = first / kNanoScanChunk;
        chunks[3u * chunk] = sums[255].x;
        chunks[3u * chunk + 1u] = sums[255].y;
        chunks[3u * chunk + 2u] = sums[255].z;
    }
}

// One group: the chunks' counts turned into exclusive sums, 256 at a time,
// then the node counts and the tables' closing entries.
void sumChunks()
{
    uint t = gl_LocalInvocationID.x;
    uint n = (uEntryCount + kNanoScanChunk - 1u) / kNanoScanChunk;
    uvec3 carry = uvec3(0u);
    for (uint base = 0u; base < n; base += 256u) {
        uint c = base + t;
        uvec3 own = c < n ? uvec3(chunks[3u * c], chunks[3u * c + 1u], chunks[3u * c + 2u]) : uvec3(0u);
        sums[t] = own;
        barrier();
        scanShared(t, 256u);
        if (c < n) {
            uvec3 before = carry + sums[t] - own;
            chunks[3u * c] = before.x;
            chunks[3u * c + 1u] = before.y;
            chunks[3u * c + 2u] = before.z;
        }
        carry += sums[255];
        barrier(); // sums is refilled
    }
    if (t != 0u) return;
    counters[kNanoCountUpper] = carry.x;
    counters[kNanoCountLower] = carry.y;
    ranks[lowerFirstEntryAt(carry.y)] = uEntryCount;
    ranks[upperFirstLowerAt(carry.x)] = carry.y;
}

void rankChunk(uint first)
{
    uint t = gl_LocalInvocationID.x;
    uint chunk = first / kNanoScanChunk;
    uvec3 carry = uvec3(chunks[3u * chunk], chunks[3u * chunk + 1u], chunks[3u * chunk + 2u]);
    for (uint r = 0u; r < kNanoScanChunk / 256u; ++r) {
        uint i = first + 256u * r + t;
        uvec3 own = startsOf(i);
        sums[t] = own;
        barrier();
        scanShared(t, 256u);
        uvec3 before = carry + sums[t] - own; // starts before entry i
        if (i < uEntryCount) {
            if (own.x != 0u) ranks[upperFirstLowerAt(before.x)] = before.y;
            if (own.y != 0u) ranks[lowerFirstEntryAt(before.y)] = i;
            ranks[lowerRankAt(i)] = before.y + own.y - 1u;
            ranks[upperRankAt(i)] = before.x + own.x - 1u;
            if (own.z != 0u) {
                ranks[leafRankAt(i)] = before.z;
                ranks[leafEntryAt(before.z)] = i;
            }
        }
        carry += sums[255];
        barrier(); // sums is refilled
    }
}

void main()
{
    if (uPhase == 1u) {
        sumChunks();
        return;
    }
    uint first = groupIndex() * kNanoScanChunk;
    if (first >= uEntryCount) return; // the same for the whole group
    if (uPhase == 0u) countChunk(first);
    else rankChunk(first);
}
