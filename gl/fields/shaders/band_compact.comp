#version 450 core
// Packs the band for the readback: per brick, the mask of the voxels nearer
// than uBand and their distances (and closest triangles) in bit order, at an
// offset taken from a counter. Only these come back to the host, a fraction
// of the 512 floats per brick, most of them beyond the band.
// One workgroup per brick; thread t holds voxels 8t .. 8t+7 (x = t >> 3,
// y = t & 7, z = 0..7), the byte 8y of the brick's 64-bit mask word x.
layout(local_size_x = 64) in;
#include "gpu_layout.h"
#include "field_layout.h"

layout(std430, binding = SVO_BIND_FIELD_DISTANCES) readonly restrict buffer Distances { float distances[]; };
layout(std430, binding = SVO_BIND_FIELD_CLOSEST) readonly restrict buffer Closest { uint closest[]; };
layout(std430, binding = SVO_BIND_FIELD_COUNTERS) restrict buffer Counters { uint counters[]; };
layout(std430, binding = SVO_BIND_COMPACT_MASKS) writeonly restrict buffer Masks { uint masks[]; };
layout(std430, binding = SVO_BIND_COMPACT_OFFSETS) writeonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = SVO_BIND_COMPACT_DISTANCES) writeonly restrict buffer Packed { float packedDistances[]; };
layout(std430, binding = SVO_BIND_COMPACT_CLOSEST) writeonly restrict buffer PackedClosest { uint packedClosest[]; };

uniform uint uBrickFirst; // this dispatch's bricks: [uBrickFirst, uBricks)
uniform uint uBricks;
uniform float uBand;     // a voxel is kept when its distance is less
uniform uint uClosest;   // 1: closest triangles were computed

shared uint sMask[16];
shared uint sCount[64];
shared uint sBase;

void main()
{
    uint t = gl_LocalInvocationID.x;
    for (uint brick = uBrickFirst + gl_WorkGroupID.x; brick < uBricks; brick += gl_NumWorkGroups.x) {
        if (t < 16u) sMask[t] = 0u;
        uint first = 512u * brick + 8u * t;
        uint bits = 0u;
        for (uint z = 0u; z < 8u; ++z)
            if (distances[first + z] < uBand) bits |= 1u << z;
        sCount[t] = uint(bitCount(bits));
        barrier();
        atomicOr(sMask[2u * (t >> 3u) + ((t & 7u) >> 2u)], bits << (8u * (t & 3u)));
        if (t == 0u) {
            uint total = 0u;
            for (uint i = 0u; i < 64u; ++i) total += sCount[i];
            sBase = atomicAdd(counters[1], total);
            offsets[brick] = sBase;
        }
        barrier();
        uint at = sBase;
        for (uint i = 0u; i < t; ++i) at += sCount[i];
        for (uint z = 0u; z < 8u; ++z)
            if ((bits & (1u << z)) != 0u) {
                packedDistances[at] = distances[first + z];
                if (uClosest != 0u) packedClosest[at] = closest[first + z];
                ++at;
            }
        if (t < 16u) masks[16u * brick + t] = sMask[t];
        barrier(); // the next brick clears the shared mask
    }
}
