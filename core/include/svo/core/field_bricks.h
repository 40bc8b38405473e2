#pragma once
/// @file field_bricks.h
/// @brief Distance fields and solids on bricks: what the GPU's field pipeline
/// (svo/gl/field_pipeline.h) computes and the converter
/// (svo/vdb_io/field_grids.h) turns into grids. Data only.
///
/// Bricks are named by their brick coordinates on the field's grid (local
/// voxel coordinate / 8) and hold 512 voxels in OpenVDB's LeafNode bit order.
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/octree.h"
#include "svo/core/parity_scan.h"

namespace svo {

using BrickCoord = std::array<uint32_t, 3>;

/// Inside and outside, for the band's bricks and beyond them.
struct FieldSigns {
    std::vector<Brick> inside; ///< per band brick, the voxels whose centres are inside
    /// Parity: runs of whole bricks inside between band bricks of a column.
    std::vector<InsideRun> runs;
    /// Winding: whole bricks beyond the band that are inside, and bricks
    /// beyond it classified voxel by voxel (their inside voxels).
    std::vector<BrickCoord> insideBricks;
    std::vector<std::pair<BrickCoord, Brick>> partial;
    uint64_t openColumns = 0; ///< parity: voxel columns crossed an odd number of times
};

/// A narrow-band distance field: per band brick the voxels nearer than the
/// band and their distances, and (signed fields) the signs.
struct DistanceBricks {
    GridSpec grid;                   ///< the field's grid (the mesh's, padded by the band)
    std::vector<BrickCoord> bricks;  ///< sorted, unique
    std::vector<Brick> near;         ///< per brick: voxels nearer than the band
    std::vector<uint32_t> offsets;   ///< per brick: where its values start in distances and closest
    std::vector<float> distances;    ///< packed, brick by brick in bit order: distances in voxels
    std::vector<int32_t> closest;    ///< packed alike: the closest triangle; empty unless asked
    bool signedField = true;         ///< false: unsigned distances, `signs` empty
    bool closestTriangle = false;    ///< `closest` was asked for (it may still be empty)
    bool winding = false;            ///< signs by winding number (known at every voxel), else by parity
    /// Only a region's bricks (VoxelizeSettings::region): signs beyond the
    /// band come from the parity runs, not from a flood fill of a band cut at the region's sides.
    bool region = false;
    FieldSigns signs;
};

/// A solid: per band brick the voxels inside or on the surface; beyond the
/// band, whole bricks and runs of bricks inside (FieldSigns).
struct SolidBricks {
    GridSpec grid;                   ///< the solid's grid (the mesh's, padded by 2 voxels)
    std::vector<BrickCoord> bricks;  ///< the band: sorted, unique
    FieldSigns signs;                ///< signs.inside holds the surface voxels too
};

} // namespace svo
