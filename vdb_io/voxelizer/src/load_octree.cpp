#include "svo/load_octree.h"

#include <chrono>
#include <filesystem>

#include "svo/core/mesh_io.h"
#include "svo/core/octree_file.h"
#include "svo/vdb_io/nanovdb_input.h"
#include "svo/vdb_io/vdb_file.h"
#include "svo/vdb_io/zero_crossing.h"
#include "svo/voxelizer.h"

namespace svo {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// One grid of a .vdb or .nvdb file as bricks, a grid of distances narrowed
/// to its zero crossing (fieldVoxels: the band's voxels it was taken from).
vdb::VdbBricks readBricks(const std::string& path, bool nano, const std::string& gridName, FieldVoxels field,
                          uint64_t& fieldVoxels)
{
    if (field == FieldVoxels::Active) return nano ? vdb::readNanoVdbBricks(path, gridName) : vdb::readVdbBricks(path, gridName);
    const openvdb::GridPtrVec grids = nano ? vdb::readNanoVdbGrids(path, gridName) : vdb::readVdbGrids(path, gridName);
    const openvdb::GridBase::Ptr grid = vdb::mainGrid(grids); // the one named, or the file's main grid
    vdb::VdbBricks vb = vdb::bricksOfGrid(*grid, path);
    if (vdb::distanceKind(*grid) != vdb::DistanceKind::None) fieldVoxels = vdb::keepZeroCrossing(*grid, vb);
    return vb;
}

} // namespace

LoadedOctree loadOctree(Voxelizer& voxelizer, const std::string& path, const std::string& gridName,
                        const GridRequest& request, const VoxelizeOptions& options, FieldVoxels field)
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
        vdb::VdbBricks vb = readBricks(path, ext == ".nvdb", gridName, field, out.fieldVoxels);
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
