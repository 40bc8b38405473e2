// What the distance and sign passes share (band_distance.comp,
// parity_flips.comp): the mesh in local double coordinates, the work items,
// and the brick table (gpu_layout.h has the layouts).
//
// Work items. For every triangle the host gives a box of bricks (3D for
// distances: the triangle's box grown by the band; 2D for signs: its columns)
// and the number of the triangle's first item, an exclusive prefix sum over
// the boxes' sizes. Item i is one brick of one box; one workgroup of 64
// threads takes it, so a large triangle spreads over many workgroups.
// Workgroups loop over the items.
#include "gpu_layout.h"

layout(std430, binding = SVO_BIND_FIELD_POSITIONS) readonly restrict buffer Positions { double positions[]; };
layout(std430, binding = SVO_BIND_FIELD_INDICES) readonly restrict buffer Indices { uint indices[]; };
layout(std430, binding = SVO_BIND_FIELD_ITEMS) readonly restrict buffer Items { uint items[]; };
layout(std430, binding = SVO_BIND_FIELD_TABLE) readonly restrict buffer Table { uint table[]; };

uniform uint uTriangles; // triangles, and so entries of items[] less one
uniform uint uItemFirst; // this dispatch's items: [uItemFirst, uItems)
uniform uint uItems;     // one past this dispatch's last item
uniform uint uTableMask; // table slots - 1 (a power of two less one)

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

// The brick (brick coordinates) that item i stands for, and its triangle.
uvec3 brickOfItem(uint i, out uint t)
{
    t = triangleOfItem(i);
    uint base = kItemWords * t;
    uint local = i - items[base];
    uvec3 origin = uvec3(items[base + 1u], items[base + 2u], items[base + 3u]);
    uvec3 size = uvec3(items[base + 4u], items[base + 5u], items[base + 6u]);
    uvec3 b = uvec3(local % size.x, (local / size.x) % size.y, local / (size.x * size.y));
    return origin + b;
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

uint workgroupIndex() { return gl_WorkGroupID.x + gl_NumWorkGroups.x * gl_WorkGroupID.y; }
uint workgroupCount() { return gl_NumWorkGroups.x * gl_NumWorkGroups.y; }
