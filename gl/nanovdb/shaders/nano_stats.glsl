// nano_stats.glsl: a node's statistics (bounding box of active voxels, the
// minimum and maximum of their values) and their order-keeping merge; the
// kind's value words.
//
// The CPU builder folds values in order, keeping the first of equals
// (`if (v < lo) lo = v`; vectors by squared length, as nanovdb::Extrema).
// merge(a, b), a before b, keeps a unless b is strictly less (more), so a
// tree reduction whose left operand always comes first gives the fold's
// result bit for bit, -0 and +0 included.

uniform uint uType; // kNanoType*

struct NodeStats {
    ivec3 lo, hi;  // empty: lo > hi
    uvec3 mn, mx;  // value bits (scalars in .x), when the box is not empty
};

NodeStats emptyStats() { return NodeStats(ivec3(0x7FFFFFFF), ivec3(-0x7FFFFFFF - 1), uvec3(0u), uvec3(0u)); }
bool hasActive(NodeStats s) { return s.lo.x <= s.hi.x; }
bool hasValues() { return uType == kNanoTypeFloat || uType == kNanoTypeInt32 || uType == kNanoTypeVec3f; }
uint valueWords() { return uType == kNanoTypeVec3f ? 3u : 1u; }

// nanovdb::Vec3f::lengthSqr in float, each product and sum rounded (no fused multiply-add).
float lengthSqr(uvec3 v)
{
    vec3 f = uintBitsToFloat(v);
    precise float xy = f.x * f.x + f.y * f.y;
    precise float xyz = xy + f.z * f.z;
    return xyz;
}

bool valueLess(uvec3 a, uvec3 b)
{
    if (uType == kNanoTypeVec3f) return lengthSqr(a) < lengthSqr(b);
    return uType == kNanoTypeFloat ? uintBitsToFloat(a.x) < uintBitsToFloat(b.x) : int(a.x) < int(b.x);
}

NodeStats merge(NodeStats a, NodeStats b)
{
    if (!hasActive(b)) return a;
    if (!hasActive(a)) return b;
    NodeStats s = NodeStats(min(a.lo, b.lo), max(a.hi, b.hi), a.mn, a.mx);
    if (valueLess(b.mn, a.mn)) s.mn = b.mn;
    if (valueLess(a.mx, b.mx)) s.mx = b.mx;
    return s;
}

NodeStats loadStats(uint node)
{
    uint at = node * kNanoStatWords;
    return NodeStats(ivec3(stats[at], stats[at + 1u], stats[at + 2u]), ivec3(stats[at + 3u], stats[at + 4u], stats[at + 5u]),
                     uvec3(stats[at + 6u], stats[at + 7u], stats[at + 8u]),
                     uvec3(stats[at + 9u], stats[at + 10u], stats[at + 11u]));
}

void storeStats(uint node, NodeStats s)
{
    uint at = node * kNanoStatWords;
    stats[at] = uint(s.lo.x), stats[at + 1u] = uint(s.lo.y), stats[at + 2u] = uint(s.lo.z);
    stats[at + 3u] = uint(s.hi.x), stats[at + 4u] = uint(s.hi.y), stats[at + 5u] = uint(s.hi.z);
    for (uint c = 0u; c < 3u; ++c) stats[at + 6u + c] = s.mn[c], stats[at + 9u + c] = s.mx[c];
}

// A node's minimum and maximum written at word `at` of the grid, a value each.
void writeExtrema(uint at, NodeStats s)
{
    uint n = valueWords();
    for (uint c = 0u; c < n; ++c) grid[at + c] = s.mn[c], grid[at + n + c] = s.mx[c];
}

// The work group's reduction (NANO_GROUP defined by the pass): each
// invocation's stats in shared memory, in order; returns the group's merge.
#ifdef NANO_GROUP
shared NodeStats groupStats[NANO_GROUP];

NodeStats reduceGroup(NodeStats mine)
{
    uint t = gl_LocalInvocationIndex;
    groupStats[t] = mine;
    memoryBarrierShared();
    barrier();
    for (uint s = 1u; s < uint(NANO_GROUP); s <<= 1u) {
        if ((t & (2u * s - 1u)) == 0u) groupStats[t] = merge(groupStats[t], groupStats[t + s]);
        memoryBarrierShared();
        barrier();
    }
    return groupStats[0];
}
#endif
