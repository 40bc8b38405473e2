#pragma once
/// @file octree_files.h
/// @brief Octrees to files, the format chosen by the extension: .vdb
/// (OpenVDB grids, as GridOptions asks), .svo (svo's own octree file,
/// octree_file.h) or .nvdb (the same grids as .vdb, in NanoVDB form).
/// Reading any input as an octree needs a Voxelizer: svo/load_octree.h.
/// Every file is written to a temporary in the same folder and renamed, so a
/// failed write never leaves a partial file. Errors name the path.
#include <map>
#include <string>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/octree.h"
#include "svo/core/voxelization.h"
#include "svo/vdb_io/grid_options.h"

namespace svo {

/// @brief The output file formats.
enum class OutputFormat { Vdb, Svo, NanoVdb };

/// @brief The format an output path names: .vdb, .svo or .nvdb.
/// @throw svo::IoError for another extension
OutputFormat outputFormat(const std::string& path);
/// @brief Checks the format and whether the path can be written, before any heavy work.
/// @throw svo::IoError for another extension or a path that cannot be
///        written (checkWritable)
void checkOutputPath(const std::string& path);

/// @brief What writeOctree took and made.
struct WriteReport {
    std::vector<StageTime> stages; ///< building the grids, writing the file
    uint64_t bytes = 0;            ///< file size
    uint64_t leaves = 0;           ///< leaves of the topology grid (.vdb, .nvdb)
    OutputFormat format = OutputFormat::Vdb; ///< the format written
    /// A .vdb output's triangle indices, in a file of their own
    /// (vdb::triangleSidecarPath) that python3-openvdb need not open; empty
    /// when the octree has none.
    std::string sidecar;
    uint64_t sidecarBytes = 0; ///< its size
};

/// @brief Writes the octree as the extension of @a path says. GridOptions
/// apply to .vdb and .nvdb; a .svo file holds the octree itself (its
/// topology is not a grid type). A .vdb output holds only grids that
/// python3-openvdb reads: the triangle indices (Int32Grid "triangle_id") go
/// to vdb::triangleSidecarPath(@a path) beside it (svo/vdb_io/reader_grids.h).
/// @param metadata stored as strings on every .vdb grid (a NanoVDB grid has no place for them)
/// @throw svo::IoError for another extension or a file that cannot be written
/// @throw svo::InvalidInput for a fog grid asked of a .svo file, or a grid
///        whose transform OpenVDB cannot hold (checkVdbGrid)
WriteReport writeOctree(const std::string& path, const Octree& octree, const GridOptions& grids = {},
                        const std::map<std::string, std::string>& metadata = {});

} // namespace svo
