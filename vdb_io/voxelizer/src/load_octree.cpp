#include "svo/load_octree.h"

#include <chrono>
#include <filesystem>

#include "svo/core/mesh_io.h"
#include "svo/core/octree_file.h"
#include "svo/vdb_io/nanovdb_input.h"
#include "svo/vdb_io/vdb_file.h"
#include "svo/voxelizer.h"

namespace svo {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

} // namespace

LoadedOctree loadOctree(Voxelizer& voxelizer, const std::string& path, const std::string& gridName,
                        const GridRequest& request, const VoxelizeOptions& options)
{
    LoadedOctree out;
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".svo") {
        const auto t0 = Clock::now();
        out.octree = readOctreeFile(path);
        out.kind = LoadedOctree::Kind::Svo;
        out.stages.push_back({"svo read", -1, msSince(t0)});
        return out;
    }
    VoxelizeStats stats;
    VoxelizeOptions o = options;
    o.stats = &stats;
    if (ext == ".vdb" || ext == ".nvdb") {
        const auto t0 = Clock::now();
        vdb::VdbBricks vb = ext == ".vdb" ? vdb::readVdbBricks(path, gridName) : vdb::readNanoVdbBricks(path, gridName);
        out.stages.push_back({ext == ".vdb" ? "vdb read" : "nvdb read", -1, msSince(t0)});
        out.kind = LoadedOctree::Kind::Vdb;
        out.gridName = vb.gridName;
        out.gridType = vb.gridType;
        out.tilesExpanded = vb.tilesExpanded;
        out.valuesDropped = vb.valuesDropped;
        out.octree = voxelizer.bricksToOctree(vb.grid, std::move(vb.bricks), o);
    } else {
        const auto t0 = Clock::now();
        TriangleMesh mesh = loadMesh(path);
        out.stages.push_back({"mesh read", -1, msSince(t0)});
        out.kind = LoadedOctree::Kind::Mesh;
        out.octree = voxelizer.voxelize(mesh, makeGrid(mesh, request), o);
        out.mesh = std::move(mesh);
    }
    for (auto& s : stats.stages) out.stages.push_back(s);
    if (options.stats) *options.stats = std::move(stats);
    return out;
}

} // namespace svo
