// NanoVDB grids from the front door (svo/voxelizer.h): the field passes'
// bricks laid out as NanoVDB grids (svo/vdb_io/nanovdb_grids.h), with no
// OpenVDB tree between them.
#include "svo/vdb_io/nanovdb_output.h"
#include "svo/vdb_io/reader_grids.h" // withTopology
#include "svo/voxelizer.h"
#include "voxelizer_state.h"

namespace svo {

using detail::Clock;
using detail::InterruptScope;
using detail::msSince;

namespace {

/// Regions and GPU memory budgets cut the grid and join OpenVDB grids
/// (level_set.cpp): those calls keep that path and convert its result.
bool viaOpenVdb(const VoxelizeOptions& options) { return options.region || options.gpuMemory; }

std::vector<vdb::NanoHandle> converted(const openvdb::GridPtrVec& grids)
{
    std::vector<vdb::NanoHandle> out;
    for (const auto& g : grids) out.push_back(vdb::toNanoVdb(g));
    return out;
}

/// The last stage and the counts, then the statistics handed out.
void finish(VoxelizeStats& stats, const char* stage, Clock::time_point t0, const vdb::NanoHandle& main,
            const Checkpoint& checkpoint, const VoxelizeOptions& options)
{
    stats.stages.push_back({stage, -1, msSince(t0)});
    const auto* grid = main.gridMetaData();
    stats.voxels = grid ? grid->activeVoxelCount() : 0;
    stats.bricks = grid ? grid->nodeCount(0) : 0;
    checkpoint(1.0, "finish");
    if (options.stats) *options.stats = std::move(stats);
}

} // namespace

std::vector<vdb::NanoHandle> Voxelizer::voxelizeNanoVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                                        const VoxelizeOptions& options, const GridOptions& grids)
{
    return vdb::octreeToNanoGrids(voxelize(mesh, grid, options), grids);
}

std::vector<vdb::NanoHandle> Voxelizer::levelSetNanoVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                                        const LevelSetOptions& ls, const VoxelizeOptions& options)
{
    if (viaOpenVdb(options)) return converted(levelSet(mesh, grid, ls, options));
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    vdb::checkVdbGrid(grid, "grid"); // the same transform rule as levelSet()
    const InterruptScope interrupt(options.interrupter, "svo: computing a distance field");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    const DistanceBricks field = gl::levelSetBricks(device_, mesh, grid, ls, options, checkpoint, stats);
    checkpoint(0.85, "nanovdb grid");
    const auto t0 = Clock::now();
    std::vector<vdb::NanoHandle> out = vdb::levelSetNanoGrids(field, ls.exteriorBand, ls.interiorBand, grid);
    finish(stats, "nanovdb grid", t0, out.front(), checkpoint, options);
    return out;
}

vdb::NanoHandle Voxelizer::solidNanoVdb(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                        const SignOptions& sign, GridOptions::Topology topology)
{
    if (viaOpenVdb(options)) return vdb::toNanoVdb(vdb::withTopology(solid(mesh, grid, options, sign), topology));
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    vdb::checkVdbGrid(grid, "grid");
    const InterruptScope interrupt(options.interrupter, "svo: filling a solid");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    const SolidBricks solidBricks = gl::solidBricks(device_, mesh, grid, options, sign, checkpoint, stats);
    checkpoint(0.8, "nanovdb grid");
    const auto t0 = Clock::now();
    vdb::NanoHandle out = vdb::solidNanoGrid(solidBricks, grid, topology);
    finish(stats, "nanovdb grid", t0, out, checkpoint, options);
    return out;
}

} // namespace svo
