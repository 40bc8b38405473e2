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

void main()
{
    uint x = gl_LocalInvocationID.x >> 3u, y = gl_LocalInvocationID.x & 7u;
    for (uint item = uItemFirst + workgroupIndex(); item < uItems; item += workgroupCount()) {
        uint t;
        uvec3 b = brickOfItem(item, t);
        uint brick = lookupBrick(b);
        if (brick == kNoChild) continue; // no voxel of this brick is in the band
        dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
        // The whole brick beyond the band from the triangle's box: skip it.
        dvec3 lo = dvec3(b << kBrickLog2), hi = lo + 7.0LF;
        dvec3 boxLo = min(A, min(B, C)), boxHi = max(A, max(B, C));
        dvec3 gap = max(max(boxLo - hi, lo - boxHi), dvec3(0.0LF));
        double band2 = double(uBand) * double(uBand);
        if (dot(gap, gap) > band2) continue;
        for (uint z = 0u; z < 8u; ++z) {
            dvec3 p = lo + dvec3(x, y, z);
            // Most centres of a brick are beyond the band from the box of a
            // small triangle: that test is cheaper than the distance.
            dvec3 g = max(max(boxLo - p, p - boxHi), dvec3(0.0LF));
            if (dot(g, g) > band2) continue;
            float d = float(sqrt(triangleDistance2(p, A, B, C)));
            if (d > uBand) continue;
            uint i = 512u * brick + ((x << kKeyLeafXShift) | (y << kKeyLeafYShift) | z);
            if (uPass == 0u) atomicMin(distances[i], floatBitsToUint(d));
            else if (distances[i] == floatBitsToUint(d)) atomicMin(closest[i], t);
        }
    }
}
