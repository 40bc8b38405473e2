#pragma once
/// @file octree_files.h
/// @brief Octrees to and from files, the format chosen by the extension.
///
/// Output: .vdb (OpenVDB grids, as GridOptions asks), .svo (svo's own octree
/// file, octree_file.h) or .nvdb (the same grids as .vdb, in NanoVDB form).
/// Input: .svo, .vdb or .nvdb (one grid's active voxels, built into an octree
/// by a Voxelizer) or a mesh file (voxelized by a Voxelizer on the requested grid).
/// Every file is written to a temporary in the same folder and renamed, so a
/// failed write never leaves a partial file. Errors are svo::Error naming the path.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/voxelization.h"
#include "svo/vdb_io/grid_options.h"

namespace svo {

class Voxelizer;
struct VoxelizeOptions;

enum class OutputFormat { Vdb, Svo, NanoVdb };

/// The format an output path names. @throw svo::IoError for another extension.
OutputFormat outputFormat(const std::string& path);
/// The format and whether the path can be written, before any heavy work.
void checkOutputPath(const std::string& path);

struct WriteReport {
    std::vector<StageTime> stages; ///< building the grids, writing the file
    uint64_t bytes = 0;            ///< file size
    uint64_t leaves = 0;           ///< leaves of the topology grid (.vdb, .nvdb)
    OutputFormat format = OutputFormat::Vdb;
};

/// Writes the octree as the extension of @a path says. GridOptions apply to
/// .vdb and .nvdb; a .svo file holds the octree itself (its topology is not
/// a grid type), and a fog grid asked for there is refused. @a metadata is stored as strings on every .vdb grid.
WriteReport writeOctree(const std::string& path, const Octree& octree, const GridOptions& grids = {},
                        const std::map<std::string, std::string>& metadata = {});

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
