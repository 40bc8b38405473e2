#pragma once
/// @file load_octree.h
/// @brief Any input as an octree: a .svo file as it is, one grid of a .vdb or
/// .nvdb file (its active voxels built into an octree by a Voxelizer), or a
/// mesh file (voxelized by a Voxelizer on the requested grid).
/// Errors are svo::Error naming the path.
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

/// What loadOctree read.
struct LoadedOctree {
    Octree octree;
    enum class Kind { Svo, Vdb, Mesh } kind = Kind::Svo;
    std::string gridName, gridType; ///< .vdb or .nvdb input: the grid read
    uint64_t tilesExpanded = 0;     ///< .vdb input: active tiles turned into bricks
    std::string valuesDropped;      ///< .vdb input: what the octree does not hold of the grid (vdb::valuesBeyondTopology)
    std::optional<TriangleMesh> mesh; ///< mesh input: the mesh
    std::vector<StageTime> stages;  ///< reading, building or voxelizing
};

/// Reads any input as an octree. @a gridName picks a .vdb grid (empty: the
/// first); @a grid says how to voxelize a mesh. The Voxelizer (with
/// @a options: backend, interrupter, statistics) builds .vdb and mesh inputs.
LoadedOctree loadOctree(Voxelizer& voxelizer, const std::string& path, const std::string& gridName,
                        const GridRequest& grid, const VoxelizeOptions& options);

} // namespace svo
