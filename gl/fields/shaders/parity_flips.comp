#version 450 core
// Inside/outside by parity along z columns: every triangle marks where it
// crosses each voxel column (i, j); a voxel centre is inside when an odd
// number of crossings lie below it. The host sums the marks up each column
// (core/parity_scan.h).
//
// Ties (simulation of simplicity). Each voxel centre is perturbed to
// (i + e^2, j + e^3, k + e) for an infinitesimal e, so no centre lies on a
// face, edge or vertex: in projection the column point misses every edge and
// vertex (edgeSide), and a centre at the crossing's exact height counts as
// above it, since e outweighs the crossing's own shift of order e^2. A column
// over an edge shared by two triangles crosses exactly one of them. Each edge
// function is evaluated with its end points in a fixed order and `precise`,
// so the two triangles of an edge compute the same value and decide alike
// even where double rounding is inexact.
layout(local_size_x = 64) in;
#include "field_common.glsl"

layout(std430, binding = SVO_BIND_FIELD_FLIPS) restrict buffer Flips { uint flips[]; };
layout(std430, binding = SVO_BIND_FIELD_COUNTERS) restrict buffer Counters { uint missing; };

uniform uint uDimZ; // local voxels along z

// Side of the perturbed column point q + (e^2, e^3) of the directed edge p0 -> p1
// (+1 left, -1 right; 0 only for an edge of zero length in projection).
int edgeSide(dvec2 p0, dvec2 p1, dvec2 q)
{
    bool swapped = p0.x > p1.x || (p0.x == p1.x && p0.y > p1.y);
    dvec2 a = swapped ? p1 : p0, b = swapped ? p0 : p1;
    precise double e = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
    int s = e > 0.0LF ? 1 : e < 0.0LF ? -1 : 0;
    if (s == 0) s = a.y > b.y ? 1 : a.y < b.y ? -1 : b.x > a.x ? 1 : b.x < a.x ? -1 : 0; // the e^2, then e^3 term
    return swapped ? -s : s;
}

// Marks where triangle t crosses one column, if it does.
void columnCrossing(uint t, dvec3 A, dvec3 B, dvec3 C, uvec2 column)
{
    dvec2 q = dvec2(column);
    int sa = edgeSide(B.xy, C.xy, q), sb = edgeSide(C.xy, A.xy, q), sc = edgeSide(A.xy, B.xy, q);
    if (sa == 0 || sa != sb || sb != sc) return; // the column misses the triangle
    // Where it crosses: barycentric weights from the same edge functions.
    // `precise`: a driver that fuses multiply-adds (NVIDIA's does) would move
    // a crossing within rounding of a centre to the other side of it, and
    // the CPU path (core/parity_crossings.cpp), which rounds each operation,
    // would no longer give the same signs.
    precise double wa = (C.x - B.x) * (q.y - B.y) - (C.y - B.y) * (q.x - B.x);
    precise double wb = (A.x - C.x) * (q.y - C.y) - (A.y - C.y) * (q.x - C.x);
    precise double wc = (B.x - A.x) * (q.y - A.y) - (B.y - A.y) * (q.x - A.x);
    precise double sum = wa + wb + wc;
    if (sum == 0.0LF) return; // zero area in projection after rounding: no crossing to place
    precise double zc = (wa * A.z + wb * B.z + wc * C.z) / sum;
    double k = ceil(zc); // the first centre above the crossing (a centre on it counts as above)
    if (k >= double(uDimZ)) return; // nothing above it in the grid
    uint kz = uint(max(k, 0.0LF));
    uint brick = lookupBrick(uvec3(column >> kBrickLog2, kz >> kBrickLog2));
    if (brick == kNoChild) {
        atomicAdd(missing, 1u);
        return;
    }
    uvec2 l = column & kBrickMask;
    uint bit = (l.x << kKeyLeafXShift) | (l.y << kKeyLeafYShift) | (kz & kBrickMask);
    atomicXor(flips[kBrickWords * brick + (bit >> 5u)], 1u << (bit & 31u));
}

void main()
{
    if (uWhole != 0u) { // a thread a one-item triangle: all its columns
        for (uint k = uItemFirst + threadIndex(); k < uItems; k += threadCount()) {
            uint t;
            uvec3 lo, size;
            wholeBox(k, t, lo, size);
            dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
            for (uint y = 0u; y < size.y; ++y)
                for (uint x = 0u; x < size.x; ++x) columnCrossing(t, A, B, C, lo.xy + uvec2(x, y));
        }
        return;
    }
    // One workgroup an item, a column a thread.
    for (uint item = uItemFirst + workgroupIndex(); item < uItems; item += workgroupCount()) {
        uint t;
        uvec3 lo, size;
        voxelBoxOfItem(item, t, lo, size); // at most 64 columns (size.z is 1)
        if (gl_LocalInvocationID.x >= size.x * size.y) continue;
        dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
        columnCrossing(t, A, B, C, lo.xy + uvec2(gl_LocalInvocationID.x % size.x, gl_LocalInvocationID.x / size.x));
    }
}
