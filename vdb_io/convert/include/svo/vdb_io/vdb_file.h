#pragma once
/// @file vdb_file.h
/// Octrees to and from .vdb files, without OpenVDB in the interface.
#include <iosfwd>
#include <openvdb/openvdb.h>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "svo/core/octree.h"
#include "svo/vdb_io/grid_options.h"

namespace svo::vdb {

/// The grid type that carries the topology.
using Topology = GridOptions::Topology;

/// The text as valid UTF-8, for string metadata (python3-openvdb decodes it
/// and raises UnicodeDecodeError otherwise): well-formed UTF-8 passes
/// unchanged, every other byte becomes \xNN (two upper-case hex digits), as
/// the messages write bytes of a file name. The writers below apply it to
/// the metadata they are given (names and values).
std::string validUtf8(const std::string& text);

/// Which grids (GridOptions), and string metadata stored on every grid
/// (source, backend, renderer, ...).
struct WriteOptions : GridOptions {
    std::map<std::string, std::string> metadata;
};

struct WriteStats {
    double buildMs = 0, writeMs = 0;
    uint64_t leaves = 0, bytes = 0;
};

/// Writes the octree's voxels as a MaskGrid or BoolGrid (and optionally a fog
/// FloatGrid, and its attribute channels as "normal", "triangle_id" and
/// "color" grids) whose transform is voxelSize scaling plus the grid's
/// translation, so the voxels sit exactly over the mesh in world space. Leaves
/// are copied from bricks in parallel and inserted with addLeaf.
///
/// The file appears atomically (atomic_file.h). Throws svo::Error naming the path.
WriteStats writeVdb(const std::string& path, const Octree& octree, const WriteOptions& options);

/// Several octrees of one grid as named MaskGrids in one file (e.g. the
/// missed and extra voxels of a validation), written atomically.
void writeVdbMasks(const std::string& path, const std::vector<std::pair<std::string, Octree>>& grids,
                   const std::map<std::string, std::string>& metadata);

/// Any grids to one .vdb file, each given @a metadata as strings, written
/// atomically. Throws svo::Error naming the path.
WriteStats writeVdbGrids(const std::string& path, const openvdb::GridPtrVec& grids,
                         const std::map<std::string, std::string>& metadata);

/// The active voxels of one grid (`gridName`, or the first grid in name
/// order when empty) as bricks, active tiles expanded. Throws svo::Error when
/// the file has no grids, the grid is missing, or its type or transform is
/// unsupported, and when the file is cut short or damaged: every grid is read
/// and must end where its descriptor says, the last one at the end of the
/// file; the voxel count and bounding box OpenVDB's writer records must match;
/// a mask or bool leaf's two copies of its mask (and its origin) must agree.
/// OpenVDB files carry no checksum: a changed bit that still decodes to a
/// consistent file (a voxel value, a mask bit in a file without the recorded
/// count) cannot be found.
struct VdbBricks {
    std::string gridName, gridType;
    GridSpec grid;
    std::vector<std::pair<uint64_t, Brick>> bricks;
    uint64_t tilesExpanded = 0;
    /// What the bricks do not hold of the grid (valuesBeyondTopology), empty
    /// when its active voxels say everything.
    std::string valuesDropped;
};
VdbBricks readVdbBricks(const std::string& path, const std::string& gridName = {});
/// The same from a stream holding a whole .vdb file (seekable, from its
/// start); `name` stands for it in messages. Active tiles standing for more
/// than `maxTileBricks` bricks are refused (see gridToBricks).
VdbBricks readVdbBricks(std::istream& in, const std::string& name, const std::string& gridName = {},
                        uint64_t maxTileBricks = kMaxTileBricks);

/// Every grid of a .vdb file, or only the one named, read and checked as
/// readVdbBricks reads them, as stored: type, class, transform, metadata and
/// values (a grid that shares another's tree gets that tree). Throws
/// svo::Error naming the path.
openvdb::GridPtrVec readVdbGrids(const std::string& path, const std::string& gridName = {});

/// One grid's bricks (gridToBricks), named with what they drop of it: what
/// readVdbBricks and readNanoVdbBricks give for the grid they pick.
VdbBricks bricksOfGrid(const openvdb::GridBase& grid, const std::string& name,
                       uint64_t maxTileBricks = kMaxTileBricks);

/// What a grid holds beyond which voxels are active, for a message ("the
/// distances of the level set grid 'surface' (Tree_float_5_4_3)"); empty when
/// nothing: a MaskGrid, or a grid that is not a level set whose active
/// values are all true or 1 (svo's own BoolGrid and fog volume).
std::string valuesBeyondTopology(const openvdb::GridBase& grid);

} // namespace svo::vdb
