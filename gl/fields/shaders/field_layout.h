/* field_layout.h: the distance, sign and winding passes' brick table and binding slots.

   C++ and GLSL at once, on top of gpu_layout.h and under its rules (see
   there). Shaders include "gpu_layout.h" and then this file. */
#ifndef SVO_FIELD_LAYOUT_H
#define SVO_FIELD_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <svo/core/gpu_layout.h>
namespace svo::gpu {
#endif

/* ---- Brick table (gl/fields/src/distance_field.cpp) ---------------------------------
   The bricks a distance or sign pass writes to, found by their brick
   coordinates (local coordinate >> 3): open addressing with linear probing
   over a power-of-two table of kTableWords uints per slot (x, y, z, index);
   an empty slot has index kNoChild. The hash is uint arithmetic, which wraps
   alike in C++ and GLSL. */
SVO_CONST(uint) kTableWords = 4u;
#define SVO_BRICK_HASH(x, y, z) ((((x) * 0x9E3779B1u) ^ ((y) * 0x85EBCA77u) ^ ((z) * 0xC2B2AE3Du)) * 0x27D4EB2Fu)

/* Distance and sign passes (band_distance.comp, parity_flips.comp). */
#define SVO_BIND_FIELD_POSITIONS 0 /* local double positions, 3 per vertex */
#define SVO_BIND_FIELD_INDICES 1   /* 3 vertex indices per triangle */
#define SVO_BIND_FIELD_ITEMS 2     /* kItemWords uints per triangle: first item, voxel box origin, box size, whole */
#define SVO_BIND_FIELD_TABLE 3     /* the brick table */
#define SVO_BIND_FIELD_DISTANCES 4 /* 512 per brick: float bits of the distance in voxels (+inf: beyond the band) */
#define SVO_BIND_FIELD_CLOSEST 5   /* 512 per brick: the closest triangle (0xFFFFFFFF: none) */
#define SVO_BIND_FIELD_FLIPS 6     /* 16 uints per brick: parity crossings, one bit per voxel */
#define SVO_BIND_FIELD_COUNTERS 7  /* uints: crossings whose brick is not in the table, then band values kept */
/* Band compaction (band_compact.comp): the slots of the mesh and items,
   which that pass does not read, hold its output, so no pass needs more than
   the 8 storage blocks GL 4.5 guarantees. */
#define SVO_BIND_COMPACT_MASKS 0     /* 16 uints per brick: the voxels nearer than the band */
#define SVO_BIND_COMPACT_OFFSETS 1   /* per brick: where its values start in the packed arrays */
#define SVO_BIND_COMPACT_DISTANCES 2 /* packed: the distances of the masked voxels, brick by brick in bit order */
#define SVO_BIND_COMPACT_CLOSEST 3   /* packed alike: their closest triangles */
/* Band leaves (band_leaves.comp, fields built into NanoVDB grids on
   the device): instead of packing, the bricks with a voxel nearer than the
   band become leaves as svo/gl/nano_grid_builder.h takes them, in the slots
   of the mesh, the items and the crossings, which the leaves pass does not
   read (a signed field's inside voxels come in a slot of their own). The
   leaf count is counter 2. */
#define SVO_BIND_LEAVES_ORIGINS 0 /* 3 ints per leaf: its origin in index space */
#define SVO_BIND_LEAVES_MASKS 1   /* 16 uints per leaf: the voxels nearer than the band */
#define SVO_BIND_LEAVES_VALUES 2  /* 512 per leaf: float bits of the distance in world units, else the background */
#define SVO_BIND_LEAVES_CLOSEST 6 /* 512 per leaf: the closest triangle where active, else -1 */
#define SVO_BIND_LEAVES_INSIDE 8  /* 16 uints per brick: the voxels inside (a signed field) */
SVO_CONST(uint) kLeafCounter = 2u;
SVO_CONST(uint) kInsideLeafCounter = 3u; /* of those, leaves with inside voxels and none active (winding signs) */
/* first item, voxel box origin x y z, box size x y z, 1 when the box is one item (else one per brick it spans) */
SVO_CONST(uint) kItemWords = 8u;

/* Winding numbers (winding_number.comp, svo/core/winding_tree.h); positions
   and indices as for the distance passes. */
#define SVO_BIND_WINDING_NODES 2  /* 9 vec4s per tree node: centre, radius, area vector, moments (winding_tree.h) */
#define SVO_BIND_WINDING_LINKS 3  /* 2 uints per tree node: children, or first and count | kWindingLeaf */
#define SVO_BIND_WINDING_ORDER 4  /* triangle indices in leaf order */
#define SVO_BIND_WINDING_BRICKS 5 /* 3 uints per brick: brick coordinates (per-voxel pass) */
#define SVO_BIND_WINDING_OUT 6    /* per-voxel: 16 uints per brick, inside bits; per-brick: a float per brick */
SVO_CONST(uint) kWindingStack = 64u; /* tree depth + 1 at most (the host checks) */

#ifdef __cplusplus
static_assert(distinctSlots({SVO_BIND_FIELD_POSITIONS, SVO_BIND_FIELD_INDICES, SVO_BIND_FIELD_ITEMS,
                             SVO_BIND_FIELD_TABLE, SVO_BIND_FIELD_DISTANCES, SVO_BIND_FIELD_CLOSEST,
                             SVO_BIND_FIELD_FLIPS, SVO_BIND_FIELD_COUNTERS}));
static_assert(distinctSlots({SVO_BIND_COMPACT_MASKS, SVO_BIND_COMPACT_OFFSETS, SVO_BIND_COMPACT_DISTANCES,
                             SVO_BIND_COMPACT_CLOSEST, SVO_BIND_FIELD_DISTANCES, SVO_BIND_FIELD_CLOSEST,
                             SVO_BIND_FIELD_COUNTERS}));
static_assert(distinctSlots({SVO_BIND_LEAVES_ORIGINS, SVO_BIND_LEAVES_MASKS, SVO_BIND_LEAVES_VALUES,
                             SVO_BIND_LEAVES_CLOSEST, SVO_BIND_LEAVES_INSIDE, SVO_BIND_FIELD_TABLE, SVO_BIND_FIELD_DISTANCES,
                             SVO_BIND_FIELD_CLOSEST, SVO_BIND_FIELD_COUNTERS}));
static_assert(distinctSlots({SVO_BIND_FIELD_POSITIONS, SVO_BIND_FIELD_INDICES, SVO_BIND_WINDING_NODES,
                             SVO_BIND_WINDING_LINKS, SVO_BIND_WINDING_ORDER, SVO_BIND_WINDING_BRICKS,
                             SVO_BIND_WINDING_OUT}));
} // namespace svo::gpu
#endif

#endif /* SVO_FIELD_LAYOUT_H */
