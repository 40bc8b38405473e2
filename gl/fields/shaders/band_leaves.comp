#version 450 core
// A field's band as NanoVDB leaves on the device, in place of the packing
// for the readback (band_compact.comp): every brick with an active voxel
// takes a leaf (a counter's slot, so in no fixed order: the NanoVDB builder
// sorts them) with its origin, its mask and 512 values, as
// svo::vdb::levelSetNanoGrids writes them on the host: a voxel is active when
// its distance is less than uBands.x (outside) or uBands.y (inside); its
// value is the distance in world units, float(double(d) * scale) exactly,
// where active, the background elsewhere, negated (the sign bit flipped)
// where the voxel is inside; and, when computed, the closest triangle where
// active, -1 elsewhere. Inside voxels come from the host (uSigned: the
// parity scan's, or winding numbers'; none for an unsigned field). With
// winding numbers a brick with inside voxels and none active takes a leaf
// too, in a second dispatch (uInsideOnly), so that those leaves follow
// every leaf with an active voxel (the closest triangles' grid takes only
// the first ones), as levelSetNanoGrids keeps them.
// One workgroup per slot of the brick table (empty slots are skipped); thread
// t holds voxels 8t .. 8t+7 (x = t >> 3, y = t & 7, z = 0..7), the byte 8y of
// the brick's 64-bit mask word x.
layout(local_size_x = 64) in;
#include "gpu_layout.h"
#include "field_layout.h"

layout(std430, binding = SVO_BIND_FIELD_TABLE) readonly restrict buffer Table { uint table[]; };
layout(std430, binding = SVO_BIND_FIELD_DISTANCES) readonly restrict buffer Distances { float distances[]; };
layout(std430, binding = SVO_BIND_FIELD_CLOSEST) readonly restrict buffer Closest { uint closest[]; };
layout(std430, binding = SVO_BIND_FIELD_COUNTERS) restrict buffer Counters { uint counters[]; };
layout(std430, binding = SVO_BIND_LEAVES_ORIGINS) writeonly restrict buffer Origins { int origins[]; };
layout(std430, binding = SVO_BIND_LEAVES_MASKS) writeonly restrict buffer Masks { uint masks[]; };
layout(std430, binding = SVO_BIND_LEAVES_VALUES) writeonly restrict buffer Values { uint values[]; };
layout(std430, binding = SVO_BIND_LEAVES_CLOSEST) writeonly restrict buffer LeafClosest { uint leafClosest[]; };
layout(std430, binding = SVO_BIND_LEAVES_INSIDE) readonly restrict buffer Inside { uint inside[]; };

uniform uint uSlotFirst; // this dispatch's table slots: [uSlotFirst, uSlots)
uniform uint uSlots;
uniform vec2 uBands;      // a voxel is active when its distance is less: x outside, y inside
uniform uint uScale[2];   // the voxel size, a double's two words (low, high)
uniform uint uBackground; // float bits of the background
uniform ivec3 uAnchor;    // index coordinates of the field grid's local origin
uniform uint uClosest;    // 1: closest triangles were computed
uniform uint uSigned;     // 1: `inside` holds the inside voxels of each brick
uniform uint uInsideOnly; // 1: only bricks with inside voxels and none active take leaves
uniform uint uValues;     // 0: a band's topology only, no values written

shared uint sMask[16];
shared uint sLeaf;

void main()
{
    uint t = gl_LocalInvocationID.x;
    double scale = packDouble2x32(uvec2(uScale[0], uScale[1]));
    for (uint slot = uSlotFirst + gl_WorkGroupID.x; slot < uSlots; slot += gl_NumWorkGroups.x) {
        uint brick = table[kTableWords * slot + 3u];
        if (brick == kNoChild) continue; // the same for the whole workgroup
        if (t < 16u) sMask[t] = 0u;
        barrier();
        uint first = 512u * brick + 8u * t;
        // Voxels 8t .. 8t+7 are bits 8(t & 3) .. of the brick's 32-bit word t >> 2.
        uint in8 = uSigned != 0u ? (inside[16u * brick + (t >> 2u)] >> (8u * (t & 3u))) & 0xFFu : 0u;
        uint bits = 0u;
        for (uint z = 0u; z < 8u; ++z)
            if (distances[first + z] < ((in8 & (1u << z)) != 0u ? uBands.y : uBands.x)) bits |= 1u << z;
        atomicOr(sMask[2u * (t >> 3u) + ((t & 7u) >> 2u)], bits << (8u * (t & 3u)));
        barrier();
        if (t == 0u) {
            uint any = 0u, anyInside = 0u;
            for (uint i = 0u; i < 16u; ++i) any |= sMask[i];
            if (uInsideOnly != 0u)
                for (uint i = 0u; i < 16u; ++i) anyInside |= inside[16u * brick + i];
            bool takes = uInsideOnly != 0u ? any == 0u && anyInside != 0u : any != 0u;
            sLeaf = takes ? atomicAdd(counters[kLeafCounter], 1u) : kNoChild;
            if (takes && uInsideOnly != 0u) atomicAdd(counters[kInsideLeafCounter], 1u);
        }
        barrier();
        uint leaf = sLeaf;
        if (leaf != kNoChild) {
            if (t < 16u) masks[16u * leaf + t] = sMask[t];
            if (t < 3u) origins[3u * leaf + t] = uAnchor[t] + 8 * int(table[kTableWords * slot + t]);
            uint at = 512u * leaf + 8u * t;
            for (uint z = 0u; z < 8u && uValues != 0u; ++z) {
                bool on = (bits & (1u << z)) != 0u;
                // In double, rounded once to float: the host's float(double(d) * scale).
                precise double world = double(distances[first + z]) * scale;
                uint value = on ? floatBitsToUint(float(world)) : uBackground;
                values[at + z] = (in8 & (1u << z)) != 0u ? value ^ 0x80000000u : value; // the host's -value
                if (uClosest != 0u) leafClosest[at + z] = on ? closest[first + z] : 0xFFFFFFFFu;
            }
        }
        barrier(); // the next slot clears the shared mask
    }
}
