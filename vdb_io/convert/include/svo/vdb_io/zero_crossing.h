#pragma once
/// @file zero_crossing.h
/// @brief The voxels where a distance field's grid crosses zero: what a
/// picture of a level set or an unsigned distance field shows, rather than
/// its whole narrow band.
///
/// A signed field (a float or double grid of class GRID_LEVEL_SET, negative
/// inside) crosses zero at the inside voxel of every sign change between face
/// neighbours: an active voxel whose value is below zero with one of its six
/// face neighbours at zero or above (inactive neighbours read as the tree
/// gives them, +/- the background). These are the voxels of OpenVDB's
/// interior mask (tools::sdfInteriorMask: values below zero) that its face
/// erosion removes: a shell one voxel thick that every 6-connected path from
/// outside to inside meets, so the surface drawn has no holes, and only the
/// signs are read, so distances that are not exact do not open it.
///
/// An unsigned field has no sign to change: a float or double grid of class
/// GRID_UNKNOWN whose background is positive and whose active values all lie
/// in [0, background] (svo's "distance" grid, OpenVDB's unsigned fields)
/// crosses zero at its active voxels within half a voxel of the surface,
/// |value| <= voxelSize / 2. Of two face neighbours whose centres lie on both
/// sides of the surface one is that close (the segment between the centres is
/// one voxel long), so for exact distances this set too is met by every
/// 6-connected path across a closed surface.
#include <openvdb/openvdb.h>

#include "svo/vdb_io/vdb_file.h"

namespace svo::vdb {

/// @brief Whether a grid holds distances, and of which kind (see the file comment).
enum class DistanceKind { None, Signed, Unsigned };

/// @brief The kind of distances @a grid holds; None for every other grid.
DistanceKind distanceKind(const openvdb::GridBase& grid);

/// @brief Keeps, of the bricks of @a grid's active voxels (bricksOfGrid,
/// readVdbBricks), the voxels at its zero crossing; bricks left empty are
/// dropped. The grid spec (extent, transform) stays the band's.
/// @param grid   the grid the bricks were made from
/// @param bricks its active voxels as bricks, narrowed in place
/// @return the active voxels the bricks held before; bricks is unchanged for
///         a grid that holds no distances (DistanceKind::None)
uint64_t keepZeroCrossing(const openvdb::GridBase& grid, VdbBricks& bricks);

} // namespace svo::vdb
