#pragma once
/// @file nanovdb_input.h
/// @brief .nvdb files read back as OpenVDB grids, checked before use.
///
/// NanoVDB's own reader (nanovdb/util/IO.h) trusts every size in the file.
/// This one reads the whole file into memory and walks its segments itself:
/// every header, grid name and grid must lie inside the file, the file must
/// end where its last grid does, and each segment's per-grid record must
/// agree with the grid it describes (size, type, class, name, voxel count,
/// bounding boxes, node counts). Inside each grid, the tree's node regions,
/// every child offset (one node reached once, at a node boundary of the next
/// level, with the origin its parent's slot says), the root table and the
/// grid name are checked against the grid's size before NanoVDB reads them;
/// then NanoVDB's validator (checksum included) runs, and
/// nanovdb::nanoToOpenVDB makes the OpenVDB grid. Grids compressed with
/// NanoVDB's codecs are decoded first (Zip always, Blosc where svo was built
/// with libblosc), each block's size checked against the file. Only
/// the grid types svo writes are read: float, double, int32, int64, Vec3f, Vec3d,
/// bool and mask. Errors are one line naming the file
/// ("x.nvdb: truncated or damaged: ...").
///
/// A NanoVDB checksum covers the grid's header and root only, or every node
/// ("full", as svo writes it), or nothing: a changed value in a grid without
/// a full checksum cannot be found.
#include <openvdb/openvdb.h>
#include <string>

#include "svo/vdb_io/vdb_file.h"

namespace svo::vdb {

/// @brief Every grid of the .nvdb file, or only the one named, as OpenVDB
/// grids: type, class, name, transform and values.
/// @param gridName the grid to read; empty for all
/// @throw svo::IoError naming the file when it is missing, unreadable, not
///        NanoVDB, compressed with a codec this build lacks, truncated or damaged, or holds a grid type svo
///        does not read
/// @throw svo::InvalidInput when no grid is named @a gridName
openvdb::GridPtrVec readNanoVdbGrids(const std::string& path, const std::string& gridName = {});
/// @brief The same from a whole file's bytes.
/// @param name stands for the file in messages
/// @throw as readNanoVdbGrids
openvdb::GridPtrVec readNanoVdbGridsFromBytes(const std::string& bytes, const std::string& name,
                                              const std::string& gridName = {});

/// @brief One grid's active voxels as bricks, as readVdbBricks gives them
/// from a .vdb.
/// @param gridName the grid; empty for the file's mainGrid() (vdb_file.h)
/// @throw as readNanoVdbGrids, and svo::InvalidInput as gridToBricks (a
///        transform or extent svo cannot take, too many tile bricks)
VdbBricks readNanoVdbBricks(const std::string& path, const std::string& gridName = {});

} // namespace svo::vdb
