// What the distance and sign passes share (band_distance.comp,
// parity_flips.comp): the mesh in local double coordinates, the work items,
// and the brick table (gpu_layout.h has the layouts).
//
// Work items. For every triangle the host gives a box of voxels (3D for
// distances: the triangle's box grown by the band; 2D for signs: its columns)
// and the number of the triangle's first item, an exclusive prefix sum over
// the items per box. A box no wider than a brick is one item; a larger one
// is an item per brick (brick column) it spans, so a large triangle spreads
// over many workgroups while a small one costs one item, not one per brick
// it touches (on a CPU rasterizer, items cost). One workgroup of 64 threads
// takes an item, a column a thread; workgroups loop over the items. The
// crossing pass, and the distance pass on CPU rasterizers
// (band_distance_columns.comp), list the one-item triangles apart (uWhole)
// and give each a thread, so a CPU rasterizer's SIMD lanes take eight of
// them at once instead of the columns of one. The distance pass on GPUs
// (band_distance.comp) cuts every box into bricks.
#include "gpu_layout.h"
#include "field_layout.h"

layout(std430, binding = SVO_BIND_FIELD_POSITIONS) readonly restrict buffer Positions { double positions[]; };
layout(std430, binding = SVO_BIND_FIELD_INDICES) readonly restrict buffer Indices { uint indices[]; };
layout(std430, binding = SVO_BIND_FIELD_ITEMS) readonly restrict buffer Items { uint items[]; };
layout(std430, binding = SVO_BIND_FIELD_TABLE) readonly restrict buffer Table { uint table[]; };

uniform uint uTriangles; // triangles, and so entries of items[] less one
uniform uint uItemFirst; // this dispatch's items: [uItemFirst, uItems)
uniform uint uItems;     // one past this dispatch's last item
uniform uint uTableMask; // table slots - 1 (a power of two less one)
uniform uint uWhole;      // 1: a thread a one-item triangle of the list at uWholeStart; 0: a workgroup an item
uniform uint uWholeStart; // where the list of one-item triangles starts in items[]

uint workgroupIndex() { return gl_WorkGroupID.x + gl_NumWorkGroups.x * gl_WorkGroupID.y; }
uint workgroupCount() { return gl_NumWorkGroups.x * gl_NumWorkGroups.y; }
uint threadIndex() { return gl_WorkGroupSize.x * workgroupIndex() + gl_LocalInvocationID.x; }
uint threadCount() { return gl_WorkGroupSize.x * workgroupCount(); }

dvec3 position(uint i) { return dvec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]); }

// The triangle whose items hold item i: the last t with first(t) <= i.
uint triangleOfItem(uint i)
{
    uint lo = 0u, hi = uTriangles; // first(lo) <= i < first(hi)
    while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1u;
        if (items[kItemWords * mid] <= i) lo = mid;
        else hi = mid;
    }
    return lo;
}

// The same when the triangle of an earlier item was `from`: a gallop from
// it, then a binary search, so consecutive items cost a step or two, not a
// search of all triangles (on a CPU rasterizer, whose lanes load one by one,
// that search was most of a pass).
uint triangleOfItemFrom(uint i, uint from)
{
    uint lo = from, hi = from + 1u, step = 1u; // first(lo) <= i
    while (hi < uTriangles && items[kItemWords * hi] <= i) {
        lo = hi;
        step <<= 1u;
        hi = uTriangles - lo > step ? lo + step : uTriangles;
    }
    while (hi - lo > 1u) { // first(lo) <= i < first(hi)
        uint mid = (lo + hi) >> 1u;
        if (items[kItemWords * mid] <= i) lo = mid;
        else hi = mid;
    }
    return lo;
}

// The voxel box that item i of triangle t stands for: the triangle's
// whole box, or the part of it in one brick (for columns: one brick column);
// at most 8 voxels along each axis.
void voxelBoxOfTriangleItem(uint i, uint t, out uvec3 lo, out uvec3 size)
{
    uint base = kItemWords * t;
    lo = uvec3(items[base + 1u], items[base + 2u], items[base + 3u]);
    size = uvec3(items[base + 4u], items[base + 5u], items[base + 6u]);
    if (items[base + 7u] != 0u) return;
    uint local = i - items[base];
    uvec3 b0 = lo >> kBrickLog2, nb = ((lo + size - 1u) >> kBrickLog2) - b0 + 1u;
    uvec3 b = b0 + uvec3(local % nb.x, (local / nb.x) % nb.y, local / (nb.x * nb.y));
    uvec3 hi = min(lo + size, (b + 1u) << kBrickLog2);
    lo = max(lo, b << kBrickLog2);
    size = hi - lo;
}

// The voxel box that item i stands for, and its triangle.
void voxelBoxOfItem(uint i, out uint t, out uvec3 lo, out uvec3 size)
{
    t = triangleOfItem(i);
    voxelBoxOfTriangleItem(i, t, lo, size);
}

// A CPU rasterizer's workgroup takes a run of consecutive items of this
// dispatch, [first, end), so that each item's triangle is found from the
// one before (triangleOfItemFrom).
void itemRun(out uint first, out uint end)
{
    uint per = (uItems - uItemFirst + workgroupCount() - 1u) / workgroupCount();
    first = min(uItemFirst + workgroupIndex() * per, uItems);
    end = min(first + per, uItems);
}

// The box of the k-th one-item triangle (uWhole), and the triangle.
void wholeBox(uint k, out uint t, out uvec3 lo, out uvec3 size)
{
    t = items[uWholeStart + k];
    uint base = kItemWords * t;
    lo = uvec3(items[base + 1u], items[base + 2u], items[base + 3u]);
    size = uvec3(items[base + 4u], items[base + 5u], items[base + 6u]);
}

// The brick's index in the field buffers, or kNoChild when it has none.
uint lookupBrick(uvec3 b)
{
    uint slot = SVO_BRICK_HASH(b.x, b.y, b.z) & uTableMask;
    for (;;) {
        uint w = kTableWords * slot;
        uint index = table[w + 3u];
        if (index == kNoChild) return kNoChild;
        if (table[w] == b.x && table[w + 1u] == b.y && table[w + 2u] == b.z) return index;
        slot = (slot + 1u) & uTableMask;
    }
}
