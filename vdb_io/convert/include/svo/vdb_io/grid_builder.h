#pragma once
/// @file grid_builder.h
/// @brief Octree bricks <-> OpenVDB leaves, by copying 512-bit masks.
///
/// Octree -> grid: traversal gives every brick's origin; each brick becomes one
/// LeafNode<T,3> whose value mask is the brick's 8 words (same bit order).
/// Leaves are made in parallel (TBB) and inserted with addLeaf, so the cost is
/// O(bricks) with no per-voxel tree descent.
///
/// Grid -> bricks: every leaf's value mask is a brick; every active tile is
/// expanded into full bricks. Any grid type in GridTypes below is accepted.
#include <openvdb/openvdb.h>
#include <utility>
#include <vector>

#include "svo/core/octree.h"
#include "svo/vdb_io/grid_options.h"

namespace svo::vdb {

/// @brief The linear transform of a grid: voxelSize scaling, then its translation.
/// @throw svo::InvalidInput when OpenVDB cannot hold it (checkVdbGrid)
openvdb::math::Transform::Ptr makeTransform(const GridSpec& grid);

/// @brief The octree's voxels as an unnamed MaskGrid on its own lattice (makeTransform).
/// @throw svo::InvalidInput as makeTransform
openvdb::MaskGrid::Ptr buildMaskGrid(const Octree& octree);
/// @brief The octree's voxels as a BoolGrid, true on them, on its own lattice.
/// @throw svo::InvalidInput as makeTransform
openvdb::BoolGrid::Ptr buildBoolGrid(const Octree& octree);
/// @brief Fog volume: 1 on every voxel, background 0, class GRID_FOG_VOLUME.
/// @throw svo::InvalidInput as makeTransform
openvdb::FloatGrid::Ptr buildFogGrid(const Octree& octree);

/// @brief The octree's attribute channels on its voxels: Vec3SGrid "normal",
/// Int32Grid "triangle_id" and Vec3SGrid "color", each only when present.
/// @throw svo::InvalidInput as makeTransform
openvdb::GridPtrVec buildAttributeGrids(const Octree& octree);

/// @brief An octree's voxels as grids, in this order: the topology grid (Mask or
/// Bool, named grids.name), the fog grid "density" when asked, then the
/// attribute grids when asked and present. Their transform is @a xform, or
/// the octree's own lattice (makeTransform) when it is null. Each carries
/// the octree's provenance (tagProvenance).
/// @throw svo::InvalidInput as makeTransform, when @a xform is null
openvdb::GridPtrVec octreeToGrids(const Octree& octree, const GridOptions& grids = {},
                                  openvdb::math::Transform::ConstPtr xform = nullptr);

/// @brief Writes what made a result into a grid's metadata: "svo:backend",
/// "svo:mode" and "svo:renderer", each only when known.
void tagProvenance(openvdb::GridBase& grid, const Provenance& madeBy);

/// @brief Grid types whose active voxels can become an octree.
using GridTypes = openvdb::TypeList<openvdb::MaskGrid, openvdb::BoolGrid, openvdb::FloatGrid, openvdb::DoubleGrid,
                                    openvdb::Int32Grid, openvdb::Int64Grid, openvdb::Vec3SGrid, openvdb::Vec3DGrid,
                                    openvdb::Vec3IGrid>;

/// @brief A grid's active voxels as bricks, on a GridSpec that holds them:
/// the anchor is the bounding box's minimum rounded down to a multiple of 8.
struct GridBricks {
    GridSpec grid;                                  ///< the grid's lattice, anchor and dims
    std::vector<std::pair<uint64_t, Brick>> bricks; ///< (brick-origin key, mask), local coordinates
    uint64_t tilesExpanded = 0;                     ///< active tiles turned into bricks
};

/// @brief A grid's active voxels as bricks, active tiles expanded.
/// @param grid          any type of GridTypes
/// @param name          prefixes error messages (the file, or the caller's name for the grid)
/// @param maxTileBricks the most bricks active tiles may stand for, counted
///        before anything is allocated
/// @throw svo::InvalidInput for an unsupported type, a non-linear or
///        non-uniform transform, a translation that is not a whole number of
///        voxels, an extent beyond kMaxGridDim, or tiles beyond @a maxTileBricks
GridBricks gridToBricks(const openvdb::GridBase& grid, const std::string& name,
                        uint64_t maxTileBricks = kMaxTileBricks);

} // namespace svo::vdb

namespace svo {
using vdb::octreeToGrids; // part of the public API (svo/svo.h)
} // namespace svo
