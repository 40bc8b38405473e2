#version 450 core
// One fragment is one voxel column. Every voxel of the column that the
// triangle's plane can reach is put to the shared overlap test on the cube
// grown by the guard band; those that pass go to the voxel list.
#include "glsl_types.glsl"
#include "overlap.glsl"
#include "gpu_layout.h"

flat in vec3 gA;
flat in vec3 gB;
flat in vec3 gC;
flat in int gAxis;
flat in vec4 gBox;

// The entry count, and how often it wrapped past 2^32 - 1.
layout(binding = SVO_BIND_RASTER_COUNTER, offset = 0) uniform atomic_uint uCount;
layout(binding = SVO_BIND_RASTER_COUNTER, offset = 4) uniform atomic_uint uWraps;
layout(std430, binding = SVO_BIND_RASTER_LIST) writeonly restrict buffer VoxelList { uvec2 voxels[]; };
// Written only when attribute channels are asked for: the triangle of each entry.
layout(std430, binding = SVO_BIND_RASTER_TRIANGLES) writeonly restrict buffer TriangleList { uint triangleOf[]; };
uniform uint uWriteTriangles;

uniform vec2 uTileOrigin;
uniform float uHalf;
uniform uint uCapacity;
uniform ivec3 uDims;
const float kUlp = 5.96046448e-08;

void main()
{
    vec2 col = floor(gl_FragCoord.xy) + uTileOrigin;
    if (col.x + uHalf < gBox.x || col.x - uHalf > gBox.z || col.y + uHalf < gBox.y || col.y - uHalf > gBox.w)
        discard;
    int w = gAxis;
    int u = (w + 1) % 3;
    int v = (w + 2) % 3;
    if (col.x < 0.0 || col.y < 0.0 || col.x >= float(uDims[u]) || col.y >= float(uDims[v])) discard;
    vec3 r = svo_column_range(gA, gB, gC, w, col.x, col.y, uHalf, kUlp);
    int k0 = max(int(ceil(r.x)), 0);
    int k1 = min(int(floor(r.y)), uDims[w] - 1);
    for (int k = k0; k <= k1; ++k) {
        vec3 centre;
        centre[u] = col.x;
        centre[v] = col.y;
        centre[w] = float(k);
        if (svo_triangle_box_overlap(gA, gB, gC, centre, uHalf)) {
            uint slot = atomicCounterIncrement(uCount);
            if (slot == 0xFFFFFFFFu) atomicCounterIncrement(uWraps);
            if (slot < uCapacity) {
                voxels[slot] = packVoxelKey(uvec3(centre));
                if (uWriteTriangles != 0u) triangleOf[slot] = uint(gl_PrimitiveID);
            }
        }
    }
}
