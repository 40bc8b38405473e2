// What the two band distance passes share (band_distance.comp for GPUs,
// band_distance_columns.comp for CPU rasterizers): the output, and the
// distance from a voxel centre to a triangle in double precision. Pass 0
// keeps the least distance of each voxel with atomicMin on its float bits
// (non-negative floats order as their bits do); pass 1, when asked for,
// records the smallest index of the triangles at that distance, so the
// result does not depend on the order of the threads.
#include "field_common.glsl"

layout(std430, binding = SVO_BIND_FIELD_DISTANCES) restrict buffer Distances { uint distances[]; };
layout(std430, binding = SVO_BIND_FIELD_CLOSEST) restrict buffer Closest { uint closest[]; };

uniform uint uPass;
uniform float uBand; // distances beyond it are not kept

// Squared distance from p to the segment [a, b]; a point when a == b.
double segmentDistance2(dvec3 p, dvec3 a, dvec3 b)
{
    dvec3 ab = b - a;
    double len2 = dot(ab, ab);
    double t = len2 > 0.0LF ? clamp(dot(p - a, ab) / len2, 0.0LF, 1.0LF) : 0.0LF;
    dvec3 d = p - (a + t * ab);
    return dot(d, d);
}

// Squared distance from p to the closed triangle abc: the distance to its
// plane where p projects inside it, else the least of the edges'. Needles and
// points are their edges, so nothing degenerate divides by zero.
double triangleDistance2(dvec3 p, dvec3 a, dvec3 b, dvec3 c)
{
    dvec3 n = cross(b - a, c - a);
    double n2 = dot(n, n);
    if (n2 > 0.0LF && dot(cross(b - a, p - a), n) >= 0.0LF && dot(cross(c - b, p - b), n) >= 0.0LF &&
        dot(cross(a - c, p - c), n) >= 0.0LF) {
        double h = dot(p - a, n);
        return h * h / n2;
    }
    return min(segmentDistance2(p, a, b), min(segmentDistance2(p, b, c), segmentDistance2(p, c, a)));
}

// The same, for a thread that queries one triangle at many centres (the CPU
// rasterizers' cut): what does not depend on p computed once, the rest by
// the same operations in the same order, so both cuts' distances are the
// same bits. (On an H100, holding these values across the loop made the
// GPUs' cut 1.5-2 times slower: bench/results/nvidia-h100/level_set_peers.md.)
struct Triangle {
    dvec3 a, b, c, ab, bc, ca, n;
    double n2, lab, lbc, lca;
};

Triangle triangleOf(dvec3 a, dvec3 b, dvec3 c)
{
    Triangle t;
    t.a = a, t.b = b, t.c = c;
    t.ab = b - a, t.bc = c - b, t.ca = a - c;
    t.n = cross(t.ab, c - a);
    t.n2 = dot(t.n, t.n);
    t.lab = dot(t.ab, t.ab), t.lbc = dot(t.bc, t.bc), t.lca = dot(t.ca, t.ca);
    return t;
}

double segmentDistance2(dvec3 p, dvec3 a, dvec3 ab, double len2)
{
    double t = len2 > 0.0LF ? clamp(dot(p - a, ab) / len2, 0.0LF, 1.0LF) : 0.0LF;
    dvec3 d = p - (a + t * ab);
    return dot(d, d);
}

double triangleDistance2(dvec3 p, Triangle t)
{
    if (t.n2 > 0.0LF && dot(cross(t.ab, p - t.a), t.n) >= 0.0LF && dot(cross(t.bc, p - t.b), t.n) >= 0.0LF &&
        dot(cross(t.ca, p - t.c), t.n) >= 0.0LF) {
        double h = dot(p - t.a, t.n);
        return h * h / t.n2;
    }
    return min(segmentDistance2(p, t.a, t.ab, t.lab),
               min(segmentDistance2(p, t.b, t.bc, t.lbc), segmentDistance2(p, t.c, t.ca, t.lca)));
}

// The plane slab of triangle abc: a centre farther than the band from the
// triangle's plane is farther from the triangle, so work can skip it. Its
// unnormalized normal n and the band measured along n, widened by 1e-6
// (above float's half ulp, so no centre whose rounded distance could be
// kept is skipped) and by 1e-10 |b - a| |c - a| (|b - a| + |c - a| + band),
// far above the rounding of n (each component off by up to about
// 2^-52 |b - a| |c - a|) times any distance from a within the grown box: a
// needle whose corners lie on a line has a normal of pure rounding noise,
// and its slab then holds the whole box.
struct Slab {
    dvec3 a, n;
    double limit;
};

Slab slabOf(dvec3 a, dvec3 b, dvec3 c)
{
    Slab s;
    s.a = a;
    s.n = cross(b - a, c - a);
    double e1 = length(b - a), e2 = length(c - a), w = double(uBand);
    s.limit = w * sqrt(dot(s.n, s.n)) * (1.0LF + 1e-6LF) + 1e-10LF * e1 * e2 * (e1 + e2 + w);
    return s;
}

// Whether every point of the box [lo, hi] lies beyond the slab on one side.
bool boxBeyondSlab(Slab s, dvec3 lo, dvec3 hi)
{
    double h = dot(s.n, 0.5LF * (lo + hi) - s.a), r = dot(abs(s.n), 0.5LF * (hi - lo));
    return h - r > s.limit || h + r < -s.limit;
}

// Narrows [zLo, zHi] to the centres of column (x, y) inside the slab;
// false when none is.
bool slabRun(Slab s, uvec2 column, inout uint zLo, inout uint zHi)
{
    double h0 = s.n.x * (double(column.x) - s.a.x) + s.n.y * (double(column.y) - s.a.y) - s.n.z * s.a.z;
    if (s.n.z == 0.0LF) return abs(h0) <= s.limit;
    double z0 = (-s.limit - h0) / s.n.z, z1 = (s.limit - h0) / s.n.z;
    double lo = max(double(zLo), ceil(min(z0, z1) - 1e-6LF)), hi = min(double(zHi), floor(max(z0, z1) + 1e-6LF));
    if (hi < lo) return false;
    zLo = uint(lo), zHi = uint(hi);
    return true;
}
