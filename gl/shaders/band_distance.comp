#version 450 core
// Unsigned distance, in voxels, from every voxel centre of the band's bricks
// to the closest triangle, in double precision (field_common.glsl has the
// work items). Pass 0 keeps the least distance of each voxel with atomicMin
// on its float bits (non-negative floats order as their bits do); pass 1,
// when asked for, records the smallest index of the triangles at that
// distance, so the result does not depend on the order of the threads.
layout(local_size_x = 64) in;
#include "field_common.glsl"

layout(std430, binding = SVO_BIND_FIELD_DISTANCES) restrict buffer Distances { uint distances[]; };
layout(std430, binding = SVO_BIND_FIELD_CLOSEST) restrict buffer Closest { uint closest[]; };

uniform uint uPass;
uniform float uBand; // distances beyond it are not kept

// A triangle, with what the distance to it needs of each voxel centre
// computed once: its normal, and per edge the normal of the edge in the
// triangle's plane and the edge's squared length.
struct Triangle {
    dvec3 a, b, c;
    dvec3 n;
    double n2;
    dvec3 nab, nbc, nca; // n x edge: a centre is on the inner side of every edge where each dot is >= 0
};

Triangle triangleOf(dvec3 a, dvec3 b, dvec3 c)
{
    Triangle T;
    T.a = a, T.b = b, T.c = c;
    T.n = cross(b - a, c - a);
    T.n2 = dot(T.n, T.n);
    T.nab = cross(T.n, b - a), T.nbc = cross(T.n, c - b), T.nca = cross(T.n, a - c);
    return T;
}

// Squared distance from p to the segment [a, b]; a point when a == b.
double segmentDistance2(dvec3 p, dvec3 a, dvec3 b)
{
    dvec3 ab = b - a;
    double len2 = dot(ab, ab);
    double t = len2 > 0.0LF ? clamp(dot(p - a, ab) / len2, 0.0LF, 1.0LF) : 0.0LF;
    dvec3 d = p - (a + t * ab);
    return dot(d, d);
}

// Squared distance from p to the closed triangle: the distance to its plane
// where p projects inside it, else the least of the edges'. Needles and
// points are their edges, so nothing degenerate divides by zero.
double triangleDistance2(dvec3 p, Triangle T)
{
    if (T.n2 > 0.0LF && dot(p - T.a, T.nab) >= 0.0LF && dot(p - T.b, T.nbc) >= 0.0LF &&
        dot(p - T.c, T.nca) >= 0.0LF) {
        double h = dot(p - T.a, T.n);
        return h * h / T.n2;
    }
    return min(segmentDistance2(p, T.a, T.b), min(segmentDistance2(p, T.b, T.c), segmentDistance2(p, T.c, T.a)));
}

// The band distances of one column of an item's box to triangle t.
void columnDistances(uint t, Triangle T, dvec3 boxLo, dvec3 boxHi, uvec2 column, uvec3 lo, uvec3 size)
{
    double band2 = double(uBand) * double(uBand);
    // Most centres of the box are beyond the band from the triangle's box:
    // the column's run of centres within it, found from the gap across the
    // column (widened for rounding), then each centre's exact test, which
    // is cheaper than the distance.
    dvec2 gxy = max(max(boxLo.xy - dvec2(column), dvec2(column) - boxHi.xy), dvec2(0.0LF));
    double rest = band2 - dot(gxy, gxy);
    if (rest < 0.0LF) return;
    double r = sqrt(rest) * (1.0LF + 1e-9LF) + 1e-9LF;
    double z0 = max(double(lo.z), ceil(boxLo.z - r)), z1 = min(double(lo.z + size.z - 1u), floor(boxHi.z + r));
    uvec2 l = column & kBrickMask;
    uint leaf = (l.x << kKeyLeafXShift) | (l.y << kKeyLeafYShift);
    uint brickZ = 0xFFFFFFFFu, brick = kNoChild; // the run may cross into the next brick up
    for (double zd = z0; zd <= z1; zd += 1.0LF) {
        uint z = uint(zd);
        dvec3 p = dvec3(column, zd);
        dvec3 g = max(max(boxLo - p, p - boxHi), dvec3(0.0LF));
        if (dot(g, g) > band2) continue;
        if (z >> kBrickLog2 != brickZ) {
            brickZ = z >> kBrickLog2;
            brick = lookupBrick(uvec3(column >> kBrickLog2, brickZ));
        }
        if (brick == kNoChild) continue; // no voxel of this brick is in the band
        float d = float(sqrt(triangleDistance2(p, T)));
        if (d > uBand) continue;
        uint i = 512u * brick + leaf + (z & kBrickMask);
        if (uPass == 0u) atomicMin(distances[i], floatBitsToUint(d));
        else if (distances[i] == floatBitsToUint(d)) atomicMin(closest[i], t);
    }
}

void main()
{
    if (uWhole != 0u) { // a thread a one-item triangle: all its columns
        for (uint k = uItemFirst + threadIndex(); k < uItems; k += threadCount()) {
            uint t;
            uvec3 lo, size;
            wholeBox(k, t, lo, size);
            dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
            Triangle T = triangleOf(A, B, C);
            dvec3 boxLo = min(A, min(B, C)), boxHi = max(A, max(B, C));
            for (uint y = 0u; y < size.y; ++y)
                for (uint x = 0u; x < size.x; ++x)
                    columnDistances(t, T, boxLo, boxHi, lo.xy + uvec2(x, y), lo, size);
        }
        return;
    }
    // One workgroup an item, a column a thread.
    for (uint item = uItemFirst + workgroupIndex(); item < uItems; item += workgroupCount()) {
        uint t;
        uvec3 lo, size;
        voxelBoxOfItem(item, t, lo, size); // at most 8 x 8 x 8
        if (gl_LocalInvocationID.x >= size.x * size.y) continue;
        dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
        columnDistances(t, triangleOf(A, B, C), min(A, min(B, C)), max(A, max(B, C)),
                        lo.xy + uvec2(gl_LocalInvocationID.x % size.x, gl_LocalInvocationID.x / size.x), lo, size);
    }
}
