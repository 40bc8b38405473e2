#pragma once
/// @file vdb_file.h
/// @brief Octrees to and from .vdb files, without OpenVDB in the interface.
#include <iosfwd>
#include <openvdb/openvdb.h>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "svo/core/octree.h"
#include "svo/vdb_io/grid_options.h"

namespace svo::vdb {

/// @brief The grid type that carries the topology.
using Topology = GridOptions::Topology;

/// @brief The text as valid UTF-8, for string metadata (python3-openvdb decodes it
/// and raises UnicodeDecodeError otherwise): well-formed UTF-8 passes
/// unchanged, every other byte becomes \xNN (two upper-case hex digits), as
/// the messages write bytes of a file name. The writers below apply it to
/// the metadata they are given (names and values).
std::string validUtf8(const std::string& text);

/// @brief Which grids (GridOptions), and string metadata stored on every grid.
struct WriteOptions : GridOptions {
    std::map<std::string, std::string> metadata; ///< name -> value (source, backend, renderer, ...)
    /// When set, the triangle indices (Int32Grid "triangle_id") go to this
    /// file instead, which python3-openvdb cannot read (reader_grids.h).
    std::string triangleSidecar;
};

/// @brief What a write took and made.
struct WriteStats {
    double buildMs = 0, writeMs = 0; ///< wall ms building the grids, writing the file
    uint64_t leaves = 0, bytes = 0;  ///< leaves (writeVdb: of the topology grid; writeVdbGrids: of all grids); the file's size
    uint64_t sidecarBytes = 0;       ///< the size of WriteOptions::triangleSidecar, when written
};

/// @brief Writes the octree's voxels as a MaskGrid or BoolGrid (and optionally a fog
/// FloatGrid, and its attribute channels as "normal", "triangle_id" and
/// "color" grids) whose transform is voxelSize scaling plus the grid's
/// translation, so the voxels sit exactly over the mesh in world space. Leaves
/// are copied from bricks in parallel and inserted with addLeaf.
///
/// The file appears atomically (atomic_file.h), as does the triangle
/// sidecar when WriteOptions::triangleSidecar asks for one and the octree
/// has triangle indices.
/// @throw svo::IoError naming the path when it cannot be written
/// @throw svo::InvalidInput for a grid whose transform OpenVDB cannot hold
///        (checkVdbGrid)
WriteStats writeVdb(const std::string& path, const Octree& octree, const WriteOptions& options);

/// @brief Any grids to one .vdb file, each given @a metadata as strings,
/// written atomically.
/// @throw svo::IoError naming the path when it cannot be written
WriteStats writeVdbGrids(const std::string& path, const openvdb::GridPtrVec& grids,
                         const std::map<std::string, std::string>& metadata);

/// @brief One grid's active voxels as bricks (readVdbBricks, readNanoVdbBricks).
struct VdbBricks {
    std::string gridName, gridType; ///< the grid read, and its type (e.g. "Tree_float_5_4_3")
    GridSpec grid;                  ///< a grid that holds the bricks, on the file's lattice
    std::vector<std::pair<uint64_t, Brick>> bricks; ///< (brick-origin key, mask), local coordinates
    uint64_t tilesExpanded = 0;     ///< active tiles turned into bricks
    /// What the bricks do not hold of the grid (valuesBeyondTopology), empty
    /// when its active voxels say everything.
    std::string valuesDropped;
};
/// @brief The grid a file stands for when no name picks one: its first level
/// set in name order, else its first grid of voxels (bool, mask, float or
/// double: a surface, solid, fog or unsigned distance field), else its first
/// grid. Per-voxel channels (normal, color, triangle_id, closest_triangle)
/// come last, though they sort before the grid they annotate. Reads the
/// grids' types and classes only, no values.
/// @param grids a file's grids, at least one
/// @return one of @a grids
openvdb::GridBase::Ptr mainGrid(const openvdb::GridPtrVec& grids);

/// @brief The active voxels of one grid of a .vdb file as bricks, active
/// tiles expanded.
///
/// The file is checked as it is read: every grid is read and must end where
/// its descriptor says, the last one at the end of the file; the voxel count
/// and bounding box OpenVDB's writer records must match; a mask or bool
/// leaf's two copies of its mask (and its origin) must agree. OpenVDB files
/// carry no checksum: a changed bit that still decodes to a consistent file
/// (a voxel value, a mask bit in a file without the recorded count) cannot
/// be found.
/// @param gridName the grid; empty for the file's mainGrid()
/// @throw svo::IoError naming the file when it is missing or unreadable, has
///        no grids, or is cut short or damaged
/// @throw svo::InvalidInput when no grid is named @a gridName, or the grid's
///        type or transform is one svo does not read (gridToBricks)
VdbBricks readVdbBricks(const std::string& path, const std::string& gridName = {});
/// @brief The same from a stream holding a whole .vdb file (seekable, from its start).
/// @param name          stands for the file in messages
/// @param maxTileBricks the most bricks active tiles may stand for (see gridToBricks)
/// @throw as readVdbBricks above
VdbBricks readVdbBricks(std::istream& in, const std::string& name, const std::string& gridName = {},
                        uint64_t maxTileBricks = kMaxTileBricks);

/// @brief Every grid of a .vdb file, or only the one named, read and checked
/// as readVdbBricks reads them, as stored: type, class, transform, metadata
/// and values (a grid that shares another's tree gets that tree).
/// @param gridName the grid to read; empty for all
/// @throw svo::IoError naming the path when it is missing, unreadable, cut
///        short or damaged, or holds no grids
/// @throw svo::InvalidInput when no grid is named @a gridName
openvdb::GridPtrVec readVdbGrids(const std::string& path, const std::string& gridName = {});

/// @brief One grid's bricks (gridToBricks), named with what they drop of it:
/// what readVdbBricks and readNanoVdbBricks give for the grid they pick.
/// @param name prefixes error messages (the file)
/// @throw svo::InvalidInput as gridToBricks
VdbBricks bricksOfGrid(const openvdb::GridBase& grid, const std::string& name,
                       uint64_t maxTileBricks = kMaxTileBricks);

/// @brief What a grid holds beyond which voxels are active, for a message
/// ("the distances of the level set grid 'surface' (Tree_float_5_4_3)").
/// @return empty when nothing: a MaskGrid, or a grid that is not a level set
///         whose active values are all true or 1 (svo's own BoolGrid and fog
///         volume)
std::string valuesBeyondTopology(const openvdb::GridBase& grid);

} // namespace svo::vdb
