#pragma once
/// @file octree_input.h
/// Any input the subcommands take, as an octree: a .svo file, a grid of a
/// .vdb file (built into an octree on the GPU, or on the CPU with
/// --backend cpu), or a mesh (voxelized first).
#include <optional>
#include <string>
#include <vector>

#include "mesh_voxelizer.h"
#include "svo/core/octree.h"

namespace svo::app {

struct InputOptions {
    std::string gridName;   ///< .vdb: which grid (default: the first)
    GridRequest gridRequest; ///< meshes: the grid to voxelize on
    BackendSettings backend;
};

struct LoadedOctree {
    Octree octree;
    std::string kind;               ///< "svo", "vdb" or "mesh"
    std::string description;        ///< one line about where it came from
    std::vector<StageTime> stages;  ///< how long it took
    std::optional<TriangleMesh> mesh; ///< the source, when the input was a mesh
};

LoadedOctree loadOctree(const std::string& path, const InputOptions& options);

} // namespace svo::app
