#pragma once
/// @file voxelization.h
/// @brief A voxel set as sorted keys, and the report of what a run measured, which
/// a call fills only when asked (its last parameter, `RunStats* report`).
#include <cstdint>
#include <string>
#include <vector>

#include "svo/core/grid.h"

namespace svo {

/// @brief One timed stage of a run.
struct StageTime {
    std::string name;    ///< e.g. "voxelize", "octree build (cpu)"
    double gpuMs = -1.0; ///< GPU milliseconds (timer queries); < 0 when the stage ran on the CPU only
    double wallMs = 0.0; ///< wall milliseconds
};

/// @brief What a run measured, whatever it produced: the report a call fills
/// when given one, apart from its result.
struct RunStats {
    std::vector<StageTime> stages; ///< in the order they ran
    uint64_t listEntries = 0; ///< voxel-list entries written, duplicates included
    int overflowRetries = 0;  ///< extra passes because a GPU buffer (list, nodes, bricks) overflowed
    uint64_t gpuBytes = 0;    ///< peak GPU buffer bytes allocated
    uint32_t tiles = 1;       ///< boxes the grid was voxelized in, to stay within GPU memory (1: the whole grid at once)
};

/// @brief A voxel set as sorted keys: the CPU reference's output, and the GPU's when
/// asked for keys rather than an octree.
struct Voxelization {
    GridSpec grid; ///< the grid the keys are local to
    /// Sorted, unique voxel keys (svo/core/voxel_key.h), local coordinates.
    std::vector<uint64_t> keys;
};

/// @brief Sorts and de-duplicates keys in place, in parallel.
void sortUniqueKeys(std::vector<uint64_t>& keys);

} // namespace svo
