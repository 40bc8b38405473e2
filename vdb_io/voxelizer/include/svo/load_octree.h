#pragma once
/// @file load_octree.h
/// @brief Any input as an octree: a .svo file as it is, one grid of a .vdb or
/// .nvdb file (its active voxels built into an octree by a Voxelizer), or a
/// mesh file (voxelized by a Voxelizer on the requested grid).
/// Errors name the path.
#include <optional>
#include <string>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/voxelization.h"

namespace svo {

class Voxelizer;
struct VoxelizeOptions;

/// @brief What loadOctree read.
struct LoadedOctree {
    Octree octree;                                       ///< the input as an octree
    enum class Kind { Svo, Vdb, Mesh } kind = Kind::Svo; ///< what the input was (Vdb: .vdb or .nvdb)
    std::string gridName, gridType; ///< .vdb or .nvdb input: the grid read
    uint64_t tilesExpanded = 0;     ///< .vdb input: active tiles turned into bricks
    std::string valuesDropped;      ///< .vdb input: what the octree does not hold of the grid (vdb::valuesBeyondTopology)
    /// .vdb or .nvdb input loaded with FieldVoxels::ZeroCrossing: the
    /// distance field's active voxels the zero crossing was taken from (0:
    /// none was taken, the octree holds the grid's active voxels).
    uint64_t fieldVoxels = 0;
    std::optional<TriangleMesh> mesh; ///< mesh input: the mesh
    std::vector<StageTime> stages;  ///< reading, building or voxelizing
};

/// @brief What loadOctree keeps of a .vdb or .nvdb grid that holds distances
/// (a level set, an unsigned distance field: svo/vdb_io/zero_crossing.h).
enum class FieldVoxels {
    Active,      ///< its active voxels, the whole narrow band
    ZeroCrossing ///< the voxels at its zero crossing (what a picture shows)
};

/// @brief Reads any input as an octree, the kind chosen by the extension.
/// @param voxelizer builds .vdb, .nvdb and mesh inputs, with @a options
///        (backend, interrupter, statistics)
/// @param gridName  picks a .vdb or .nvdb grid (empty: the file's vdb::mainGrid)
/// @param grid      how to voxelize a mesh
/// @param field     what to keep of a grid of distances (other grids: their active voxels)
/// @throw svo::IoError for a file that is missing, unreadable or damaged
/// @throw svo::InvalidInput for a missing grid, a grid or mesh svo cannot
///        take, or a bad grid request
/// @throw svo::DeviceError, svo::OutOfMemory, svo::Unsupported,
///        svo::Interrupted as the Voxelizer's calls
LoadedOctree loadOctree(Voxelizer& voxelizer, const std::string& path, const std::string& gridName,
                        const GridRequest& grid, const VoxelizeOptions& options,
                        FieldVoxels field = FieldVoxels::Active);

} // namespace svo
