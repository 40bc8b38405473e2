/* gpu_layout.h: every layout that the shaders and C++ both read, written once.

   This file is C++ and GLSL at the same time. C++ includes it as
   "svo/core/gpu_layout.h" (voxel_key.h, octree.h, voxel_attributes.h, the GL
   backend); the shaders include it as "gpu_layout.h" (embedded by
   gl/CMakeLists.txt, expanded by gl/src/shaders.cpp). So it keeps to what both
   preprocessors share: #define (function-like too), #if arithmetic, #error,
   comments. Comments inside macros are block comments, since a line comment
   would swallow the line continuation. The C++ part includes only <...>
   headers (the shader expander would try to inline a quoted one) and has no
   string literals, which some GLSL preprocessors may reject even when skipped.

   Numbers that #if checks or layout(binding = ...) need are macros; the rest
   are typed constants declared by SVO_CONST, a constexpr in namespace
   svo::gpu for C++ and a global const for GLSL. */
#ifndef SVO_GPU_LAYOUT_H
#define SVO_GPU_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <initializer_list>
namespace svo::gpu {
using uint = std::uint32_t; /* GLSL spelling, so declarations read the same */
#define SVO_CONST(type) inline constexpr type
#else
#define SVO_CONST(type) const type
#endif

/* ---- Voxel keys (voxel_key.h) ------------------------------------------
   64 bits, brick-major: bit 63 clear, then brick x, brick y, brick z (18 bits
   each, local coordinate >> 3), then the voxel's bit within its 8^3 brick,
   (x&7)<<6 | (y&7)<<3 | (z&7), which is OpenVDB's LeafNode<T,3> bit order.
   GLSL has no 64-bit integers here and holds a key as uvec2(low, high). */
#define SVO_BRICK_LOG2 3
#define SVO_KEY_LEAF_BITS (3 * SVO_BRICK_LOG2)
#define SVO_KEY_BRICK_BITS 18
#define SVO_KEY_BRICK_Z_SHIFT SVO_KEY_LEAF_BITS
#define SVO_KEY_BRICK_Y_SHIFT (SVO_KEY_BRICK_Z_SHIFT + SVO_KEY_BRICK_BITS)
#define SVO_KEY_BRICK_X_SHIFT (SVO_KEY_BRICK_Y_SHIFT + SVO_KEY_BRICK_BITS)

#if SVO_KEY_BRICK_X_SHIFT + SVO_KEY_BRICK_BITS > 63
#error gpu_layout.h: voxel keys must keep bit 63 clear
#endif
/* The GLSL helpers below assume brick z and the leaf bits lie in the low
   word, brick x in the high word, and brick y across the two. */
#if SVO_KEY_BRICK_Z_SHIFT + SVO_KEY_BRICK_BITS > 32 || SVO_KEY_BRICK_X_SHIFT < 32
#error gpu_layout.h: brick z must lie in the low key word and brick x in the high one
#endif
#if SVO_KEY_BRICK_Y_SHIFT >= 32 || SVO_KEY_BRICK_Y_SHIFT + SVO_KEY_BRICK_BITS <= 32
#error gpu_layout.h: brick y must straddle the two key words
#endif

SVO_CONST(uint) kBrickLog2 = uint(SVO_BRICK_LOG2);
SVO_CONST(uint) kBrickMask = uint((1 << SVO_BRICK_LOG2) - 1); /* a coordinate within its brick */
SVO_CONST(uint) kKeyLeafMask = uint((1 << SVO_KEY_LEAF_BITS) - 1);
SVO_CONST(uint) kKeyLeafXShift = uint(2 * SVO_BRICK_LOG2);
SVO_CONST(uint) kKeyLeafYShift = uint(SVO_BRICK_LOG2);
SVO_CONST(uint) kKeyLeafZShift = 0u;
SVO_CONST(uint) kKeyBrickMask = uint((1 << SVO_KEY_BRICK_BITS) - 1);
SVO_CONST(uint) kKeyBrickXShift = uint(SVO_KEY_BRICK_X_SHIFT);
SVO_CONST(uint) kKeyBrickYShift = uint(SVO_KEY_BRICK_Y_SHIFT);
SVO_CONST(uint) kKeyBrickZShift = uint(SVO_KEY_BRICK_Z_SHIFT);

/* ---- Octree buffers (octree.h) -----------------------------------------
   A node is two uints (child, childMask); a brick is 512 bits, 8
   little-endian uint64 words on the CPU and so 16 uints on the GPU. */
SVO_CONST(uint) kNodeWords = 2u;
SVO_CONST(uint) kBrickWords = 16u;
/* A child pointer that could not be allocated (GPU capacity overflow). */
SVO_CONST(uint) kNoChild = 0xFFFFFFFFu;

/* ---- Attribute sums (voxel_attributes.h) -------------------------------
   Per voxel, 8 uints: ~(smallest triangle id) (0: none), the normal sum
   (3), the colour sum (3), the contribution count. Sums are 16.16 fixed
   point, so they do not depend on the order of the additions. A unit value
   is 2^16; the count is capped so that many of them still fit an int32. */
#define SVO_FIXED_FRACTION_BITS 16
#define SVO_FIXED_MAX_CONTRIBUTIONS (0x7FFFFFFF >> SVO_FIXED_FRACTION_BITS)

SVO_CONST(float) kFixedScale = float(1 << SVO_FIXED_FRACTION_BITS);
SVO_CONST(uint) kFixedMaxContributions = uint(SVO_FIXED_MAX_CONTRIBUTIONS);
SVO_CONST(uint) kSumTriangle = 0u;
SVO_CONST(uint) kSumNormal = 1u;
SVO_CONST(uint) kSumColor = 4u;
SVO_CONST(uint) kSumCount = 7u;
SVO_CONST(uint) kSumWords = 8u;

/* ---- Octree build state (gl/src/octree_builder.h) ----------------------
   Counters and indirect dispatch arguments of the GPU build, one std430
   block. Only uints, so C++ lays it out exactly as std430 does. */
#define SVO_BUILD_LEVEL_SLOTS 24
#if SVO_BUILD_LEVEL_SLOTS < SVO_KEY_BRICK_BITS + 2
#error gpu_layout.h: levelStart needs brick levels 0 to SVO_KEY_BRICK_BITS and one past the end
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

/* Viewer (gl/src/octree_view.cpp, view_*.vert/frag/comp): the octree's
   buffers as uploaded for drawing, and each node's origin in voxels. */
#define SVO_BIND_VIEW_NODES 0
#define SVO_BIND_VIEW_BRICKS 1
#define SVO_BIND_VIEW_ORIGINS 2 /* uvec4 per node: local origin (voxels), unused */
#define SVO_BIND_VIEW_VOXEL_START 3 /* uint per brick: its first voxel in voxel order */
#define SVO_BIND_VIEW_ATTRIBUTE 4   /* the coloured channel, voxel order: 3 floats (normal, colour) or 1 uint (triangle) */
#define SVO_BIND_VIEW_OPACITY 5     /* 2 floats per node, AO mip-map: min(1, voxels / face voxels); that or the most opaque child's */
#define SVO_BIND_VIEW_LIGHTS 6      /* lighting: 2 vec4 per light, cell space (light_volume.glsl) */
#define SVO_BIND_VIEW_NORMALS 7     /* lighting: the normal channel, 3 floats per voxel, voxel order */
#define SVO_BIND_VIEW_ALBEDO 8      /* lighting: the colour channel, 3 floats per voxel (or unused) */
#define SVO_BIND_VIEW_DIRECT 9      /* lighting: per voxel, the irradiance on its normal's side and on the other, packed halves (view_lights.glsl) */
#define SVO_BIND_VIEW_LOOP_CUT 10   /* uint: invocations whose loops a CPU rasterizer cut short (loop_cut.glsl) */
/* Lighting volume (gl/src/light_volume.cpp): texture and image units. */
#define SVO_UNIT_LIGHT_OPACITY 0  /* texture: rgb = opacity seen along x, y, z */
#define SVO_UNIT_LIGHT_RADIANCE 1 /* texture: rgb = radiance x coverage, a = coverage */
#define SVO_UNIT_LIGHT_ALONG 2 /* textures 2..7: radiance seen along +x -x +y -y +z -z, levels 1.. */
#define SVO_UNIT_LIGHT_LIT_SIDE 8 /* texture: level 0's lit side times its light (rgba16f) */
#define SVO_UNIT_LIGHT_CLEAR 11   /* texture: per texel of level 0, the coarsest level clear of voxels (r8ui) */
/* Viewer: the voxel pass's pixels, written as an image by view_voxels.comp
   and read as a texture by view_pixels.frag. GL promises 8 image units. */
#define SVO_IMAGE_VIEW_PIXELS 0
#define SVO_UNIT_VIEW_PIXELS 9
/* Viewer, interleaved cones: each pixel's gathered light, albedo and normal
   (rgba32ui) and the point its cones left from (rgba32f), written by
   view_voxels.comp and averaged by view_resolve.comp. */
#define SVO_IMAGE_VIEW_GATHER 1
#define SVO_IMAGE_VIEW_POINTS 2
/* Viewer, ViewLayers::surface = Mesh: the mesh rasterized into the triangle
   each pixel sees (its index + 1; 0 where none covers the pixel), read by
   view_voxels.comp with the mesh's positions (3 floats a vertex, cell
   space) and triangles (3 uints), where each pixel's ray meets it. */
#define SVO_UNIT_VIEW_SURFACE_TRIANGLE 10
#define SVO_BIND_VIEW_MESH_POSITIONS 11
#define SVO_BIND_VIEW_MESH_TRIANGLES 12
/* ViewLayers::voxelColor as the shader reads it. */
#define SVO_VIEW_COLOR_FLAT 0
#define SVO_VIEW_COLOR_NORMAL 1
#define SVO_VIEW_COLOR_RGB 2
#define SVO_VIEW_COLOR_TRIANGLE 3

/* ---- Brick table (gl/src/brick_table.h) ---------------------------------
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
/* first item, voxel box origin x y z, box size x y z, 1 when the box is one item (else one per brick it spans) */
SVO_CONST(uint) kItemWords = 8u;

/* Winding numbers (winding_number.comp, svo/core/winding_tree.h); positions
   and indices as for the distance passes. */
#define SVO_BIND_WINDING_NODES 2  /* 9 vec4s per tree node: centre, radius, area vector, moments (winding_tree.h) */
#define SVO_BIND_WINDING_LINKS 3  /* 2 uints per tree node: children, or first and count | kWindingLeaf */
#define SVO_BIND_WINDING_ORDER 4  /* triangle indices in leaf order */
#define SVO_BIND_WINDING_BRICKS 5 /* 3 uints per brick: brick coordinates (per-voxel pass) */
#define SVO_BIND_WINDING_OUT 6    /* per-voxel: 16 uints per brick, inside bits; per-brick: a float per brick */
SVO_CONST(uint) kWindingLeaf = 0x80000000u;
SVO_CONST(uint) kWindingNodeVec4s = 9u; /* winding_tree.h: kWindingNodeFloats / 4 */
SVO_CONST(uint) kWindingStack = 64u; /* tree depth + 1 at most (the host checks) */

#ifndef __cplusplus
/* ---- GLSL helpers ------------------------------------------------------ */

/* voxel_key.h's packVoxelKey, as uvec2(low, high). */
uvec2 packVoxelKey(uvec3 p)
{
    uvec3 b = p >> kBrickLog2;
    uvec3 v = p & kBrickMask;
    uint leaf = (v.x << kKeyLeafXShift) | (v.y << kKeyLeafYShift) | (v.z << kKeyLeafZShift);
    return uvec2(leaf | (b.z << kKeyBrickZShift) | (b.y << kKeyBrickYShift),
                 (b.y >> (32u - kKeyBrickYShift)) | (b.x << (kKeyBrickXShift - 32u)));
}

/* The brick coordinates (local coordinate >> 3) of a key. */
uvec3 brickOfVoxelKey(uvec2 key)
{
    return uvec3((key.y >> (kKeyBrickXShift - 32u)) & kKeyBrickMask,
                 ((key.x >> kKeyBrickYShift) | (key.y << (32u - kKeyBrickYShift))) & kKeyBrickMask,
                 (key.x >> kKeyBrickZShift) & kKeyBrickMask);
}

/* The voxel's bit within its brick (0..511). */
uint leafBitOfVoxelKey(uvec2 key) { return key.x & kKeyLeafMask; }

/* voxel_attributes.h's toFixed: 16.16, rounding half to even. */
int toFixed(float v) { return int(roundEven(v * kFixedScale)); }

#else
/* ---- C++ checks -------------------------------------------------------- */

static_assert(kSumNormal == kSumTriangle + 1 && kSumColor == kSumNormal + 3 && kSumCount == kSumColor + 3 &&
              kSumWords == kSumCount + 1);
static_assert(double(kFixedMaxContributions) * kFixedScale <= 2147483647.0); /* a full sum of unit values fits int32 */

struct BuildState {
    SVO_BUILD_STATE_FIELDS
};
/* Byte offsets the C++ side passes to glDispatchComputeIndirect, and std430's
   (every field a uint or uint array: no padding anywhere). */
static_assert(offsetof(BuildState, entryDispatch) == 0 && offsetof(BuildState, levelDispatch) == 12);
static_assert(offsetof(BuildState, entryCount) == 24 && offsetof(BuildState, levelStart) == 40);
static_assert(sizeof(BuildState) == 40 + 4 * SVO_BUILD_LEVEL_SLOTS);

/* Buffers one program sees must not share a slot. */
constexpr bool distinctSlots(std::initializer_list<int> slots)
{
    for (const int* a = slots.begin(); a != slots.end(); ++a)
        for (const int* b = a + 1; b != slots.end(); ++b)
            if (*a == *b) return false;
    return true;
}
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
static_assert(distinctSlots({SVO_IMAGE_VIEW_PIXELS, SVO_IMAGE_VIEW_GATHER, SVO_IMAGE_VIEW_POINTS}));
static_assert(distinctSlots({SVO_UNIT_LIGHT_OPACITY, SVO_UNIT_LIGHT_RADIANCE, SVO_UNIT_LIGHT_ALONG,
                             SVO_UNIT_LIGHT_ALONG + 1, SVO_UNIT_LIGHT_ALONG + 2, SVO_UNIT_LIGHT_ALONG + 3,
                             SVO_UNIT_LIGHT_ALONG + 4, SVO_UNIT_LIGHT_ALONG + 5, SVO_UNIT_LIGHT_LIT_SIDE, SVO_UNIT_VIEW_PIXELS,
                             SVO_UNIT_VIEW_SURFACE_TRIANGLE, SVO_UNIT_LIGHT_CLEAR}));
static_assert(distinctSlots({SVO_BIND_VIEW_NODES, SVO_BIND_VIEW_BRICKS, SVO_BIND_VIEW_ORIGINS,
                             SVO_BIND_VIEW_VOXEL_START, SVO_BIND_VIEW_ATTRIBUTE, SVO_BIND_VIEW_OPACITY,
                             SVO_BIND_VIEW_LIGHTS, SVO_BIND_VIEW_NORMALS, SVO_BIND_VIEW_ALBEDO,
                             SVO_BIND_VIEW_DIRECT, SVO_BIND_VIEW_LOOP_CUT, SVO_BIND_VIEW_MESH_POSITIONS,
                             SVO_BIND_VIEW_MESH_TRIANGLES}));
static_assert(distinctSlots({SVO_BIND_FIELD_POSITIONS, SVO_BIND_FIELD_INDICES, SVO_BIND_FIELD_ITEMS,
                             SVO_BIND_FIELD_TABLE, SVO_BIND_FIELD_DISTANCES, SVO_BIND_FIELD_CLOSEST,
                             SVO_BIND_FIELD_FLIPS, SVO_BIND_FIELD_COUNTERS}));
static_assert(distinctSlots({SVO_BIND_COMPACT_MASKS, SVO_BIND_COMPACT_OFFSETS, SVO_BIND_COMPACT_DISTANCES,
                             SVO_BIND_COMPACT_CLOSEST, SVO_BIND_FIELD_DISTANCES, SVO_BIND_FIELD_CLOSEST,
                             SVO_BIND_FIELD_COUNTERS}));
static_assert(distinctSlots({SVO_BIND_FIELD_POSITIONS, SVO_BIND_FIELD_INDICES, SVO_BIND_WINDING_NODES,
                             SVO_BIND_WINDING_LINKS, SVO_BIND_WINDING_ORDER, SVO_BIND_WINDING_BRICKS,
                             SVO_BIND_WINDING_OUT}));

} // namespace svo::gpu
#endif

#undef SVO_CONST
#endif /* SVO_GPU_LAYOUT_H */
