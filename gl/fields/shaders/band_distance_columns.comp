#version 450 core
// Unsigned distance, in voxels, from every voxel centre of the band's bricks
// to the closest triangle (band_distance.glsl), on a CPU rasterizer, whose
// SIMD lanes are the threads of a workgroup: a triangle whose box grown by
// the band fits a brick takes one thread (uWhole; its list after the items'
// records), so eight small triangles fill eight lanes; a larger one takes an
// item per brick it spans. A workgroup is 8 threads, llvmpipe's one vector
// (it runs a workgroup's vectors one after another, each through the whole
// shader, so with 64 threads every item was found and read 8 times), and
// takes a run of items, a thread a row of the columns of each.
layout(local_size_x = 8) in;
#include "band_distance.glsl"

// The band distances of one column of an item's box to triangle t, at the
// centres from zLo to zHi (at most 8, so in at most two bricks). With
// `run`, first narrowed to the run of centres whose distance to the
// triangle's box is within the band, found from the gap across the column
// (widened for rounding): what a thread that takes all the columns of a
// small triangle saves. Then to the run within the band of the triangle's
// plane, which a large slanted triangle's box holds a small part of. Then
// each centre's exact test against the box, which is cheaper than the
// distance.
// The triangle, its slab and its box come prepared, once for all its
// columns, and so do the brick table's answers: the column's brick at brick
// height `lowZ` and the one above it.
void columnDistances(uint t, svo_Triangle tri, svo_Slab slab, dvec3 boxLo, dvec3 boxHi, uvec2 column, uint zLo,
                     uint zHi, bool run, uint lowZ, uint low, uint high)
{
    double band2 = double(uBand) * double(uBand);
    double x = double(column.x), y = double(column.y), z0 = double(zLo), z1 = double(zHi);
    if (run && !svo_box_run(boxLo, boxHi, x, y, band2, z0, z1)) return;
    if (!svo_slab_run(slab, x, y, z0, z1)) return;
    zLo = uint(z0), zHi = uint(z1);
    uvec2 l = column & kBrickMask;
    uint leaf = (l.x << kKeyLeafXShift) | (l.y << kKeyLeafYShift);
    for (uint z = zLo; z <= zHi; ++z) {
        uint brick = z >> kBrickLog2 == lowZ ? low : high;
        if (brick == kNoChild) continue; // no voxel of this brick is in the band
        dvec3 p = dvec3(column, z);
        dvec3 g = max(max(boxLo - p, p - boxHi), dvec3(0.0LF));
        if (dot(g, g) > band2) continue;
        uint i = 512u * brick + leaf + (z & kBrickMask);
        if (knownInBand(i)) continue;
        float d = float(sqrt(svo_prepared_distance2(p, tri)));
        if (d > uBand) continue;
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
            svo_Triangle tri = svo_triangle_of(A, B, C);
            svo_Slab slab = svo_slab_of(A, B, C, double(uBand));
            dvec3 boxLo = min(A, min(B, C)), boxHi = max(A, max(B, C));
            // The box spans at most 2 bricks a side: their table entries,
            // looked up once instead of twice a column.
            uvec3 b0 = lo >> kBrickLog2, b1 = (lo + size - 1u) >> kBrickLog2;
            uint bricks[8];
            for (uint k = 0u; k < 8u; ++k) {
                uvec3 b = b0 + uvec3(k & 1u, (k >> 1u) & 1u, k >> 2u);
                bricks[k] = all(lessThanEqual(b, b1)) ? lookupBrick(b) : kNoChild;
            }
            for (uint y = 0u; y < size.y; ++y)
                for (uint x = 0u; x < size.x; ++x) {
                    uvec2 column = lo.xy + uvec2(x, y);
                    uvec2 o = (column >> kBrickLog2) - b0.xy;
                    uint k = o.x + 2u * o.y;
                    columnDistances(t, tri, slab, boxLo, boxHi, column, lo.z, lo.z + size.z - 1u, true, b0.z,
                                    bricks[k], bricks[k + 4u]);
                }
        }
        return;
    }
    // One workgroup (one SIMD vector) a run of items, one after another; a
    // thread a row of an item's columns.
    uint first, end;
    itemRun(first, end);
    uint t = first < end ? triangleOfItem(first) : 0u;
    for (uint item = first; item < end; ++item) {
        t = triangleOfItemFrom(item, t);
        uvec3 lo, size;
        voxelBoxOfTriangleItem(item, t, lo, size); // at most 8 x 8 x 8
        uint x = gl_LocalInvocationID.x;
        if (x >= size.x) continue;
        dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
        svo_Triangle tri = svo_triangle_of(A, B, C);
        svo_Slab slab = svo_slab_of(A, B, C, double(uBand));
        dvec3 boxLo = min(A, min(B, C)), boxHi = max(A, max(B, C));
        uint brick = lookupBrick(lo >> kBrickLog2); // an item lies in one brick
        if (brick == kNoChild) continue;
        for (uint y = 0u; y < size.y; ++y)
            columnDistances(t, tri, slab, boxLo, boxHi, lo.xy + uvec2(x, y), lo.z, lo.z + size.z - 1u, false,
                            lo.z >> kBrickLog2, brick, kNoChild);
    }
}
