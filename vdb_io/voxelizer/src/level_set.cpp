// Level sets, unsigned distance fields and solids (svo/voxelizer.h): the GPU's
// field pipeline (svo/gl/field_pipeline.h) computes them on bricks, and the
// converter (svo/vdb_io/field_grids.h) makes the grids.
#include <algorithm>
#include <climits>
#include <fmt/format.h>
#include <optional>

#include "svo/core/error.h"
#include "svo/gl/field_pipeline.h"
#include "svo/vdb_io/field_grids.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/vdb_file.h"
#include "voxelizer_state.h"

namespace svo {
namespace {

using detail::Clock;
using detail::InterruptScope;
using detail::msSince;

/// A region's grids hold nothing outside it: the field passes cut their work
/// to the region's bricks (or, for parity, its columns), and this cuts the
/// rest, as the whole grid cut to the box would be (docs/design.md, "Regions").
void clipToRegion(openvdb::GridBase& grid, const std::optional<IndexBox>& region)
{
    if (!region) return;
    auto coord = [](const std::array<int64_t, 3>& v, int64_t add) {
        auto c = [&](int a) { return int32_t(std::clamp<int64_t>(v[a] + add, INT32_MIN, INT32_MAX)); };
        return openvdb::Coord(c(0), c(1), c(2));
    };
    grid.clip(openvdb::CoordBBox(coord(region->lo, 0), coord(region->hi, -1)));
}

/// The last stage, the result's record of what ran (each grid's metadata:
/// backend, renderer and the sign method with why, "" for unsigned fields)
/// and its counts, then the statistics handed out.
void finishStats(VoxelizeStats& stats, const char* stage, Clock::time_point t0, const openvdb::GridPtrVec& result,
                 const Checkpoint& checkpoint, const VoxelizeOptions& options)
{
    stats.stages.push_back({stage, -1, msSince(t0)});
    for (const auto& grid : result) {
        vdb::tagProvenance(*grid, {stats.backend, "", stats.renderer});
        grid->insertMeta("svo:sign", openvdb::StringMetadata(vdb::validUtf8(stats.sign)));
    }
    stats.voxels = result.front()->activeVoxelCount();
    stats.bricks = result.front()->baseTree().leafCount();
    checkpoint(1.0, "finish");
    if (options.stats) *options.stats = std::move(stats);
}

} // namespace

namespace detail {
double uniformScale(const openvdb::math::Transform& xform)
{
    if (!xform.isLinear() || !xform.hasUniformScale())
        throw Unsupported("level sets need a linear transform with uniform scale, so that index distances are world "
                    "distances");
    return xform.voxelSize()[0];
}
} // namespace detail

openvdb::GridPtrVec Voxelizer::levelSet(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                                        const VoxelizeOptions& options, openvdb::math::Transform::Ptr xform)
{
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    if (!xform) xform = vdb::makeTransform(grid);
    const double scale = detail::uniformScale(*xform);
    return levelSetChecked(mesh, grid, ls, options, xform, scale);
}

openvdb::MaskGrid::Ptr Voxelizer::solid(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                        const SignOptions& sign, openvdb::math::Transform::Ptr xform)
{
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    return solidChecked(mesh, grid, options, sign, xform ? xform : vdb::makeTransform(grid));
}

openvdb::GridPtrVec Voxelizer::levelSetChecked(const TriangleMesh& mesh, const GridSpec& grid,
                                               const LevelSetOptions& ls, const VoxelizeOptions& options,
                                               openvdb::math::Transform::Ptr xform, double worldPerVoxel)
{
    const InterruptScope interrupt(options.interrupter, "svo: computing a distance field");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    const DistanceBricks field = gl::levelSetBricks(device_, mesh, grid, ls, options, checkpoint, stats);
    checkpoint(0.85, "level set grid");
    const auto t0 = Clock::now();
    openvdb::GridPtrVec out = vdb::levelSetGrids(field, ls.exteriorBand, ls.interiorBand, worldPerVoxel, xform);
    for (auto& g : out) clipToRegion(*g, options.region);
    finishStats(stats, "level set grid", t0, out, checkpoint, options);
    return out;
}

openvdb::MaskGrid::Ptr Voxelizer::solidChecked(const TriangleMesh& mesh, const GridSpec& grid,
                                               const VoxelizeOptions& options, const SignOptions& sign,
                                               openvdb::math::Transform::Ptr xform)
{
    const InterruptScope interrupt(options.interrupter, "svo: filling a solid");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    const SolidBricks solid = gl::solidBricks(device_, mesh, grid, options, sign, checkpoint, stats);
    checkpoint(0.8, "solid grid");
    const auto t0 = Clock::now();
    openvdb::MaskGrid::Ptr out = vdb::solidGrid(solid, xform);
    clipToRegion(*out, options.region);
    finishStats(stats, "solid grid", t0, {out}, checkpoint, options);
    return out;
}

} // namespace svo
