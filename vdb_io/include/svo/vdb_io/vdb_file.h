#pragma once
/// @file vdb_file.h
/// Voxelizations to and from .vdb files, without OpenVDB in the interface.
#include <map>
#include <string>

#include "svo/core/voxelization.h"

namespace svo::vdb {

struct WriteOptions {
    std::string gridName = "surface";
    bool fog = false; ///< also write a fog-volume FloatGrid "density" (1 inside voxels)
    /// String metadata stored on every grid (source, backend, renderer, ...).
    std::map<std::string, std::string> metadata;
};

struct WriteStats {
    double buildMs = 0, writeMs = 0;
    uint64_t leaves = 0, bytes = 0;
};

/// Writes the topology as a MaskGrid (and optionally a fog FloatGrid) whose
/// transform is voxelSize scaling plus the grid's translation, so the voxels
/// sit exactly over the mesh in world space. Leaves are built from brick
/// masks in parallel and inserted with addLeaf.
///
/// The file appears atomically: it is written to a temporary file in the same
/// folder and renamed, so a failure leaves any earlier file untouched and no
/// partial one. Throws svo::Error naming the path on failure.
WriteStats writeVdb(const std::string& path, const Voxelization& voxels, const WriteOptions& options);

/// Fails early, before any heavy work, if `path` cannot be created: its folder
/// is missing or not writable, or it names a folder.
void checkWritable(const std::string& path);

} // namespace svo::vdb
