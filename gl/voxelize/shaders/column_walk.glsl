// One voxel column of one triangle: every voxel of the column that the
// triangle's plane can reach is put to the shared overlap test on the cube
// grown by the guard band (thin mode: on the voxel's three centre segments,
// grown by it; they lie inside the cube, so the cube's candidates hold every
// voxel they can keep); those that pass go to the voxel list. The raster
// fragment shader and the compute backend both call this, so that for the
// columns they visit they keep exactly the same voxels.
#include "gpu_layout.h"
#include "voxelize_layout.h"

// The entry count, and how often it wrapped past 2^32 - 1.
layout(binding = SVO_BIND_RASTER_COUNTER, offset = 0) uniform atomic_uint uCount;
layout(binding = SVO_BIND_RASTER_COUNTER, offset = 4) uniform atomic_uint uWraps;
layout(std430, binding = SVO_BIND_RASTER_LIST) writeonly restrict buffer VoxelList { uvec2 voxels[]; };
// Written only when attribute channels are asked for: the triangle of each entry.
layout(std430, binding = SVO_BIND_RASTER_TRIANGLES) writeonly restrict buffer TriangleList { uint triangleOf[]; };
uniform uint uWriteTriangles;
uniform float uHalf;      // cube half side, or thin segments' half length, with the guard band
uniform uint uThin;       // 1: thin (6-separating) test, 0: conservative cube test
uniform float uThickness; // thin segments' half width: the guard band's half
uniform uint uCapacity;
// Voxels are kept only inside [uClipLo, uClipHi): the whole grid, or one tile
// of it when a grid's list or octree would not fit in GPU memory at once.
uniform ivec3 uClipLo;
uniform ivec3 uClipHi;
const float kUlp = 5.96046448e-08;

/// Column (col.x, col.y) on the plane across axis w; box = (umin, vmin, umax,
/// vmax) of the projected triangle. Columns whose square misses the box, or
/// that lie outside the clip box, keep nothing; the clip box only removes
/// voxels, so a tile keeps exactly the whole grid's voxels that lie in it.
void svo_walk_column(vec3 a, vec3 b, vec3 c, int w, vec2 col, vec4 box, uint triangle)
{
    if (col.x + uHalf < box.x || col.x - uHalf > box.z || col.y + uHalf < box.y || col.y - uHalf > box.w) return;
    int u = (w + 1) % 3;
    int v = (w + 2) % 3;
    if (col.x < float(uClipLo[u]) || col.y < float(uClipLo[v]) || col.x >= float(uClipHi[u]) ||
        col.y >= float(uClipHi[v]))
        return;
    vec3 r = svo_column_range(a, b, c, w, col.x, col.y, uHalf, kUlp);
    int k0 = max(int(ceil(r.x)), uClipLo[w]);
    int k1 = min(int(floor(r.y)), uClipHi[w] - 1);
    for (int k = k0; k <= k1; ++k) {
        vec3 centre;
        centre[u] = col.x;
        centre[v] = col.y;
        centre[w] = float(k);
        bool keep = uThin != 0u ? svo_triangle_thin_overlap(a, b, c, centre, uHalf, uThickness)
                                : svo_triangle_box_overlap(a, b, c, centre, uHalf);
        if (keep) {
            uint slot = atomicCounterIncrement(uCount);
            if (slot == 0xFFFFFFFFu) atomicCounterIncrement(uWraps);
            if (slot < uCapacity) {
                voxels[slot] = packVoxelKey(uvec3(centre));
                if (uWriteTriangles != 0u) triangleOf[slot] = triangle;
            }
        }
    }
}
