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
/// nanovdb::nanoToOpenVDB makes the OpenVDB grid. Only uncompressed files
/// are read (svo is built without NanoVDB's zip and Blosc codecs), and only
/// the grid types svo writes: float, double, int32, int64, Vec3f, Vec3d,
/// bool and mask. Errors are one-line svo::Error naming the file
/// ("x.nvdb: truncated or damaged: ...").
///
/// A NanoVDB checksum covers the grid's header and root only, or every node
/// ("full", as svo writes it), or nothing: a changed value in a grid without
/// a full checksum cannot be found.
#include <openvdb/openvdb.h>
#include <string>

#include "svo/vdb_io/vdb_file.h"

namespace svo::vdb {

/// Every grid of the .nvdb file (empty @a gridName), or only the one named,
/// as OpenVDB grids: type, class, name, transform and values.
openvdb::GridPtrVec readNanoVdbGrids(const std::string& path, const std::string& gridName = {});
/// The same from a whole file's bytes; @a name stands for it in messages.
openvdb::GridPtrVec readNanoVdbGridsFromBytes(const std::string& bytes, const std::string& name,
                                              const std::string& gridName = {});

/// One grid's active voxels as bricks (@a gridName, or the first grid in name
/// order), as readVdbBricks gives them from a .vdb.
VdbBricks readNanoVdbBricks(const std::string& path, const std::string& gridName = {});

} // namespace svo::vdb
