// Level sets, unsigned distance fields and solids on bricks
// (svo/gl/field_pipeline.h): the band's bricks (svo/core/band_bricks.h),
// distances and parity crossings (distance_field.h), winding numbers
// (winding_number.h); with Backend::Cpu their CPU counterparts in core
// (band_distances.h, parity_crossings.h, winding_signs.h).
#include "svo/gl/field_pipeline.h"

#include <algorithm>
#include <cstdint>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <utility>

#include "svo/core/band_bricks.h"
#include "svo/core/band_distances.h"
#include "svo/core/byte_size.h"
#include "svo/core/parity_crossings.h"
#include "svo/core/error.h"
#include "svo/core/local_positions.h"
#include "svo/core/parity_scan.h"
#include "svo/core/region.h"
#include "svo/core/sign_choice.h"
#include "svo/core/winding_signs.h"
#include "svo/core/winding_tree.h"
#include "svo/gl/buffer.h"
#include "svo/gl/distance_field.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/voxelize_pipeline.h"
#include "svo/gl/winding_number.h"

namespace svo {

void checkFieldMode(const VoxelizeSettings& options)
{
    if (options.mode != VoxelMode::Conservative)
        throw InvalidInput(std::vector<Error::Part>{
            Error::option("VoxelizeOptions::mode"), fmt::format(" {}: ", voxelModeName(options.mode)),
            Error::option("VoxelizeOptions::mode"),
            " applies to surface voxels; level sets, unsigned distances and solids do not depend on it (leave it "
            "conservative)"});
}

namespace gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// The grid grown by `pad` voxels on every side (the anchor kept a multiple
/// of 8), so that a band around the mesh lies inside its local range.
GridSpec padded(const GridSpec& grid, uint32_t pad, const std::string& what)
{
    GridSpec g = grid;
    for (int a = 0; a < 3; ++a) {
        g.anchor[a] = floorTo8(grid.anchor[a] - int64_t(pad));
        const uint64_t dims = uint64_t(grid.anchor[a] - g.anchor[a]) + grid.dims[a] + pad;
        if (dims > kMaxGridDim)
            throw Unsupported(fmt::format("{}: the grid with its band is {} voxels wide, more than svo's {}", what, dims,
                                    kMaxGridDim));
        g.dims[a] = uint32_t(dims);
    }
    checkGrid(g, what);
    return g;
}

/// What a region's distances and signs need of a list of bricks: those that
/// meet the region, or with `columns` (parity, which counts crossings from
/// the bottom of each column) those under, in or over it. All without a region.
std::vector<BrickCoord> forRegion(std::vector<BrickCoord> bricks, const GridSpec& g,
                                  const std::optional<IndexBox>& region, bool columns)
{
    if (!region) return bricks;
    const VoxelBox box = localBox(g, *region);
    if (box.empty()) return {};
    const int axes = columns ? 2 : 3;
    const auto outside = [&](const BrickCoord& b) {
        for (int a = 0; a < axes; ++a)
            if (8 * b[a] + 8 <= box.lo[a] || 8 * b[a] >= box.hi[a]) return true;
        return false;
    };
    bricks.erase(std::remove_if(bricks.begin(), bricks.end(), outside), bricks.end());
    return bricks;
}

/// Whether @a region holds no voxel of the grid: a call there computes no
/// value, and winding signs skip their passes (the whole mesh's tree: the
/// plan of svo.distributed asks for such a region to learn a grid's
/// transform and sign method).
bool missesGrid(const GridSpec& g, const std::optional<IndexBox>& region)
{
    return region && localBox(g, *region).empty();
}

/// The band's bricks that forRegion() keeps, searched only there.
std::vector<BrickCoord> bandBricksFor(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& g,
                                      double band, const std::optional<IndexBox>& region, bool columns)
{
    VoxelBox within = wholeBox(g);
    if (region) {
        const VoxelBox box = localBox(g, *region);
        for (int a = 0; a < (columns ? 2 : 3); ++a) within.lo[a] = box.lo[a], within.hi[a] = box.hi[a];
        if (box.empty()) return {};
    }
    return bricksNearTriangles(local, mesh, g, std::max(band, 1.0), within);
}

/// Refuses, before any GPU buffer is made, field work that a GPU memory
/// budget cannot hold (VoxelizeSettings::gpuMemory; none: no check): per
/// band brick its distances, closest triangles and masks, per triangle its
/// corners and work items. The front door then cuts the grid into regions.
void checkFieldBudget(const VoxelizeSettings& settings, size_t bricks, const TriangleMesh& mesh)
{
    if (!settings.gpuMemory) return;
    constexpr uint64_t kBytesPerBrick = 512 * 4 * 2 + 64 * 4 + 16; // distances, closest, masks, coordinates
    constexpr uint64_t kBytesPerTriangle = 3 * 12 + 12 + 16;        // corners, indices, work items
    const uint64_t brickBytes = uint64_t(bricks) * kBytesPerBrick;
    const uint64_t meshBytes = uint64_t(mesh.triangles.size()) * kBytesPerTriangle;
    if (brickBytes + meshBytes > settings.gpuMemory)
        throw OutOfMemory(fmt::format("a GPU memory budget of {} cannot hold the field's {} band bricks ({}) with the "
                                      "mesh's {} triangles ({}: corners, indices, work items); raise the budget",
                                      byteSize(settings.gpuMemory), bricks, byteSize(brickBytes),
                                      mesh.triangles.size(), byteSize(meshBytes)));
}

/// Winding-number signs: the number at every brick centre of the grid's box
/// (of a region's bricks, in a region),
/// then voxel by voxel in the band's bricks and in the bricks whose centre is
/// within kWindingMargin of 1/2 (bricksBeyondBand, the CPU path's rule too).
/// The mesh's winding tree in @a g's local frame: the device's kept one when
/// the last call's was over the same triangles (a region's after another's),
/// timed into `stats` ("winding tree", or "winding tree (kept)" for the
/// comparison alone).
const WindingTree& windingTree(WindingTreeCache& trees, const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                               VoxelizeStats& stats)
{
    const auto t0 = Clock::now();
    bool built = false;
    const WindingTree& tree = trees.treeFor(local, mesh.triangles, &built);
    stats.stages.push_back({built ? "winding tree" : "winding tree (kept)", -1, msSince(t0)});
    return tree;
}

FieldSigns windingSigns(Device& device, const TriangleMesh& mesh, const GridSpec& g,
                   const std::vector<BrickCoord>& band, double beta, const std::optional<IndexBox>& region,
                   const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    if (missesGrid(g, region)) return {};
    Context& context = device.context();
    const WindingTree& tree = windingTree(device.windingTrees(), localPositions(mesh, g), mesh, stats);
    WindingRequest coarse;
    coarse.perBrick = true;
    coarse.brickBox = bricksMeeting(g, region); // a region's own bricks, as on the CPU
    coarse.beta = beta;
    coarse.checkpoint = checkpoint.part(0.0, 0.3);
    RunStats centresReport;
    WindingResult centres = computeWinding(context, g, tree, coarse, &centresReport);
    for (auto& st : centresReport.stages) stats.stages.push_back(std::move(st));

    FieldSigns signs;
    BricksBeyondBand beyond = bricksBeyondBand(centres.perBrick, centres.brickDims, band, centres.brickOrigin);
    beyond.voxelwise = forRegion(std::move(beyond.voxelwise), g, region, false);
    signs.insideBricks = forRegion(std::move(beyond.inside), g, region, false);
    WindingRequest fine;
    fine.bricks = band;
    fine.bricks.insert(fine.bricks.end(), beyond.voxelwise.begin(), beyond.voxelwise.end());
    fine.beta = beta;
    fine.checkpoint = checkpoint.part(0.3, 1.0);
    stats.windingBricks = beyond.voxelwise.size();
    stats.windingWalks = 512 * uint64_t(fine.bricks.size()) + centres.perBrick.size();
    RunStats voxelsReport;
    WindingResult voxels = computeWinding(context, g, tree, fine, &voxelsReport);
    for (auto& st : voxelsReport.stages) stats.stages.push_back(std::move(st));
    stats.gpuBytes = std::max({stats.gpuBytes, centresReport.gpuBytes, voxelsReport.gpuBytes});
    signs.inside.assign(voxels.inside.begin(), voxels.inside.begin() + std::ptrdiff_t(band.size()));
    for (size_t i = band.size(); i < fine.bricks.size(); ++i)
        if (voxels.inside[i].count()) signs.partial.push_back({fine.bricks[i], voxels.inside[i]});
    return signs;
}

/// @a anchors with the bricks its caller's band was searched in whole: the
/// grid's, or the region's (the band of a winding-signed field is searched
/// in the region's box, bandBricksFor; a solid's surface voxels are).
ClimbAnchors searchedBricks(const GridSpec& g, const std::optional<IndexBox>& region, ClimbAnchors anchors)
{
    VoxelBox box = wholeBox(g);
    if (region) box = localBox(g, *region);
    for (int a = 0; a < 3; ++a) {
        anchors.lo[a] = (box.lo[a] + 7) / 8;
        anchors.hi[a] = std::min(box.hi[a], g.dims[a]) / 8;
    }
    return anchors;
}

/// The same on the CPU (svo/core/winding_signs.h): the same tree, rule and
/// sums, walked where climbing a column from its lowest centres does not
/// decide (windingInsideAlongColumns).
FieldSigns windingSignsCpu(WindingTreeCache& trees, const TriangleMesh& mesh, const std::vector<Vec3d>& local,
                           const GridSpec& g, const std::vector<BrickCoord>& band, double beta,
                           const std::optional<IndexBox>& region, const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    if (missesGrid(g, region)) return {};
    const WindingTree& tree = windingTree(trees, local, mesh, stats);
    auto t0 = Clock::now();
    // Only the region's bricks: a region's signs cost its own volume, not the grid's.
    const BrickBox box = bricksMeeting(g, region);
    const BrickCentreColumns centreColumns = brickCentreColumns(local, mesh, g, &box);
    uint64_t centresWalked = 0;
    std::vector<float> doubts;
    const std::vector<float> centres =
        windingAtBrickCentres(tree, g, beta, checkpoint.part(0.0, 0.3), &centreColumns, &centresWalked, &doubts);
    stats.stages.push_back({"winding bricks (cpu)", -1, msSince(t0)});
    t0 = Clock::now();
    BricksBeyondBand beyond = bricksBeyondBand(centres, centreColumns.dims, band, centreColumns.origin);
    beyond.voxelwise = forRegion(std::move(beyond.voxelwise), g, region, false);
    FieldSigns signs;
    signs.insideBricks = forRegion(std::move(beyond.inside), g, region, false);
    std::vector<BrickCoord> fine = band;
    fine.insert(fine.end(), beyond.voxelwise.begin(), beyond.voxelwise.end());
    stats.windingBricks = beyond.voxelwise.size();
    const WindingColumns columns = windingColumns(local, mesh, g, fine);
    stats.stages.push_back({"winding columns (cpu)", -1, msSince(t0)});
    t0 = Clock::now();
    const ClimbAnchors anchors = searchedBricks(g, region, {&centreColumns, &centres, &doubts});
    std::vector<Brick> inside =
        windingInsideAlongColumns(tree, fine, columns, beta, checkpoint.part(0.3, 1.0), &stats.windingWalks, &anchors);
    stats.windingWalks += centresWalked;
    stats.stages.push_back({"winding voxels (cpu)", -1, msSince(t0)});
    signs.inside.assign(inside.begin(), inside.begin() + std::ptrdiff_t(band.size()));
    for (size_t i = band.size(); i < fine.size(); ++i)
        if (inside[i].count()) signs.partial.push_back({fine[i], inside[i]});
    return signs;
}

/// Parity signs from the crossings the distance pass marked.
FieldSigns paritySigns(const std::vector<BrickCoord>& band, const std::vector<Brick>& crossings)
{
    ParityScan scan = scanParity(band, crossings);
    FieldSigns signs;
    signs.inside = std::move(scan.inside);
    signs.runs = std::move(scan.runs);
    signs.openColumns = scan.openColumns;
    return signs;
}

/// computeField, with its stages and buffer bytes added to `stats`.
FieldResult fieldPass(Context& context, const TriangleMesh& mesh, const GridSpec& g,
                          const FieldRequest& request, bool region, VoxelizeStats& stats)
{
    RunStats report;
    FieldResult field = computeField(context, mesh, g, request, &report);
    // A region keeps only its columns' bricks: the other columns' crossings are not needed.
    if (field.lostCrossings && !region)
        throw DeviceError(fmt::format("internal error: {} parity crossings fell outside the band's bricks",
                                field.lostCrossings));
    for (auto& st : report.stages) stats.stages.push_back(std::move(st));
    stats.gpuBytes = std::max(stats.gpuBytes, report.gpuBytes);
    return field;
}

/// Records parity's open columns, warning with what they mean for the result.
void noteOpenColumns(VoxelizeStats& stats, uint64_t openColumns, const char* consequence)
{
    stats.openColumns = openColumns;
    if (openColumns)
        stats.warnings.push_back(fmt::format("{} voxel columns cross the surface an odd number of times: the mesh is "
                                             "open there, and {}",
                                             openColumns, consequence));
}

/// grownBricks, counted and timed in `stats`.
std::vector<BrickCoord> bandBricks(const Octree& surface, uint32_t reach, VoxelizeStats& stats)
{
    const auto t0 = Clock::now();
    std::vector<BrickCoord> band = grownBricks(surface, reach);
    stats.bandBricks = band.size();
    stats.stages.push_back({"band bricks", -1, msSince(t0)});
    return band;
}

/// The conservative surface voxels a solid starts from, as voxelizeMesh
/// gives them whatever the mode asked: the band is grown from, and every
/// crossing lies in, a voxel a triangle touches. The call's statistics begin
/// as theirs, after the warnings gathered so far.
Octree surfaceVoxels(Device& device, const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeSettings& settings,
                     VoxelizeStats& stats)
{
    VoxelizeSettings surface = settings;
    surface.attributes = 0;
    surface.mode = VoxelMode::Conservative;
    VoxelizeStats surfaceStats;
    Octree octree = voxelizeMesh(device, mesh, grid, surface, Checkpoint{}, surfaceStats);
    surfaceStats.warnings.insert(surfaceStats.warnings.begin(), stats.warnings.begin(), stats.warnings.end());
    stats = std::move(surfaceStats);
    return octree;
}

/// ORs the surface's voxels into the band bricks' inside masks (every
/// surface brick is a band brick: the band grows from them).
void addSurface(const Octree& surface, const std::vector<BrickCoord>& band, std::vector<Brick>& inside)
{
    std::vector<std::pair<BrickCoord, uint32_t>> bricks;
    for (const auto& r : occupiedBricks(surface))
        bricks.push_back({{r.origin[0] / 8, r.origin[1] / 8, r.origin[2] / 8}, r.index});
    tbb::parallel_sort(bricks.begin(), bricks.end());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, band.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const auto it = std::lower_bound(bricks.begin(), bricks.end(), std::make_pair(band[i], uint32_t(0)));
            if (it != bricks.end() && it->first == band[i])
                for (int w = 0; w < 8; ++w) inside[i].words[w] |= surface.bricks[it->second].words[w];
        }
    });
}

/// The parity crossings found on the CPU, refused (as the GPU's pass refuses them)
/// when one falls outside the band's bricks, timed into `stats`.
std::vector<Brick> crossingsCpu(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& g,
                                const std::vector<BrickCoord>& bricks, bool region, VoxelizeStats& stats)
{
    const auto t0 = Clock::now();
    ParityCrossings found = parityCrossings(local, mesh, g, bricks);
    if (found.lost && !region) // as fieldPass
        throw Error(fmt::format("internal error: {} parity crossings fell outside the band's bricks", found.lost));
    stats.stages.push_back({"crossings (cpu)", -1, msSince(t0)});
    return std::move(found.crossings);
}

/// levelSetBricks on the CPU (svo/core/band_distances.h, parity_crossings.h,
/// winding_signs.h): the same bricks, distances and signs as the GPU's.
DistanceBricks levelSetOnCpu(WindingTreeCache& trees, const TriangleMesh& mesh, const GridSpec& g, const LevelSetOptions& ls,
                             const SignChoice& sign, double band, const std::optional<IndexBox>& region,
                             const Checkpoint& checkpoint, VoxelizeStats& stats, bool bandOnly)
{
    const bool signedField = !ls.unsignedDistance;
    const bool winding = signedField && sign.method == SignMethod::Winding;
    DistanceBricks out;
    auto t0 = Clock::now();
    const std::vector<Vec3d> local = localPositions(mesh, g);
    out.bricks = bandBricksFor(local, mesh, g, band, region, signedField && !winding);
    stats.bandBricks = out.bricks.size();
    stats.stages.push_back({"band bricks", -1, msSince(t0)});
    checkpoint(0.05, "band distance");
    t0 = Clock::now();
    BandDistances field =
        bandDistances(local, mesh, g, out.bricks, band, ls.closestTriangle, checkpoint.part(0.05, winding ? 0.3 : 0.8),
                      bandOnly);
    stats.stages.push_back({"band distance (cpu)", -1, msSince(t0)});
    if (winding) {
        out.signs = windingSignsCpu(trees, mesh, local, g, out.bricks, ls.sign.windingAccuracy, region,
                                    checkpoint.part(0.3, 0.85), stats);
    } else if (signedField) {
        const std::vector<Brick> crossings = crossingsCpu(local, mesh, g, out.bricks, region.has_value(), stats);
        checkpoint(0.82, "parity scan");
        t0 = Clock::now();
        out.signs = paritySigns(out.bricks, crossings);
        stats.stages.push_back({"parity scan", -1, msSince(t0)});
    }
    out.near = std::move(field.near);
    out.offsets = std::move(field.offsets);
    out.distances = std::move(field.distances);
    out.closest = std::move(field.closest);
    return out;
}

/// What a level set's passes start from: the checked options, the sign
/// method, the band and the grid padded by it (recorded in `stats`).
struct FieldSetup {
    SignChoice sign;
    bool signedField = true, winding = false;
    double band = 0;
    GridSpec g;
};

FieldSetup setUpField(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                      const VoxelizeSettings& settings, VoxelizeStats& stats)
{
    FieldSetup f;
    f.signedField = !ls.unsignedDistance;
    checkLevelSetOptions(ls);
    checkFieldMode(settings);
    if (settings.region) checkRegion(*settings.region);
    if (f.signedField) f.sign = chooseSign(mesh, ls.sign, stats.warnings);
    f.winding = f.signedField && f.sign.method == SignMethod::Winding;
    f.band = f.signedField ? std::max(ls.exteriorBand, ls.interiorBand) : ls.exteriorBand;
    // Every voxel within `band` of a triangle is within reach (Chebyshev) of
    // the triangle's box; the first centre above a crossing is within 1.
    const uint32_t reach = std::max<uint32_t>(1, uint32_t(std::floor(f.band + 0.5)));
    f.g = padded(grid, reach + 1, mesh.source);
    stats.grid = f.g;
    stats.epsilon = f.g.epsilon();
    stats.sign = f.sign.why;
    return f;
}

/// The GPU passes' request: the band's bricks (timed into `stats`), checked
/// against the GPU memory budget, and what to compute.
FieldRequest bandRequest(const TriangleMesh& mesh, const FieldSetup& f, const LevelSetOptions& ls,
                         const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    FieldRequest request;
    const auto t0 = Clock::now();
    request.bricks = bandBricksFor(localPositions(mesh, f.g), mesh, f.g, f.band, settings.region,
                                   f.signedField && !f.winding);
    stats.bandBricks = request.bricks.size();
    stats.stages.push_back({"band bricks", -1, msSince(t0)});
    checkFieldBudget(settings, request.bricks.size(), mesh);
    request.band = f.band;
    request.closestTriangle = ls.closestTriangle;
    request.crossings = f.signedField && !f.winding;
    request.checkpoint = checkpoint.part(0.3, f.winding ? 0.55 : 0.85);
    return request;
}

/// levelSetBricks once the field is set up; `bandOnly`: only the voxels
/// nearer than the band are asked (an unsigned field's, bandTopologyBricks).
DistanceBricks bricksOf(Device& device, const TriangleMesh& mesh, const LevelSetOptions& ls,
                        const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats,
                        const FieldSetup& f, bool bandOnly = false)
{
    const bool signedField = f.signedField, winding = f.winding;
    const GridSpec& g = f.g;
    checkpoint(0.0, "band bricks");
    if (runsOnCpu(device, settings)) { // no GL context is made
        describeBackend(device, Backend::Cpu, stats);
        DistanceBricks out =
            levelSetOnCpu(device.windingTrees(), mesh, g, ls, f.sign, f.band, settings.region, checkpoint, stats, bandOnly);
        noteOpenColumns(stats, out.signs.openColumns, "signs above its last crossing count as outside");
        out.grid = g;
        out.closestTriangle = ls.closestTriangle;
        out.signedField = signedField;
        out.winding = winding;
        out.region = settings.region.has_value();
        return out;
    }
    describeBackend(device, Backend::Compute, stats); // compute passes only, whatever the backend asked

    FieldRequest request = bandRequest(mesh, f, ls, settings, checkpoint, stats);
    request.bandOnly = bandOnly;
    FieldResult field = fieldPass(device.context(), mesh, g, request, settings.region.has_value(), stats);
    DistanceBricks out;
    if (winding) {
        out.signs = windingSigns(device, mesh, g, request.bricks, ls.sign.windingAccuracy, settings.region,
                                 checkpoint.part(0.55, 0.85), stats);
    } else if (signedField) {
        const auto t0 = Clock::now();
        out.signs = paritySigns(request.bricks, field.crossings);
        stats.stages.push_back({"parity scan", -1, msSince(t0)});
    }
    noteOpenColumns(stats, out.signs.openColumns, "signs above its last crossing count as outside");
    stats.startup = device.takeStartup(stats.warnings);
    out.grid = g;
    out.bricks = std::move(request.bricks);
    out.near = std::move(field.bandMasks);
    out.offsets = std::move(field.bandOffsets);
    out.distances = std::move(field.distances);
    out.closest = std::move(field.closest);
    out.closestTriangle = ls.closestTriangle;
    out.signedField = signedField;
    out.winding = winding;
    out.region = settings.region.has_value();
    return out;
}

/// Whether the band can stay on the device: a GL backend and no region.
bool leavesOnDevice(Device& device, const VoxelizeSettings& settings)
{
    return !settings.region && !runsOnCpu(device, settings);
}

/// Winding signs' bricks beyond the band classified voxel by voxel, added
/// after the band's leaves: nothing active, the background negated where
/// inside (levelSetNanoGrids' leaves of FieldSigns::partial).
void addPartialLeaves(const Context& context, const GridSpec& g, const FieldSigns& signs, float background,
                      FieldLeaves& leaves)
{
    const size_t n = signs.partial.size();
    if (!n) return;
    std::vector<std::array<int32_t, 3>> origins(n);
    std::vector<Brick> masks(n);
    std::vector<float> values(512 * n, background);
    for (size_t i = 0; i < n; ++i) {
        const auto& [b, inside] = signs.partial[i];
        for (int a = 0; a < 3; ++a) origins[i][size_t(a)] = int32_t(g.anchor[size_t(a)] + 8 * int64_t(b[size_t(a)]));
        for (uint32_t v = 0; v < 512; ++v)
            if ((inside.words[v >> 6] >> (v & 63)) & 1u) values[512 * i + v] = -background;
    }
    const uint64_t at = leaves.count;
    const Context::Scope scope(context);
    leaves.origins->write(12 * at, 12 * n, origins.data());
    leaves.masks->write(sizeof(Brick) * at, sizeof(Brick) * n, masks.data());
    leaves.values->write(2048 * at, 2048 * n, values.data());
    checkGl("partial leaves");
    leaves.count += uint32_t(n);
}

/// The band as NanoVDB leaves on the device, once the field is set up
/// (leavesOnDevice): distances, and for a signed field the inside voxels
/// negated (the parity scan's, or winding numbers', computed first), as
/// levelSetNanoGrids lays them out; with winding numbers, the leaves of the
/// bricks beyond the band it adds, and the whole bricks inside it makes tiles.
DeviceField deviceLeavesOf(Device& device, const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                           const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats,
                           const FieldSetup& f, bool bandOnly = false)
{
    checkpoint(0.0, "band bricks");
    describeBackend(device, Backend::Compute, stats);
    FieldRequest request = bandRequest(mesh, f, ls, settings, checkpoint, stats);
    request.deviceLeaves = true;
    request.bandOnly = bandOnly;
    request.leafScale = grid.voxelSize;
    request.leafBackground = float(ls.exteriorBand * grid.voxelSize); // as levelSetNanoGrids
    request.leafBands = {float(ls.exteriorBand), float(f.signedField ? ls.interiorBand : ls.exteriorBand)};
    FieldSigns signs;
    if (f.winding) {
        signs = windingSigns(device, mesh, f.g, request.bricks, ls.sign.windingAccuracy, std::nullopt,
                             checkpoint.part(0.05, 0.3), stats);
        request.insideVoxels = &signs.inside;
        request.extraLeaves = uint32_t(signs.partial.size());
    }
    FieldResult field = fieldPass(device.context(), mesh, f.g, request, false, stats);
    if (f.signedField && !f.winding)
        noteOpenColumns(stats, field.openColumns, "signs above its last crossing count as outside");
    if (f.winding) addPartialLeaves(device.context(), f.g, signs, request.leafBackground, field.leaves);
    stats.startup = device.takeStartup(stats.warnings);
    return {f.g, field.leaves, f.signedField, f.winding, std::move(signs.insideBricks)};
}

} // namespace

DistanceBricks levelSetBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                              const LevelSetOptions& ls, const VoxelizeSettings& settings,
                              const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    return bricksOf(device, mesh, ls, settings, checkpoint, stats, setUpField(mesh, grid, ls, settings, stats));
}

bool unsignedFieldOnDevice(Device& device, const LevelSetOptions& ls, const VoxelizeSettings& settings)
{
    return ls.unsignedDistance && !settings.region && !runsOnCpu(device, settings);
}

DeviceField unsignedFieldLeaves(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                                const LevelSetOptions& ls, const VoxelizeSettings& settings,
                                const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    if (!unsignedFieldOnDevice(device, ls, settings))
        throw InvalidInput("internal error: band leaves on the device need an unsigned field without a region on a GL backend");
    const FieldSetup f = setUpField(mesh, grid, ls, settings, stats);
    return deviceLeavesOf(device, mesh, grid, ls, settings, checkpoint, stats, f);
}

LevelSetOptions bandFieldOptions(double band)
{
    LevelSetOptions ls;
    ls.unsignedDistance = true;
    ls.exteriorBand = ls.interiorBand = band;
    return ls;
}

DistanceBricks bandTopologyBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid, double band,
                                  const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    const LevelSetOptions ls = bandFieldOptions(band);
    return bricksOf(device, mesh, ls, settings, checkpoint, stats, setUpField(mesh, grid, ls, settings, stats), true);
}

DeviceField bandTopologyLeaves(Device& device, const TriangleMesh& mesh, const GridSpec& grid, double band,
                               const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    const LevelSetOptions ls = bandFieldOptions(band);
    if (!unsignedFieldOnDevice(device, ls, settings))
        throw InvalidInput("internal error: band leaves on the device need no region and a GL backend");
    const FieldSetup f = setUpField(mesh, grid, ls, settings, stats);
    return deviceLeavesOf(device, mesh, grid, ls, settings, checkpoint, stats, f, true);
}

LevelSetBand levelSetBand(Device& device, const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                          const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    const FieldSetup f = setUpField(mesh, grid, ls, settings, stats);
    LevelSetBand out;
    if (leavesOnDevice(device, settings))
        out.device = deviceLeavesOf(device, mesh, grid, ls, settings, checkpoint, stats, f);
    else
        out.host = bricksOf(device, mesh, ls, settings, checkpoint, stats, f);
    return out;
}

SolidBricks solidBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                        const VoxelizeSettings& settings, const SignOptions& signOptions,
                        const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    checkFieldMode(settings); // the sign options: chooseSign
    if (settings.region) checkRegion(*settings.region);
    const SignChoice sign = chooseSign(mesh, signOptions, stats.warnings);
    const bool winding = sign.method == SignMethod::Winding;
    const GridSpec g = padded(grid, 2, mesh.source);
    checkpoint(0.0, "surface voxels");
    // Parity counts crossings from the bottom of each column: a region's
    // solid needs the surface of its columns, top to bottom. The band grows
    // a voxel from the surface, so a brick of the region can be in it for a
    // surface voxel just beyond the region's sides: the surface is taken a
    // brick past them, and the band is then the whole grid's there (regions'
    // bricks join into the whole grid's: svo/core/field_join.h).
    VoxelizeSettings surfaceSettings = settings;
    if (settings.region) {
        IndexBox& r = *surfaceSettings.region;
        for (int a = 0; a < 3; ++a) { // saturating: a region may lie anywhere in int64
            r.lo[a] = std::max(r.lo[a], INT64_MIN + 8) - 8;
            r.hi[a] = std::min(r.hi[a], INT64_MAX - 8) + 8;
        }
        if (!winding) {
            r.lo[2] = floorTo8(g.anchor[2]);
            r.hi[2] = floorTo8(g.anchor[2] + int64_t(g.dims[2]) + 7);
        }
    }
    const Octree surface = surfaceVoxels(device, mesh, g, surfaceSettings, stats);
    stats.sign = sign.why;
    checkpoint(0.3, "signs");

    // The first centre above a crossing is within 1 voxel of it.
    SolidBricks out;
    out.grid = g;
    out.bricks = forRegion(bandBricks(surface, 1, stats), g, settings.region, !winding);
    if (!runsOnCpu(device, settings)) checkFieldBudget(settings, out.bricks.size(), mesh);
    if (runsOnCpu(device, settings)) { // the surface voxels came from the CPU voxelizer too
        const std::vector<Vec3d> local = localPositions(mesh, g);
        if (winding) {
            out.signs = windingSignsCpu(device.windingTrees(), mesh, local, g, out.bricks, signOptions.windingAccuracy, settings.region,
                                        checkpoint.part(0.35, 0.8), stats);
        } else {
            checkpoint(0.35, "parity crossings");
            const std::vector<Brick> crossings = crossingsCpu(local, mesh, g, out.bricks, settings.region.has_value(), stats);
            checkpoint(0.7, "parity scan");
            const auto t0 = Clock::now();
            out.signs = paritySigns(out.bricks, crossings);
            stats.stages.push_back({"parity scan", -1, msSince(t0)});
        }
    } else if (winding) {
        out.signs = windingSigns(device, mesh, g, out.bricks, signOptions.windingAccuracy, settings.region,
                                 checkpoint.part(0.35, 0.8), stats);
    } else {
        FieldRequest request;
        request.bricks = out.bricks;
        request.checkpoint = checkpoint.part(0.35, 0.8);
        out.signs = paritySigns(out.bricks, fieldPass(device.context(), mesh, g, request, settings.region.has_value(), stats).crossings);
    }
    noteOpenColumns(stats, out.signs.openColumns, "the solid stops at its last crossing");
    addSurface(surface, out.bricks, out.signs.inside);
    return out;
}

} // namespace gl
} // namespace svo
