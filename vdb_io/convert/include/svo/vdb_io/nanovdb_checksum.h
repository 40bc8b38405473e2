#pragma once
/// @file nanovdb_checksum.h
/// @brief NanoVDB's full checksum (nanovdb::ChecksumMode::Full), the same
/// 64 bits nanovdb::updateChecksum stores, computed with zlib's crc32 on all
/// cores: the CRC-32 of the grid, tree and root past the checksum field, and
/// the CRC-32 of the per-node CRC-32s (upper, lower, leaf nodes in buffer
/// order). NanoVDB's own CRC reads a byte at a time on one thread per node
/// list, which was most of a layout's time (bench/results/cpu-2core-llvmpipe/nanovdb_layout.md).
#include <nanovdb/NanoVDB.h>

namespace svo::vdb {

/// @brief Sets @a grid's checksum to its full checksum, as
/// nanovdb::updateChecksum(grid, ChecksumMode::Full) would.
/// @param grid a breadth-first grid (every grid svo lays out or NanoVDB converts)
template <typename BuildT>
void updateFullChecksum(nanovdb::NanoGrid<BuildT>& grid);

} // namespace svo::vdb
