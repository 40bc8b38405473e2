#pragma once
/// @file library_call.h
/// What a subcommand needs to call the library: a Voxelizer on the chosen
/// device, the options the arguments ask for, its progress shown on stderr,
/// and the call's statistics kept for printing.
#include <string>

#include "cli_options.h"
#include "progress.h"
#include "svo/voxelizer.h"

namespace svo::app {

struct LibraryCall {
    LibraryCall(const BackendArgs& args, std::string progressLabel)
        : voxelizer(args.device), options(args.voxelizeOptions()), progress(std::move(progressLabel))
    {
        options.interrupter = &progress;
        options.stats = &stats;
    }
    LibraryCall(const LibraryCall&) = delete;
    LibraryCall& operator=(const LibraryCall&) = delete;

    /// @brief The octree of an input (loadOctree: a mesh voxelized, or a
    /// .vdb, .nvdb or .svo read), with the mesh's warnings and the call's printed.
    LoadedOctree load(const std::string& input, const std::string& gridName, const GridRequest& request)
    {
        LoadedOctree loaded = loadOctree(voxelizer, input, gridName, request, options);
        if (loaded.mesh) printWarnings(loaded.mesh->warnings);
        printWarnings(stats.warnings);
        return loaded;
    }

    Voxelizer voxelizer;
    VoxelizeOptions options; ///< points at `progress` and `stats` below
    VoxelizeStats stats;
    ProgressInterrupter progress;
};

} // namespace svo::app
