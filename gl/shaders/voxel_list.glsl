// The voxel list: 64-bit keys appended through an atomic counter that keeps
// counting past the list's end (so an overflow tells the size it needed).
#include "gpu_layout.h"

// The entry count, and how often it wrapped past 2^32 - 1.
layout(binding = SVO_BIND_RASTER_COUNTER, offset = 0) uniform atomic_uint uCount;
layout(binding = SVO_BIND_RASTER_COUNTER, offset = 4) uniform atomic_uint uWraps;
layout(std430, binding = SVO_BIND_RASTER_LIST) writeonly restrict buffer VoxelList { uvec2 voxels[]; };
// Written only when attribute channels are asked for: the triangle of each entry.
layout(std430, binding = SVO_BIND_RASTER_TRIANGLES) writeonly restrict buffer TriangleList { uint triangleOf[]; };
uniform uint uWriteTriangles;
uniform uint uCapacity;

void svo_append(vec3 centre, uint triangle)
{
    uint slot = atomicCounterIncrement(uCount);
    if (slot == 0xFFFFFFFFu) atomicCounterIncrement(uWraps);
    if (slot < uCapacity) {
        voxels[slot] = packVoxelKey(uvec3(centre));
        if (uWriteTriangles != 0u) triangleOf[slot] = triangle;
    }
}
