#version 450 core
// Pass 3, one work group: over the sorted entries, which start a new lower
// or upper node and which are leaves; their ranks (exclusive prefix sums of
// those), each node's first child, each leaf's entry, the node counts, and
// a repeated entry (a leaf or tile given twice, or a tile on a leaf) if any.
layout(local_size_x = 1024) in;
#include "nano_common.glsl"

shared uint partialUpper[1024];
shared uint partialLower[1024];
shared uint partialLeaves[1024];

bool sameWords(uint a, uint b, uint words)
{
    for (uint w = 0u; w < words; ++w)
        if (sortWord(a, w) != sortWord(b, w)) return false;
    return true;
}

bool startsUpper(uint i) { return i == 0u || !sameWords(i, i - 1u, 3u); }
bool startsLower(uint i) { return startsUpper(i) || lowerIndexOf(i) != lowerIndexOf(i - 1u); }

// The inclusive scan of the group's partial sums, in place.
void scanGroup(uint t)
{
    for (uint offset = 1u; offset < 1024u; offset <<= 1u) {
        uint u = t >= offset ? partialUpper[t - offset] : 0u;
        uint l = t >= offset ? partialLower[t - offset] : 0u;
        uint f = t >= offset ? partialLeaves[t - offset] : 0u;
        memoryBarrierShared();
        barrier();
        partialUpper[t] += u;
        partialLower[t] += l;
        partialLeaves[t] += f;
        memoryBarrierShared();
        barrier();
    }
}

void main()
{
    uint t = gl_LocalInvocationID.x;
    uint per = (uEntryCount + 1023u) / 1024u;
    uint begin = min(t * per, uEntryCount), end = min(begin + per, uEntryCount);
    uint uppers = 0u, lowers = 0u, leaves = 0u;
    for (uint i = begin; i < end; ++i) {
        if (startsUpper(i)) ++uppers;
        if (startsLower(i)) ++lowers;
        if (!isTile(i)) ++leaves;
        if (i > 0u && sameWords(i, i - 1u, 4u)) atomicMax(counters[kNanoCountRepeated], inputLeaf(i) + 1u);
    }
    partialUpper[t] = uppers;
    partialLower[t] = lowers;
    partialLeaves[t] = leaves;
    memoryBarrierShared();
    barrier();
    scanGroup(t);
    // Before this range:
    uint upper = partialUpper[t] - uppers, lower = partialLower[t] - lowers, leaf = partialLeaves[t] - leaves;
    for (uint i = begin; i < end; ++i) {
        if (startsUpper(i)) {
            ranks[upperFirstLowerAt(upper)] = lower;
            ++upper;
        }
        if (startsLower(i)) {
            ranks[lowerFirstEntryAt(lower)] = i;
            ++lower;
        }
        ranks[lowerRankAt(i)] = lower - 1u;
        ranks[upperRankAt(i)] = upper - 1u;
        if (!isTile(i)) {
            ranks[leafRankAt(i)] = leaf;
            ranks[leafEntryAt(leaf)] = i;
            ++leaf;
        }
    }
    if (t != 1023u) return;
    counters[kNanoCountUpper] = upper;
    counters[kNanoCountLower] = lower;
    ranks[lowerFirstEntryAt(lower)] = uEntryCount;
    ranks[upperFirstLowerAt(upper)] = lower;
}
