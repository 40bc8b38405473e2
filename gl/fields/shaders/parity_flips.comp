#version 450 core
// Inside/outside by parity along z columns: every triangle marks where it
// crosses each voxel column (i, j); a voxel centre is inside when an odd
// number of crossings lie below it. The host sums the marks up each column
// (core/parity_scan.h). Which columns a triangle crosses, and where, is column_crossing.glsl's
// (core's, one text with the CPU backend's core/src/parity_crossings.cpp),
// ties broken by simulation of simplicity.
layout(local_size_x = 64) in;
#include "field_common.glsl"
#include "field_double.glsl"
#include "column_crossing.glsl"

layout(std430, binding = SVO_BIND_FIELD_FLIPS) restrict buffer Flips { uint flips[]; };
layout(std430, binding = SVO_BIND_FIELD_COUNTERS) restrict buffer Counters { uint missing; };

uniform uint uDimZ; // local voxels along z

// Marks where triangle t crosses one column, if it does.
void columnCrossing(uint t, dvec3 A, dvec3 B, dvec3 C, uvec2 column)
{
    double zc;
    if (!svo_column_crossing(A, B, C, double(column.x), double(column.y), zc)) return;
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
