/* nano_layout.h: NanoVDB 32.4's grid layout as the GPU grid builder writes
   it, in 32-bit words, and the builder's binding slots.

   C++ and GLSL at once, on top of gpu_layout.h and under its rules (see
   there). The numbers are facts of NanoVDB's ABI (the byte offsets of
   nanovdb::GridData, TreeData, RootData and its Tile, InternalData and
   LeafData, as Debian's PNanoVDB.h lists them too); tests/test_gpu_nano_grid.cpp
   checks each against offsetof/sizeof on NanoVDB's own structs. The scalar
   kinds (Float, Int32, Mask, Boolean) share the root and the internal
   nodes' layout (a table entry is 8 bytes: a 4-byte value or an int64 child
   offset); only their leaves differ. Vec3f (3 words a value) has its own:
   table entries of 16 bytes, a larger root, the leaves' values at word 32. */
#ifndef SVO_NANO_LAYOUT_H
#define SVO_NANO_LAYOUT_H

#ifdef __cplusplus
#include <svo/core/gpu_layout.h>
namespace svo::gpu {
#endif

/* ---- Kinds (nanovdb::GridType values) ----------------------------------- */
SVO_CONST(uint) kNanoTypeFloat = 1u;
SVO_CONST(uint) kNanoTypeInt32 = 4u;
SVO_CONST(uint) kNanoTypeVec3f = 6u;
SVO_CONST(uint) kNanoTypeMask = 8u;
SVO_CONST(uint) kNanoTypeBool = 11u;

/* ---- Headers (bytes) ---------------------------------------------------- */
SVO_CONST(uint) kNanoGridBytes = 672u; /* GridData */
SVO_CONST(uint) kNanoTreeBytes = 64u;  /* TreeData */
SVO_CONST(uint) kNanoRootBytes = 64u;  /* RootData of a 4-byte value, before its tiles */
SVO_CONST(uint) kNanoRootBytesVec3f = 96u;
SVO_CONST(uint) kNanoRootBackground = 7u; /* word; the minimum and maximum follow it, a value each */
SVO_CONST(uint) kNanoTileBytes = 32u;  /* RootData::Tile: key (8), child (8), state (4), value (4), padding */

/* ---- Internal nodes (words) ----------------------------------------------
   bbox min (3), bbox max (3), flags (uint64), value mask, child mask,
   minimum, maximum, average, deviation, then the table at a 32-byte
   boundary (the maximum a value after the minimum). */
SVO_CONST(uint) kNanoNodeFlags = 6u;
SVO_CONST(uint) kNanoNodeValueMask = 8u;
SVO_CONST(uint) kNanoLowerLog2 = 4u; /* 16^3 children of 8^3 voxels */
SVO_CONST(uint) kNanoUpperLog2 = 5u; /* 32^3 children of 128^3 voxels */
SVO_CONST(uint) kNanoLowerChildMask = 136u;
SVO_CONST(uint) kNanoLowerMinimum = 264u;
SVO_CONST(uint) kNanoLowerTable = 272u;
SVO_CONST(uint) kNanoLowerWords = 8464u; /* 33856 bytes */
SVO_CONST(uint) kNanoUpperChildMask = 1032u;
SVO_CONST(uint) kNanoUpperMinimum = 2056u;
SVO_CONST(uint) kNanoUpperTable = 2064u;
SVO_CONST(uint) kNanoUpperWords = 67600u; /* 270400 bytes */
SVO_CONST(uint) kNanoLowerWordsVec3f = 16656u;  /* 66624 bytes: entries of 4 words */
SVO_CONST(uint) kNanoUpperWordsVec3f = 133136u; /* 532544 bytes */

/* ---- Leaves (words) ------------------------------------------------------
   bbox min (3), bbox size - 1 as 3 bytes and flags as the 4th, value mask
   (16), then per kind: Float and Int32 minimum, maximum, average,
   deviation, 512 values at word 24; Vec3f minimum and maximum (3 words
   each), average, deviation, 512 values of 3 words at word 32; Boolean its
   512 value bits at word 20; Mask nothing (padding). */
SVO_CONST(uint) kNanoLeafDifFlags = 3u;
SVO_CONST(uint) kNanoLeafValueMask = 4u;
SVO_CONST(uint) kNanoLeafMinimum = 20u;
SVO_CONST(uint) kNanoLeafValues = 24u;    /* Float, Int32 */
SVO_CONST(uint) kNanoLeafBoolValues = 20u; /* Boolean: a 512-bit mask */
SVO_CONST(uint) kNanoLeafWordsValue = 536u; /* Float, Int32: 2144 bytes */
SVO_CONST(uint) kNanoLeafWordsMask = 24u;   /* Mask: 96 bytes */
SVO_CONST(uint) kNanoLeafWordsBool = 40u;   /* Boolean: 160 bytes */
SVO_CONST(uint) kNanoLeafValuesVec3f = 32u;
SVO_CONST(uint) kNanoLeafWordsVec3f = 1568u; /* Vec3f: 6272 bytes */

/* ---- Per-node statistics scratch (words per node) ------------------------
   bbox min xyz, bbox max xyz (an empty box: INT_MAX then INT_MIN), the
   minimum's bits (3 words, scalars in the first), the maximum's. */
SVO_CONST(uint) kNanoStatWords = 12u;

/* ---- Sort entries ---------------------------------------------------------
   Per leaf and per 8^3 tile, 4 key words compared in order: upper node
   origin x, y, z (each coordinate >> 12, plus 2^19 so that unsigned order is
   signed order), then lower index << 12 | leaf index; a fifth word holds the
   entry's input index (a leaf's index, or the leaf count plus a tile's).
   Padding entries (up to a power of two) have all key words 0xFFFFFFFF. */
SVO_CONST(uint) kNanoSortWords = 5u;

/* ---- Tiles (words per 8^3 tile of a lower node) ---------------------------
   origin x, y, z, the value's word, 1 when active (else 0). */
SVO_CONST(uint) kNanoTileWords = 5u;

/* ---- Counters (words) ---------------------------------------------------- */
SVO_CONST(uint) kNanoCountUpper = 0u;
SVO_CONST(uint) kNanoCountLower = 1u;
SVO_CONST(uint) kNanoCountRepeated = 2u; /* 1 + sorted index of a repeated leaf, or 0 */
SVO_CONST(uint) kNanoCountVoxelsLow = 3u;
SVO_CONST(uint) kNanoCountVoxelsHigh = 4u;
SVO_CONST(uint) kNanoCountMisaligned = 5u; /* 1 + input index of an origin not a multiple of 8, or 0 */
SVO_CONST(uint) kNanoCountActiveTiles = 6u; /* active 8^3 tiles (TreeData's first tile count) */
SVO_CONST(uint) kNanoCountWords = 8u;
/* nano_scan.comp: the sorted entries a work group of its counting and
   writing phases takes (256 threads, 8 rounds). */
SVO_CONST(uint) kNanoScanChunk = 2048u;

/* ---- Binding slots --------------------------------------------------------- */
#define SVO_BIND_NANO_ORIGINS 0  /* per leaf: its origin, 3 ints (input order) */
#define SVO_BIND_NANO_MASKS 1    /* per leaf: 16 uints, OpenVDB's bit order (input order) */
#define SVO_BIND_NANO_VALUES 2   /* per leaf: 512 values of 1 word (Vec3f: 3) (input order), when given */
#define SVO_BIND_NANO_SORT 3     /* kNanoSortWords per entry */
#define SVO_BIND_NANO_RANKS 4    /* nano_common.glsl's tables: per sorted entry its lower and upper rank, per lower its first entry, per upper its first lower, per entry its leaf rank, per leaf its entry */
#define SVO_BIND_NANO_STATS 5    /* kNanoStatWords per node: leaves, then lowers, then uppers */
#define SVO_BIND_NANO_COUNTERS 6 /* kNanoCountWords */
#define SVO_BIND_NANO_GRID 7     /* the grid */
#define SVO_BIND_NANO_TILES 8    /* per 8^3 tile: kNanoTileWords (input order) */
#define SVO_BIND_NANO_SCAN 9     /* nano_scan.comp: per chunk of kNanoScanChunk entries, its upper, lower and leaf starts (then their exclusive sums) */

#ifdef __cplusplus
static_assert(distinctSlots({SVO_BIND_NANO_ORIGINS, SVO_BIND_NANO_MASKS, SVO_BIND_NANO_VALUES, SVO_BIND_NANO_SORT,
                             SVO_BIND_NANO_RANKS, SVO_BIND_NANO_STATS, SVO_BIND_NANO_COUNTERS, SVO_BIND_NANO_GRID,
                             SVO_BIND_NANO_TILES, SVO_BIND_NANO_SCAN}));
} // namespace svo::gpu
#endif

#endif /* SVO_NANO_LAYOUT_H */
