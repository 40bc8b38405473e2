#version 450 core
// Unsigned distance, in voxels, from every voxel centre of the band's bricks
// to the closest triangle (band_distance.glsl), on a GPU: every work item is
// one brick of a triangle's box grown by the band (field_common.glsl), taken
// whole by a workgroup. A shader of its own, as small as it can be: on an
// H100 this pass ran 1.7-1.9 times slower inside one shader with the CPU
// rasterizers' paths (bench/results/nvidia-h100/band_ab.md).
layout(local_size_x = 32) in;
#include "band_distance.glsl"

void main()
{
    // A workgroup a brick of a triangle's grown box, a thread a centre of
    // the item's part of the box: a slanted triangle's part of a brick is
    // about 5x5x5 centres, which a thread a column of 8 left mostly idle
    // (32 threads a centre each: 27 % less time on the bunny at 2048³, 42 %
    // on the 1.3 M-triangle icosphere; bench/results/nvidia-h100/nanovdb/
    // shader-ab-2026-12-05). Each centre is tested against the triangle's
    // box and plane grown by the band (svo_slab_of: widened for rounding, so
    // no kept distance changes) before its distance, and its square root is
    // skipped where the square is beyond the band with a margin no rounding
    // closes.
    // A workgroup takes a run of consecutive items, so each item's triangle
    // is found from the one before (a step or two), not by a search of all
    // triangles per item (21 dependent loads a thread on a 1.3 M-triangle mesh).
    uint first, end;
    itemRun(first, end);
    uint t = first < end ? triangleOfItem(first) : 0u;
    for (uint item = first; item < end; ++item) {
        t = triangleOfItemFrom(item, t);
        uvec3 lo, size;
        voxelBoxOfTriangleItem(item, t, lo, size); // one brick's part of the box
        uvec3 b = lo >> kBrickLog2;
        uint brick = lookupBrick(b);
        if (brick == kNoChild) continue; // no voxel of this brick is in the band
        dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
        dvec3 boxLo = min(A, min(B, C)), boxHi = max(A, max(B, C));
        dvec3 brickLo = dvec3(b << kBrickLog2), brickHi = brickLo + 7.0LF;
        dvec3 gap = max(max(boxLo - brickHi, brickLo - boxHi), dvec3(0.0LF));
        double band2 = double(uBand) * double(uBand);
        double keep2 = band2 * (1.0LF + 1e-5LF);
        if (dot(gap, gap) > band2) continue; // the whole brick is beyond the band from the triangle's box
        dvec3 w = dvec3(uBand);
        svo_Slab slab = svo_slab_of(A, B, C, double(uBand));
        if (svo_box_beyond_slab(slab, max(brickLo, boxLo - w), min(brickHi, boxHi + w))) continue;
        uint count = size.x * size.y * size.z;
        for (uint c = gl_LocalInvocationID.x; c < count; c += gl_WorkGroupSize.x) {
            uvec3 v = lo + uvec3(c % size.x, (c / size.x) % size.y, c / (size.x * size.y));
            dvec3 p = dvec3(v);
            dvec3 g = max(max(boxLo - p, p - boxHi), dvec3(0.0LF));
            if (dot(g, g) > band2) continue;
            if (abs(dot(slab.n, p - slab.a)) > slab.limit) continue; // beyond the band of the plane
            uvec3 l = v & 7u;
            uint i = 512u * brick + ((l.x << kKeyLeafXShift) | (l.y << kKeyLeafYShift) | l.z);
            if (knownInBand(i)) continue;
            double d2 = svo_triangle_distance2(p, A, B, C);
            if (d2 > keep2) continue; // beyond the band with a wide margin: no sqrt
            float d = float(sqrt(d2));
            if (d > uBand) continue;
            if (uPass == 0u) atomicMin(distances[i], floatBitsToUint(d));
            else if (distances[i] == floatBitsToUint(d)) atomicMin(closest[i], t);
        }
    }
}
