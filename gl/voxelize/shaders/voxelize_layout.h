/* voxelize_layout.h: the voxelization and octree build passes' state block and binding slots.

   C++ and GLSL at once, on top of gpu_layout.h and under its rules (see
   there). Shaders include "gpu_layout.h" and then this file. */
#ifndef SVO_VOXELIZE_LAYOUT_H
#define SVO_VOXELIZE_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <svo/core/gpu_layout.h>
namespace svo::gpu {
#endif

/* ---- Octree build state (gl/voxelize/src/octree_passes.h) ----------------------
   Counters and indirect dispatch arguments of the GPU build, one std430
   block. Only uints, so C++ lays it out exactly as std430 does. */
#define SVO_BUILD_LEVEL_SLOTS 24
#if SVO_BUILD_LEVEL_SLOTS < SVO_KEY_BRICK_BITS + 2
#error voxelize_layout.h: levelStart needs brick levels 0 to SVO_KEY_BRICK_BITS and one past the end
#endif
/* Up to this brick level the build works from occupancy bitmaps
   (octree_bitmap.glsl): level l's nodes one bit each in Morton order (x the
   lowest bit of each triple), level by level, each level from a block of
   kBitmapBlockWords uints. Past it (grids over 4096 voxels a side, whose
   level-L bitmap would pass 16 MiB) the build descends from the root. */
#define SVO_BUILD_BITMAP_MAX_LEVEL 9
SVO_CONST(uint) kBitmapBlockWords = 16u;
SVO_CONST(uint) kBitmapBlockShift = 9u; /* 512 bits a block */
#define SVO_BUILD_STATE_FIELDS                                                  \
    uint entryDispatch[3]; /* indirect args over the input entries */          \
    uint levelDispatch[3]; /* indirect args over the nodes of the level */     \
    uint entryCount;       /* input entries to read */                         \
    uint nodeCount;        /* node allocation counter (may pass capacity) */   \
    uint brickCount;       /* brick allocation counter (may pass capacity) */  \
    uint pad;                                                                  \
    uint levelStart[SVO_BUILD_LEVEL_SLOTS]; /* first node of each level */

/* ---- Binding slots -----------------------------------------------------
   Raster pass (raster.frag). */
#define SVO_BIND_RASTER_COUNTER 0   /* atomic counters: entries, wraps past 2^32 */
#define SVO_BIND_RASTER_LIST 0      /* voxel keys */
#define SVO_BIND_RASTER_TRIANGLES 1 /* triangle of each entry */
/* Compute backend (voxelize.comp): the column walk's buffers above, and */
#define SVO_BIND_COMPUTE_POSITIONS 2 /* local float positions, 3 per vertex */
#define SVO_BIND_COMPUTE_INDICES 3   /* 3 vertex indices per triangle */
#define SVO_BIND_COMPUTE_WORK 4      /* (triangle, first work item) of each large triangle */
/* Octree passes (octree_*.comp): four buffers every pass sees ... */
#define SVO_BIND_BUILD_STATE 0
#define SVO_BIND_NODES 1
#define SVO_BIND_BRICKS 2
#define SVO_BIND_ENTRIES 3 /* voxel keys, or brick keys with masks */
/* ... then each pass its own. */
#define SVO_BIND_LIST_COUNTER 4       /* prepare: the raster counters, read as uints */
#define SVO_BIND_ENTRY_MASKS 5        /* fill: 16 uints per brick entry */
#define SVO_BIND_BUILD_BITMAP 6       /* bitmap build: the levels' occupancy bits */
#define SVO_BIND_BUILD_BLOCKS 7       /* bitmap build: per block its set bits, then the exclusive prefix of them */
#define SVO_BIND_ENTRY_TRIANGLES 4    /* attributes: the raster triangle list */
#define SVO_BIND_BRICK_VOXEL_OFFSETS 5 /* attributes: first voxel of each brick */
#define SVO_BIND_TRIANGLE_VALUES 6    /* attributes: 6 floats per triangle, normal then colour */
#define SVO_BIND_ATTRIBUTE_SUMS 7     /* attributes: kSumWords uints per voxel */

#ifdef __cplusplus
struct BuildState {
    SVO_BUILD_STATE_FIELDS
};
/* Byte offsets the C++ side passes to glDispatchComputeIndirect, and std430's
   (every field a uint or uint array: no padding anywhere). */
static_assert(offsetof(BuildState, entryDispatch) == 0 && offsetof(BuildState, levelDispatch) == 12);
static_assert(offsetof(BuildState, entryCount) == 24 && offsetof(BuildState, levelStart) == 40);
static_assert(sizeof(BuildState) == 40 + 4 * SVO_BUILD_LEVEL_SLOTS);

static_assert(distinctSlots({SVO_BIND_RASTER_LIST, SVO_BIND_RASTER_TRIANGLES}));
static_assert(distinctSlots({SVO_BIND_RASTER_LIST, SVO_BIND_RASTER_TRIANGLES, SVO_BIND_COMPUTE_POSITIONS,
                             SVO_BIND_COMPUTE_INDICES, SVO_BIND_COMPUTE_WORK}));
static_assert(distinctSlots({SVO_BIND_BUILD_STATE, SVO_BIND_NODES, SVO_BIND_BRICKS, SVO_BIND_ENTRIES,
                             SVO_BIND_LIST_COUNTER}));
static_assert(distinctSlots({SVO_BIND_BUILD_STATE, SVO_BIND_NODES, SVO_BIND_BRICKS, SVO_BIND_ENTRIES,
                             SVO_BIND_ENTRY_MASKS, SVO_BIND_LIST_COUNTER, SVO_BIND_BUILD_BITMAP, SVO_BIND_BUILD_BLOCKS}));
static_assert(distinctSlots({SVO_BIND_BUILD_STATE, SVO_BIND_NODES, SVO_BIND_BRICKS, SVO_BIND_ENTRIES,
                             SVO_BIND_ENTRY_TRIANGLES, SVO_BIND_BRICK_VOXEL_OFFSETS, SVO_BIND_TRIANGLE_VALUES,
                             SVO_BIND_ATTRIBUTE_SUMS}));
} // namespace svo::gpu
#endif

#endif /* SVO_VOXELIZE_LAYOUT_H */
