#pragma once
/// @file nanovdb_file.h
/// @brief NanoVDB grids (svo/vdb_io/nanovdb_grids.h) written to a .nvdb file
/// in NanoVDB's file format, with NanoVDB's codecs.
#include <string>
#include <vector>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/HostBuffer.h>

#include "svo/vdb_io/grid_options.h" // NanoCodec

namespace svo::vdb {

/// @brief Whether this build of svo writes @a codec (Zip always; Blosc where
/// libblosc was found at build time).
bool nanoCodecAvailable(NanoCodec codec);

/// @brief Writes NanoVDB grids to one .nvdb file in NanoVDB's file format,
/// atomically (a temporary file renamed into place), with no OpenVDB tree.
/// @param codec NanoVDB's compression of each grid (svo's own reader,
///        nanovdb_input.h, reads every codec this build writes)
/// @return the file's size in bytes
/// @throw svo::IoError naming the path when it cannot be written
/// @throw svo::Unsupported for a codec this build lacks (nanoCodecAvailable)
uint64_t writeNanoVdb(const std::string& path, const std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>>& handles,
                      NanoCodec codec = NanoCodec::None);

} // namespace svo::vdb
