#version 450 core
// Unsigned distance, in voxels, from every voxel centre of the band's bricks
// to the closest triangle (band_distance.glsl), on a GPU: every work item is
// one brick of a triangle's box grown by the band (field_common.glsl), taken
// whole by a workgroup. A shader of its own, as small as it can be: on an
// H100 this pass ran 1.7-1.9 times slower inside one shader with the CPU
// rasterizers' paths (bench/results/nvidia-h100/band_ab.md).
layout(local_size_x = 64) in;
#include "band_distance.glsl"

void main()
{
    // A workgroup a brick of a triangle's grown box, a column of 8 centres a
    // thread: the column first narrowed to the centres within the band of
    // the triangle's box and of its plane (svo_box_run, svo_slab_run: the
    // CPU rasterizers' tests, widened for rounding, so no kept distance
    // changes), then each centre's box test before its distance. Without
    // the narrowing, a slanted triangle's brick computed every centre the
    // box test passed, about three times those within the band.
    // A workgroup takes a run of consecutive items, so each item's triangle
    // is found from the one before (a step or two), not by a search of all
    // triangles per item (21 dependent loads a thread on a 1.3 M-triangle mesh).
    uint x = gl_LocalInvocationID.x >> 3u, y = gl_LocalInvocationID.x & 7u;
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
        if (dot(gap, gap) > band2) continue; // the whole brick is beyond the band from the triangle's box
        // ... or from its plane, over the centres the box test can pass.
        dvec3 w = dvec3(uBand);
        svo_Slab slab = svo_slab_of(A, B, C, double(uBand));
        if (svo_box_beyond_slab(slab, max(brickLo, boxLo - w), min(brickHi, boxHi + w))) continue;
        // The centres of the item's box only (the grown box, cut to the
        // grid and to this brick), as the CPU's field takes them.
        uvec3 c = (b << kBrickLog2) + uvec3(x, y, 0u);
        if (any(lessThan(c.xy, lo.xy)) || any(greaterThanEqual(c.xy, lo.xy + size.xy))) continue;
        double px = double(c.x), py = double(c.y), z0 = double(lo.z), z1 = double(lo.z + size.z - 1u);
        if (!svo_box_run(boxLo, boxHi, px, py, band2, z0, z1) || !svo_slab_run(slab, px, py, z0, z1)) continue;
        for (uint z = uint(z0 - brickLo.z); z <= uint(z1 - brickLo.z); ++z) {
            dvec3 p = brickLo + dvec3(x, y, z);
            dvec3 g = max(max(boxLo - p, p - boxHi), dvec3(0.0LF));
            if (dot(g, g) > band2) continue;
            float d = float(sqrt(svo_triangle_distance2(p, A, B, C)));
            if (d > uBand) continue;
            uint i = 512u * brick + ((x << kKeyLeafXShift) | (y << kKeyLeafYShift) | z);
            if (uPass == 0u) atomicMin(distances[i], floatBitsToUint(d));
            else if (distances[i] == floatBitsToUint(d)) atomicMin(closest[i], t);
        }
    }
}
