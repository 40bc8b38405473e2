#pragma once
/// @file parity_scan.h
/// Inside/outside from parity crossings: the host half of svo's solids and
/// level sets (the GPU marks the crossings, svo/gl/distance_field.h).
///
/// Input: a set of bricks and, per brick, the voxels where an odd number of
/// the mesh's crossings of that voxel's z column lie just below the voxel
/// centre. A voxel centre is inside when the crossings below it in its column
/// are odd in number. Every crossing lies next to the surface, so its voxel is
/// in a brick of the band; the bricks of a column between two band bricks hold
/// no surface and are wholly inside or wholly outside, as the parity leaving
/// the lower one says.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/octree.h"

namespace svo {

/// A run of whole bricks between two band bricks of one brick column that is
/// inside for the voxel columns in `columns` (bit x * 8 + y).
struct InsideRun {
    std::array<uint32_t, 3> first; ///< brick coordinates of the lowest brick of the run
    uint32_t bricks = 0;           ///< bricks in the run, going up in z
    uint64_t columns = 0;          ///< voxel columns of the brick column that are inside
};

struct ParityScan {
    std::vector<Brick> inside;      ///< per input brick: the voxels whose centres are inside
    std::vector<InsideRun> runs;    ///< inside runs between the bricks
    /// Voxel columns with an odd number of crossings in all: the mesh is not
    /// closed there, and the columns above its last crossing count as outside.
    uint64_t openColumns = 0;
};

/// @param bricks    brick coordinates (local voxel coordinate / 8), unique
/// @param crossings per brick, the odd-crossing voxels (bit order of Brick)
/// @throw svo::InvalidInput when the two sizes differ.
ParityScan scanParity(const std::vector<std::array<uint32_t, 3>>& bricks, const std::vector<Brick>& crossings);

} // namespace svo
