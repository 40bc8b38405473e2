#pragma once
/// @file mesh_voxelizer.h
/// The GPU/CPU backend choice the subcommands share: a mesh and a grid in, an
/// octree out, with the words that describe where it ran.
#include <string>
#include <vector>

#include "svo/core/mesh.h"
#include "svo/gl/octree_builder.h"

namespace CLI {
class App;
}

namespace svo::app {

struct BackendSettings {
    std::string backend = "raster"; ///< raster | cpu
    std::string conservative = "auto";
    std::string device;
    bool glDebug = false;
    int repeat = 1; ///< >1: one warm-up, then per-stage medians
    uint32_t attributes = 0; ///< AttributeChannel bits to compute
};

/// --attributes normal,triangle,color on a subcommand.
void addAttributeOption(CLI::App& cmd, BackendSettings& settings);

/// Adds --backend, --conservative, --device, --gl-debug to a subcommand.
void addBackendOptions(CLI::App& cmd, BackendSettings& settings);

struct MeshVoxelization {
    gl::OctreeVoxelization result;
    std::string backendLine; ///< e.g. "raster, hardware dilation, on NVIDIA ..."
    std::string renderer;    ///< GL renderer, or "cpu"
};

MeshVoxelization voxelizeMesh(const TriangleMesh& mesh, const GridSpec& grid, const BackendSettings& settings);

/// 1234567 -> "1,234,567"
std::string thousands(uint64_t n);

/// `text` as the inside of a JSON string: quotes, backslashes and control
/// characters escaped.
std::string jsonEscape(const std::string& text);

/// Throws svo::Error when two output paths name the same file.
void checkDistinctOutputs(const std::vector<std::string>& paths);

} // namespace svo::app
