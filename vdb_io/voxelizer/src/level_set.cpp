// Level sets, unsigned distance fields and solids (svo/voxelizer.h): the GPU's
// field pipeline (svo/gl/field_pipeline.h) computes them on bricks, and the
// converter (svo/vdb_io/field_grids.h) makes the grids.
#include <algorithm>
#include <climits>
#include <cmath>
#include <fmt/format.h>
#include <optional>

#include "svo/core/error.h"
#include "svo/gl/field_pipeline.h"
#include "svo/vdb_io/field_grids.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/join_region.h"
#include "svo/vdb_io/vdb_file.h"
#include "regions.h"
#include "voxelizer_state.h"

namespace svo {
namespace {

using detail::Clock;
using detail::fieldBox;
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

/// What a field call is called in progress and statistics, and the box its
/// regions are cut from past a GPU memory budget.
struct FieldCall {
    const char* task;  ///< the interrupter's task name
    const char* stage; ///< the grid stage's name
    double stageAt;    ///< the share of the work done when the grid stage starts
    IndexBox box;      ///< every voxel the field can hold (fieldBox)
};

/// One field call: `bricks(options, checkpoint, stats)` computes the field
/// on the call's region (or each budget region), `grids(field)` turns it into
/// grids, which are cut to the region, joined, and handed out with the last
/// stage's record.
template <typename Bricks, typename Grids>
openvdb::GridPtrVec runFieldCall(const FieldCall& call, const VoxelizeOptions& options, Bricks&& bricks, Grids&& grids)
{
    const InterruptScope interrupt(options.interrupter, call.task);
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    Clock::time_point t0;
    auto run = [&](const std::optional<IndexBox>& region, const Checkpoint& progress) {
        VoxelizeOptions part = options;
        part.region = region;
        stats = VoxelizeStats{};
        const auto field = bricks(part, progress, stats);
        progress(call.stageAt, call.stage);
        t0 = Clock::now();
        openvdb::GridPtrVec out = grids(field);
        for (auto& g : out) clipToRegion(*g, region);
        return out;
    };
    auto join = [](openvdb::GridPtrVec& into, const openvdb::GridPtrVec& more) {
        for (size_t i = 0; i < into.size(); ++i) vdb::joinRegion(*into[i], *more[i]);
    };
    openvdb::GridPtrVec out = detail::withinBudget(run, join, options, call.box, checkpoint, stats);
    finishStats(stats, call.stage, t0, out, checkpoint, options);
    return out;
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

openvdb::MaskGrid::Ptr Voxelizer::band(const TriangleMesh& mesh, const GridSpec& grid, double band,
                                       const VoxelizeOptions& options, openvdb::math::Transform::Ptr xform)
{
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    if (!xform) xform = vdb::makeTransform(grid);
    detail::uniformScale(*xform); // as levelSet(): the band is a distance
    const LevelSetOptions ls = detail::bandOptions(band);
    const FieldCall call{"svo: finding a band", "band grid", 0.85, fieldBox(grid, detail::levelSetPad(ls))};
    const openvdb::GridPtrVec out = runFieldCall(
        call, options,
        [&](const VoxelizeOptions& part, const Checkpoint& checkpoint, VoxelizeStats& stats) {
            return gl::bandTopologyBricks(device_, mesh, grid, band, part, checkpoint, stats);
        },
        [&](const DistanceBricks& field) { return openvdb::GridPtrVec{vdb::bandGrid(field, band, xform)}; });
    return openvdb::gridPtrCast<openvdb::MaskGrid>(out.front());
}

openvdb::GridPtrVec Voxelizer::levelSetChecked(const TriangleMesh& mesh, const GridSpec& grid,
                                               const LevelSetOptions& ls, const VoxelizeOptions& options,
                                               openvdb::math::Transform::Ptr xform, double worldPerVoxel)
{
    const FieldCall call{"svo: computing a distance field", "level set grid", 0.85,
                         fieldBox(grid, detail::levelSetPad(ls))};
    return runFieldCall(
        call, options,
        [&](const VoxelizeOptions& part, const Checkpoint& checkpoint, VoxelizeStats& stats) {
            return gl::levelSetBricks(device_, mesh, grid, ls, part, checkpoint, stats);
        },
        [&](const DistanceBricks& field) {
            return vdb::levelSetGrids(field, ls.exteriorBand, ls.interiorBand, worldPerVoxel, xform);
        });
}

openvdb::MaskGrid::Ptr Voxelizer::solidChecked(const TriangleMesh& mesh, const GridSpec& grid,
                                               const VoxelizeOptions& options, const SignOptions& sign,
                                               openvdb::math::Transform::Ptr xform)
{
    const FieldCall call{"svo: filling a solid", "solid grid", 0.8, fieldBox(grid, detail::kSolidPad)};
    const openvdb::GridPtrVec out = runFieldCall(
        call, options,
        [&](const VoxelizeOptions& part, const Checkpoint& checkpoint, VoxelizeStats& stats) {
            return gl::solidBricks(device_, mesh, grid, part, sign, checkpoint, stats);
        },
        [&](const SolidBricks& solid) { return openvdb::GridPtrVec{vdb::solidGrid(solid, xform)}; });
    return openvdb::gridPtrCast<openvdb::MaskGrid>(out.front());
}

} // namespace svo
