/* gpu_layout.h: the data layouts that the shaders and C++ both read, written
   once: voxel keys, octree nodes and bricks, fixed-point attribute sums and
   the winding tree's nodes. Each GL layer keeps its passes' binding slots
   beside its shaders (voxelize_layout.h, field_layout.h, view_layout.h),
   written the same way on top of this file.

   This file is C++ and GLSL at the same time. C++ includes it as
   "svo/core/gpu_layout.h" (voxel_key.h, octree.h, voxel_attributes.h,
   winding_tree.cpp, the GL layers); the shaders include it as "gpu_layout.h"
   (embedded by each GL layer's CMakeLists.txt, expanded by
   gl/device/src/shaders.cpp). So it keeps to what both preprocessors share:
   #define (function-like too), #if arithmetic, #error, comments. Comments
   inside macros are block comments, since a line comment would swallow the
   line continuation. The C++ part includes only <...> headers (the shader
   expander would try to inline a quoted one) and has no string literals,
   which some GLSL preprocessors may reject even when skipped.

   Numbers that #if checks or layout(binding = ...) need are macros; the rest
   are typed constants declared by SVO_CONST, a constexpr in namespace
   svo::gpu for C++ and a global const for GLSL. SVO_CONST stays defined for
   the layers' layout headers. */
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
/* ---- Winding tree nodes (winding_tree.h) -------------------------------
   The GPU's copy of the tree: a node is kWindingNodeVec4s vec4s, and a link
   with kWindingLeaf set is a leaf's first triangle. */
SVO_CONST(uint) kWindingLeaf = 0x80000000u;
SVO_CONST(uint) kWindingNodeVec4s = 9u; /* winding_tree.h: kWindingNodeFloats / 4 */

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

/* Buffers one program sees must not share a slot (the layers' layout headers check theirs). */
constexpr bool distinctSlots(std::initializer_list<int> slots)
{
    for (const int* a = slots.begin(); a != slots.end(); ++a)
        for (const int* b = a + 1; b != slots.end(); ++b)
            if (*a == *b) return false;
    return true;
}

} // namespace svo::gpu
#endif

#endif /* SVO_GPU_LAYOUT_H */
