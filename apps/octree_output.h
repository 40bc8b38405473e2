#pragma once
/// @file octree_output.h
/// What the subcommands share around octree files: grid options, and writing
/// an octree to .vdb or .svo chosen by the output's extension.
#include <map>
#include <string>
#include <vector>

#include "svo/core/octree.h"
#include "svo/core/voxelization.h"

namespace CLI {
class App;
}

namespace svo::app {

/// -r/--resolution and --voxel-size (mutually exclusive).
void addGridOptions(CLI::App& cmd, int64_t& resolution, double& voxelSize);
/// The request those options make; resolution 256 when neither is given.
GridRequest gridRequest(const CLI::App& cmd, int64_t resolution, double voxelSize);

struct OutputSettings {
    std::string topology = "mask"; ///< mask | bool
    bool fog = false;
};
/// --topology and --fog.
void addOutputOptions(CLI::App& cmd, OutputSettings& settings);

/// "vdb" or "svo" from the extension; svo::Error for anything else.
std::string outputKind(const std::string& path);
/// Kind and writability, checked before heavy work.
void checkOutputPath(const std::string& path);

struct OutputReport {
    std::vector<StageTime> stages; ///< build and write times
    std::string description;       ///< "out.vdb (1.2 MB, 345 leaves)"
};
OutputReport writeOctreeOutput(const std::string& path, const Octree& octree, const OutputSettings& settings,
                               const std::map<std::string, std::string>& metadata);

/// Prints levels, nodes per level, bricks, bytes, bytes per voxel, fill ratio.
void printOctreeSummary(const Octree& octree);

} // namespace svo::app
