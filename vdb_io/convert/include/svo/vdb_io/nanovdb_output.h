#pragma once
/// @file nanovdb_output.h
/// @brief OpenVDB grids as NanoVDB grids, for GPU renderers that read NanoVDB.
///
/// Method: NanoVDB's own converter (nanovdb::openToNanoVDB) with its default
/// statistics and a full checksum (every node, which svo's reader checks). Supported: MaskGrid, BoolGrid, FloatGrid,
/// DoubleGrid, Int32Grid, Int64Grid, Vec3SGrid, Vec3DGrid: every grid svo writes.
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/HostBuffer.h>
#include <openvdb/openvdb.h>

#include <string>

#include "svo/vdb_io/grid_options.h" // NanoCodec

namespace svo::vdb {

/// @brief One grid in NanoVDB form (name and transform kept).
/// @throw svo::InvalidInput for a null grid
/// @throw svo::Unsupported for a grid type NanoVDB cannot hold
nanovdb::GridHandle<nanovdb::HostBuffer> toNanoVdb(const openvdb::GridBase::Ptr& grid);

/// @brief Writes the grids to one .nvdb file, atomically (a temporary file
/// renamed into place), as writeNanoVdb in nanovdb_file.h.
/// @param codec NanoVDB's compression of each grid
/// @return the file's size in bytes
/// @throw svo::IoError naming the path when it cannot be written
/// @throw svo::Unsupported as toNanoVdb, or for a codec this build lacks
uint64_t writeNanoVdb(const std::string& path, const openvdb::GridPtrVec& grids, NanoCodec codec = NanoCodec::None);

} // namespace svo::vdb
