#pragma once
/// @file voxelize_stats.h
/// @brief svo::VoxelizeStats: what one voxelization, level set or solid call
/// measured and decided, handed out only when asked.
#include <cstdint>
#include <string>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/voxelization.h"
#include "svo/gl/startup_stats.h"

namespace svo {

/// @brief What one call measured. Kept apart from the result; filled only when asked.
struct VoxelizeStats {
    std::vector<StageTime> stages; ///< GPU (timer queries) and wall milliseconds per stage
    uint64_t voxels = 0, bricks = 0; ///< the result's voxels and bricks
    uint64_t listEntries = 0;      ///< voxel-list entries written, duplicates included
    int overflowRetries = 0;       ///< passes repeated because a GPU buffer was too small
    uint32_t tiles = 1;            ///< boxes the grid was voxelized in to stay within GPU memory (1: all at once)
    uint64_t gpuBytes = 0;         ///< GPU buffer bytes the call used (reused scratch counts at its full size)
    double epsilon = 0;            ///< guard band in voxels
    std::string backend;           ///< "raster", "compute" or "cpu"
    std::string mode;              ///< "conservative" or "thin"; empty for grids and bricks, which are not voxelized
    std::string dilation;          ///< "hardware", "shader", "centroid-push (baseline)"; empty for cpu
    std::string device;            ///< "vendor | renderer | version (EGL device)", or "cpu"
    std::string renderer;          ///< GL renderer string, or "cpu"
    GridSpec grid;                 ///< the local grid the call used
    /// What was asked for but could not be given (colours without vertex
    /// colours), one sentence each. Warnings name no option by its identifier
    /// (LevelSetOptions::exteriorBand, ...), so front ends show them as they
    /// are; a warning about an option would need its identifier kept apart,
    /// as svo::Error keeps it.
    std::vector<std::string> warnings;
    std::string sign;              ///< level sets and solids: the sign method used and why ("parity: closed and ...")
    uint64_t openColumns = 0;      ///< level sets and solids: voxel columns crossed an odd number of times (open mesh)
    uint64_t bandBricks = 0;       ///< level sets and solids: bricks whose distances or signs were computed
    uint64_t windingBricks = 0;    ///< winding signs: bricks beyond the band classified voxel by voxel
    /// Winding signs: the points (voxel centres of those bricks, brick
    /// centres of the box) whose number a walk of the tree summed: all of
    /// them on a GPU; the CPU climbs columns (svo/core/winding_signs.h) and
    /// walks where a climb cannot decide.
    uint64_t windingWalks = 0;
    /// Start-up paid since the previous call returned: the context if this
    /// call created it, and the programs this call made. Kept apart from
    /// `stages`, whose wall times exclude it.
    StartupStats startup;
    double gpuMs() const;          ///< the sum of the stages' GPU times
};

/// @brief Statistics of repeated runs: each stage's median GPU and wall time;
/// the other fields are the last run's.
/// @throw svo::InvalidInput for an empty list
VoxelizeStats medianStats(const std::vector<VoxelizeStats>& runs);

} // namespace svo
