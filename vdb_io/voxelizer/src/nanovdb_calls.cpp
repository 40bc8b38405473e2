// NanoVDB grids from the front door (svo/voxelizer.h): the field passes'
// bricks laid out as NanoVDB grids (svo/vdb_io/nanovdb_grids.h), with no
// OpenVDB tree between them; on a GL backend, a field's grids built on the
// GPU from leaves that never leave it (svo/gl/nano_grid_builder.h), and a
// surface's and a solid's from their bricks uploaded; read back, or kept on
// the GPU for the caller (the ...OnDevice calls). Fields and solids cut into
// regions join their bricks (svo/core/field_join.h).
#include <cstring>
#include <tuple>
#include <type_traits>
#include <utility>

#include "svo/core/error.h"
#include "svo/core/field_clip.h"
#include "svo/core/field_join.h"
#include "svo/core/region.h"
#include "svo/gl/field_pipeline.h"
#include "svo/gl/nano_grid_builder.h"
#include "svo/gl/voxelize_pipeline.h"
#include "svo/vdb_io/nanovdb_checksum.h"
#include "svo/vdb_io/nanovdb_grids.h"
#include "svo/vdb_io/nanovdb_layout.h"
#include "svo/vdb_io/nanovdb_output.h"
#include "svo/voxelizer.h"
#include "built_grids.h"
#include "regions.h"
#include "voxelizer_state.h"

namespace svo {

using detail::BuiltGrids;
using detail::Clock;
using detail::InterruptScope;
using detail::msSince;

namespace {

constexpr const char* kFieldTask = "svo: computing a distance field";
constexpr const char* kSolidTask = "svo: filling a solid";
constexpr const char* kBandTask = "svo: finding a band";

/// The bracket of levelSetNanoVdb and solidNanoVdb: the checks (the same
/// transform rule as levelSet()), the interrupter, then `make(checkpoint,
/// stats)` (the field and its grids, its stages recorded), the counts of
/// its first grid and the statistics handed out. A `make` that keeps its
/// grids on the device returns nothing and sets the counts itself.
template <typename Make>
auto nanoCall(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options, const char* what,
              Make&& make) -> decltype(make(std::declval<const Checkpoint&>(), std::declval<VoxelizeStats&>()))
{
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    vdb::checkVdbGrid(grid, "grid");
    const InterruptScope interrupt(options.interrupter, what);
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    auto finish = [&] {
        checkpoint(1.0, "finish");
        if (options.stats) *options.stats = std::move(stats);
    };
    if constexpr (std::is_void_v<decltype(make(checkpoint, stats))>) {
        make(checkpoint, stats);
        finish();
    } else {
        std::vector<vdb::NanoHandle> out = make(checkpoint, stats);
        const auto* main = out.front().gridMetaData();
        stats.voxels = main ? main->activeVoxelCount() : 0;
        stats.bricks = main ? main->nodeCount(0) : 0;
        finish();
        return out;
    }
}

/// The CPU layout of device leaves read back (float or int32 values) and
/// the host tiles: the grid the GPU builder makes of them, with its checksum.
template <typename V>
vdb::NanoHandle laidOutOnHost(const gl::NanoLeaves& leaves, const gl::NanoGridHeader& header, V background,
                              bool checksum = true)
{
    static_assert(sizeof(V) == 4, "value words");
    vdb::SparseVoxels<V> s;
    s.background = background;
    const uint64_t n = leaves.count;
    s.origins.resize(n);
    s.masks.resize(n);
    s.values.resize(512 * n);
    if (n) {
        leaves.originBuffer->readBulk(0, 12 * n, s.origins.data());
        leaves.maskBuffer->readBulk(0, 64 * n, s.masks.data());
        leaves.valueBuffer->readBulk(0, 2048 * n, s.values.data());
    }
    for (uint32_t i = 0; i < leaves.tileCount; ++i) {
        const gl::NanoTile& t = leaves.tiles[i];
        V value;
        std::memcpy(&value, &t.value, 4);
        s.tiles.push_back({t.origin, 1, value, t.active != 0});
    }
    vdb::NanoGridInfo info;
    info.name = header.name;
    info.gridClass = nanovdb::GridClass(header.gridClass);
    info.voxelSize = header.voxelSize;
    info.translation = header.translation;
    info.checksum = checksum;
    return vdb::buildNanoGrid<V>(s, info);
}

/// The device field's leaves as the builder takes them (values: the distances).
gl::NanoLeaves leavesOf(const gl::DeviceField& field)
{
    gl::NanoLeaves leaves;
    leaves.count = field.leaves.count;
    leaves.originBuffer = field.leaves.origins;
    leaves.maskBuffer = field.leaves.masks;
    leaves.valueBuffer = field.leaves.values;
    return leaves;
}

/// The main grid's header, as levelSetNanoGrids makes it: "surface" (a level
/// set) for a signed field, "distance" for an unsigned one.
gl::NanoGridHeader distanceHeader(const GridSpec& grid, const LevelSetOptions& ls, bool signedField = false)
{
    gl::NanoGridHeader header;
    header.name = signedField ? "surface" : "distance";
    header.gridClass = uint32_t(signedField ? nanovdb::GridClass::LevelSet : nanovdb::GridClass::Unknown);
    header.voxelSize = grid.voxelSize;
    header.translation = grid.translation();
    header.background = double(float(ls.exteriorBand * grid.voxelSize));
    return header;
}

/// A winding-signed field's whole bricks inside beyond the band: inactive
/// 8³ tiles of the negated background.
std::vector<gl::NanoTile> insideTiles(const gl::DeviceField& field, float background)
{
    uint32_t word = 0;
    const float inside = -background;
    std::memcpy(&word, &inside, 4);
    std::vector<gl::NanoTile> tiles;
    tiles.reserve(field.insideBricks.size());
    for (const BrickCoord& b : field.insideBricks) {
        gl::NanoTile t;
        for (size_t a = 0; a < 3; ++a) t.origin[a] = int32_t(field.grid.anchor[a] + 8 * int64_t(b[a]));
        t.value = word;
        tiles.push_back(t);
    }
    return tiles;
}

/// A field's grids on the GPU: its band's leaves stay on the device
/// (gl::levelSetBand) and the builder lays out the grids levelSetNanoGrids
/// lays out on the host, byte for byte, into @a out: a winding-signed
/// field's whole bricks inside as tiles; a parity-signed field's values
/// beyond the band flood filled by the builder, as levelSetNanoGrids fills them.
void fieldGridsOnGpu(const gl::DeviceField& field, const GridSpec& grid, const LevelSetOptions& ls, BuiltGrids& out)
{
    gl::NanoLeaves leaves = leavesOf(field);
    gl::NanoGridHeader header = distanceHeader(grid, ls, field.signedField);
    const float background = float(header.background);
    const std::vector<gl::NanoTile> tiles = insideTiles(field, background);
    leaves.tileCount = uint32_t(tiles.size());
    leaves.tiles = tiles.data();
    header.signedFloodFill = field.signedField && !field.winding;
    out.add(gl::NanoKind::Float, leaves, header, [&] {
        if (!header.signedFloodFill) return laidOutOnHost<float>(leaves, header, background);
        vdb::NanoHandle h = laidOutOnHost<float>(leaves, header, background, false);
        vdb::signedFloodFill(*h.grid<float>());
        vdb::updateFullChecksum(*h.grid<float>());
        return h;
    });
    if (field.leaves.closest) {
        // The leaves with an active voxel come first: the closest triangles' grid has only those, and no tiles.
        leaves.count = field.leaves.activeCount;
        leaves.tileCount = 0;
        leaves.tiles = nullptr;
        leaves.valueBuffer = field.leaves.closest;
        header.name = "closest_triangle";
        header.gridClass = uint32_t(nanovdb::GridClass::Unknown);
        header.background = -1.0;
        header.signedFloodFill = false;
        out.add(gl::NanoKind::Int32, leaves, header, [&] { return laidOutOnHost<int32_t>(leaves, header, -1); });
    }
}

/// `bricks(options, checkpoint)` (a field's or a solid's) on the call's
/// region (none: the whole grid), cut into regions past a GPU memory budget
/// or past one shader buffer as levelSet() cuts them, and joined by `join`
/// (svo/core/field_join.h): each region's bricks are the whole grid's there,
/// so the result is the whole grid's bricks (of the call's region: cut to
/// it by the caller), with no OpenVDB tree. `pastOneBuffer`: the whole grid
/// is known not to fit (BufferLimit), so it is not tried again, and a
/// warning says so. Each region reports on its share of @a checkpoint; the
/// region count goes to `stats`.
template <typename Bricks, typename Join>
auto bricksInRegions(Bricks&& bricks, Join&& join, const VoxelizeOptions& options, const IndexBox& box,
                     bool pastOneBuffer, const Checkpoint& checkpoint, VoxelizeStats& stats)
    -> decltype(bricks(options, checkpoint))
{
    auto run = [&](const std::optional<IndexBox>& region, const Checkpoint& progress) {
        VoxelizeOptions part = options;
        part.region = region;
        stats = VoxelizeStats{};
        return bricks(part, progress);
    };
    if (!pastOneBuffer) return detail::withinBudget(run, join, options, box, checkpoint, stats);
    uint32_t tiles = 0;
    auto out = detail::allRegions(run, join, box, checkpoint, tiles);
    stats.tiles = tiles;
    stats.warnings.push_back(detail::pastOneBufferWarning(tiles));
    return out;
}

/// A field's grids laid out on the CPU (levelSetNanoGrids), a stage of `stats`.
std::vector<vdb::NanoHandle> fieldGridsOnHost(const DistanceBricks& field, const GridSpec& grid,
                                              const LevelSetOptions& ls, VoxelizeStats& stats)
{
    const auto t0 = Clock::now();
    std::vector<vdb::NanoHandle> out = vdb::levelSetNanoGrids(field, ls.exteriorBand, ls.interiorBand, grid);
    stats.stages.push_back({"nanovdb grid", -1, msSince(t0)});
    return out;
}

/// A band's grid (bandNanoGrid) laid out on the CPU, a stage of `stats`.
std::vector<vdb::NanoHandle> bandGridOnHost(const DistanceBricks& field, const GridSpec& grid, double band,
                                            GridOptions::Topology topology, VoxelizeStats& stats)
{
    const auto t0 = Clock::now();
    std::vector<vdb::NanoHandle> out;
    out.push_back(vdb::bandNanoGrid(field, band, grid, topology));
    stats.stages.push_back({"nanovdb grid", -1, msSince(t0)});
    return out;
}

/// A field, `fieldOf(options, checkpoint)` (gl::levelSetBricks, or a band's
/// gl::bandTopologyBricks), on the call's region or cut into regions
/// (bricksInRegions), laid out on the CPU by `layout(field)`
/// (fieldGridsOnHost, or bandGridOnHost): the whole grid's grids, or the
/// call's region's, cut to it (clipField) as levelSet() clips its grids.
template <typename FieldOf, typename Layout>
std::vector<vdb::NanoHandle> fieldInRegions(FieldOf&& fieldOf, const GridSpec& grid, const LevelSetOptions& ls,
                                            const VoxelizeOptions& options, bool pastOneBuffer,
                                            const Checkpoint& checkpoint, VoxelizeStats& stats, Layout&& layout)
{
    DistanceBricks field = bricksInRegions(fieldOf, joinFields, options, detail::fieldBox(grid, detail::levelSetPad(ls)),
                                           pastOneBuffer, checkpoint.part(0.0, 0.85), stats);
    if (options.region) clipField(field, bricksMeeting(field.grid, options.region));
    else field.region = false; // the regions make up the whole grid: a parity field's signs beyond the band are its fill's
    checkpoint(0.85, "nanovdb grid");
    return layout(field);
}

/// An octree's channel grids, byte for byte octreeChannelNanoGrids'. Read
/// back, they are laid out on the host: their 512 values a leaf are
/// expanded there either way, and uploading them (6 KB a leaf for Vec3f,
/// 2 KB for triangle ids) made a .nvdb with channels 0.74-1.01 times as fast
/// (bench/results/nvidia-h100/nanovdb/sdf-2026-12-05). Kept on the device,
/// each channel's leaves are uploaded to the GPU builder.
void channelGrids(const Octree& o, const GridOptions& grids, VoxelizeStats& stats, BuiltGrids& out)
{
    auto t0 = Clock::now();
    if (!out.onDevice()) {
        std::vector<vdb::NanoHandle> handles = vdb::octreeChannelNanoGrids(o, grids);
        if (handles.empty()) return;
        for (vdb::NanoHandle& h : handles) out.host().push_back(std::move(h));
        stats.stages.push_back({"nanovdb channels (cpu)", -1, msSince(t0)});
        return;
    }
    const std::vector<vdb::OctreeChannel> channels = vdb::octreeChannelVoxels(o, grids);
    if (channels.empty()) return;
    stats.stages.push_back({"nanovdb channel leaves", -1, msSince(t0)});
    for (const vdb::OctreeChannel& c : channels) {
        gl::NanoLeaves leaves;
        const auto& origins = c.vector ? c.vectors.origins : c.ints.origins;
        leaves.count = uint32_t(origins.size());
        leaves.origins = origins.data();
        leaves.masks = c.vector ? c.vectors.masks.data() : c.ints.masks.data();
        static_assert(sizeof(nanovdb::Vec3f) == 12, "three float words");
        leaves.values = c.vector ? reinterpret_cast<const uint32_t*>(c.vectors.values.data())
                                 : reinterpret_cast<const uint32_t*>(c.ints.values.data());
        gl::NanoGridHeader header;
        header.name = c.name;
        header.gridClass = uint32_t(nanovdb::GridClass::Unknown);
        header.voxelSize = o.grid.voxelSize;
        header.translation = o.grid.translation();
        header.background = c.vector ? 0.0 : -1.0;
        vdb::NanoGridInfo info;
        info.name = c.name;
        info.voxelSize = o.grid.voxelSize;
        info.translation = o.grid.translation();
        auto onHost = [&] {
            return c.vector ? vdb::buildNanoGrid<nanovdb::Vec3f>(c.vectors, info) : vdb::buildNanoGrid<int32_t>(c.ints, info);
        };
        out.add(c.vector ? gl::NanoKind::Vec3f : gl::NanoKind::Int32, leaves, header, onHost);
    }
}

/// An octree's grids built on the GPU, byte for byte octreeToNanoGrids':
/// the topology and fog from its bricks (uploaded: 76 bytes a leaf), then
/// the channels. Stages are added to `stats`.
void surfaceGridsOnGpu(const Octree& o, const GridOptions& grids, VoxelizeStats& stats, BuiltGrids& out)
{
    auto t0 = Clock::now();
    const OctreeLeaves bricks = octreeLeaves(o);
    stats.stages.push_back({"nanovdb leaves", -1, msSince(t0)});
    gl::NanoLeaves leaves;
    leaves.count = uint32_t(bricks.origins.size());
    leaves.origins = bricks.origins.data();
    leaves.masks = bricks.masks.data();
    gl::NanoGridHeader header;
    header.name = grids.name;
    header.voxelSize = o.grid.voxelSize;
    header.translation = o.grid.translation();
    const bool mask = grids.topology == GridOptions::Topology::Mask;
    // NanoVDB keeps class Topology for ValueMask grids (nanovdb::isValid); bool grids are Unknown.
    header.gridClass = uint32_t(mask ? nanovdb::GridClass::Topology : nanovdb::GridClass::Unknown);
    // Past the builder's limits: octreeToNanoGrids' grid of that kind.
    auto onHost = [&](bool fog) {
        GridOptions one = grids;
        one.fog = fog;
        one.attributes = false;
        return [&o, one, fog] { return std::move(vdb::octreeToNanoGrids(o, one)[fog ? 1 : 0]); };
    };
    out.add(mask ? gl::NanoKind::Mask : gl::NanoKind::Bool, leaves, header, onHost(false));
    if (grids.fog) {
        const float one = 1.0f;
        uint32_t word = 0;
        std::memcpy(&word, &one, 4);
        leaves.activeWord = word;
        header.name = "density";
        header.gridClass = uint32_t(nanovdb::GridClass::FogVolume);
        out.add(gl::NanoKind::Float, leaves, header, onHost(true));
    }
    channelGrids(o, grids, stats, out);
}

/// Host leaves and 8³ tiles as the builder takes them (the tiles' words
/// in @a tiles, which must outlive the leaves); values are not passed.
gl::NanoLeaves hostLeaves(const vdb::SparseVoxels<bool>& s, std::vector<gl::NanoTile>& tiles)
{
    gl::NanoLeaves leaves;
    leaves.count = uint32_t(s.origins.size());
    leaves.origins = s.origins.data();
    leaves.masks = s.masks.data();
    tiles.clear();
    for (const auto& t : s.tiles) tiles.push_back({t.origin, uint32_t(t.value), uint32_t(t.active)});
    leaves.tileCount = uint32_t(tiles.size());
    leaves.tiles = tiles.data();
    return leaves;
}

/// A solid's grid on the GPU builder from its voxels (vdb::solidVoxels,
/// uploaded: 76 bytes a leaf, 20 a tile), byte for byte solidNanoGrid's.
void solidGridOnGpu(const SolidBricks& bricks, const GridSpec& grid, GridOptions::Topology topology,
                    VoxelizeStats& stats, BuiltGrids& out)
{
    auto t0 = Clock::now();
    const vdb::SparseVoxels<bool> voxels = vdb::solidVoxels(bricks);
    stats.stages.push_back({"nanovdb leaves", -1, msSince(t0)});
    std::vector<gl::NanoTile> tiles;
    const gl::NanoLeaves leaves = hostLeaves(voxels, tiles);
    gl::NanoGridHeader header;
    header.name = "solid";
    header.voxelSize = grid.voxelSize;
    header.translation = grid.translation();
    const bool mask = topology == GridOptions::Topology::Mask;
    header.gridClass = uint32_t(mask ? nanovdb::GridClass::Topology : nanovdb::GridClass::Unknown);
    out.add(mask ? gl::NanoKind::Mask : gl::NanoKind::Bool, leaves, header,
            [&] { return vdb::solidNanoGrid(bricks, grid, topology); });
}

/// A band's grid on the GPU builder from its leaves on the device (masks
/// only), byte for byte bandNanoGrid's.
void bandGridOnGpu(const gl::DeviceField& field, const GridSpec& grid, GridOptions::Topology topology,
                   BuiltGrids& out)
{
    gl::NanoLeaves leaves = leavesOf(field);
    leaves.valueBuffer = nullptr;
    gl::NanoGridHeader header;
    header.name = "band";
    header.voxelSize = grid.voxelSize;
    header.translation = grid.translation();
    const bool mask = topology == GridOptions::Topology::Mask;
    header.gridClass = uint32_t(mask ? nanovdb::GridClass::Topology : nanovdb::GridClass::Unknown);
    out.add(mask ? gl::NanoKind::Mask : gl::NanoKind::Bool, leaves, header, [&] {
        // Past the builder's limits: the leaves read back, laid out on the host.
        vdb::SparseVoxels<bool> s;
        const uint64_t n = leaves.count;
        s.origins.resize(n);
        s.masks.resize(n);
        if (n) {
            leaves.originBuffer->readBulk(0, 12 * n, s.origins.data());
            leaves.maskBuffer->readBulk(0, 64 * n, s.masks.data());
        }
        vdb::NanoGridInfo info;
        info.name = header.name;
        info.gridClass = nanovdb::GridClass(header.gridClass);
        info.voxelSize = header.voxelSize;
        info.translation = header.translation;
        return mask ? vdb::buildNanoGrid<nanovdb::ValueMask>(s, info) : vdb::buildNanoGrid<bool>(s, info);
    });
}

/// `make(out)` with the grids built in @a context and read back: their handles.
template <typename Make>
std::vector<vdb::NanoHandle> readBack(const gl::Context& context, VoxelizeStats& stats, Make&& make)
{
    const gl::Context::Scope scope(context); // the leaves' buffers and the grids'
    BuiltGrids out(context, false, stats);
    make(out);
    return std::move(out.host());
}

/// `make(out)` with the grids built in @a context and kept there, handed to
/// @a use while the context is current, then freed.
template <typename Make>
void keptOnDevice(const gl::Context& context, VoxelizeStats& stats, const NanoGridsOnDevice& use, Make&& make)
{
    const gl::Context::Scope scope(context); // the grids are made, used and freed in it
    BuiltGrids out(context, true, stats);
    make(out);
    use(out.device());
}

/// nanoCall's checks, interrupter and statistics for grids kept on the
/// device: `make(checkpoint, stats, out)` builds them into `out`, and @a use
/// gets them.
template <typename Make>
void nanoCallOnDevice(gl::Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                      const VoxelizeOptions& options, const char* what, const NanoGridsOnDevice& use, Make&& make)
{
    nanoCall(mesh, grid, options, what, [&](const Checkpoint& checkpoint, VoxelizeStats& stats) {
        keptOnDevice(device.context(), stats, use, [&](BuiltGrids& out) {
            make(checkpoint, stats, out);
            std::tie(stats.voxels, stats.bricks) = out.firstDeviceCounts();
        });
    });
}

} // namespace

std::vector<vdb::NanoHandle> Voxelizer::voxelizeNanoVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                                        const VoxelizeOptions& options, const GridOptions& grids)
{
    return octreeNanoVdb(voxelize(mesh, grid, options), grids, options);
}

std::vector<vdb::NanoHandle> Voxelizer::octreeNanoVdb(const Octree& octree, const GridOptions& grids,
                                                      const VoxelizeOptions& options)
{
    VoxelizeStats local;
    VoxelizeStats& stats = options.stats ? *options.stats : local;
    // On a GL backend (the test runsOnCpu makes for level sets and solids).
    if (!gl::runsOnCpu(device_, options))
        return readBack(device_.context(), stats, [&](BuiltGrids& out) { surfaceGridsOnGpu(octree, grids, stats, out); });
    const auto t0 = Clock::now();
    std::vector<vdb::NanoHandle> out = vdb::octreeToNanoGrids(octree, grids);
    stats.stages.push_back({"nvdb build (cpu)", -1, msSince(t0)});
    return out;
}

void Voxelizer::octreeNanoVdbOnDevice(const Octree& octree, const GridOptions& grids, const VoxelizeOptions& options,
                                      const NanoGridsOnDevice& use)
{
    if (gl::runsOnCpu(device_, options))
        throw Unsupported("an octree's NanoVDB grids stay on the GPU only on a GL backend (not Backend::Cpu, nor "
                          "Auto on a software renderer)");
    VoxelizeStats local;
    VoxelizeStats& stats = options.stats ? *options.stats : local;
    keptOnDevice(device_.context(), stats, use, [&](BuiltGrids& out) { surfaceGridsOnGpu(octree, grids, stats, out); });
}

std::vector<vdb::NanoHandle> Voxelizer::levelSetNanoVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                                        const LevelSetOptions& ls, const VoxelizeOptions& options)
{
    auto inRegions = [&](bool pastOneBuffer) {
        return nanoCall(mesh, grid, options, kFieldTask, [&](const Checkpoint& checkpoint, VoxelizeStats& stats) {
            auto fieldOf = [&](const VoxelizeOptions& part, const Checkpoint& progress) {
                return gl::levelSetBricks(device_, mesh, grid, ls, part, progress, stats);
            };
            return fieldInRegions(fieldOf, grid, ls, options, pastOneBuffer, checkpoint, stats,
                                  [&](const DistanceBricks& field) { return fieldGridsOnHost(field, grid, ls, stats); });
        });
    };
    if (options.gpuMemory || options.region) return inRegions(false);
    auto make = [&](const Checkpoint& checkpoint, VoxelizeStats& stats) {
        const gl::LevelSetBand band = gl::levelSetBand(device_, mesh, grid, ls, options, checkpoint, stats);
        checkpoint(0.85, "nanovdb grid");
        if (!band.device) return fieldGridsOnHost(band.host, grid, ls, stats);
        return readBack(device_.context(), stats,
                        [&](BuiltGrids& out) { fieldGridsOnGpu(*band.device, grid, ls, out); });
    };
    try {
        return nanoCall(mesh, grid, options, kFieldTask, make);
    } catch (const BufferLimit&) {
        return inRegions(true);
    }
}

void Voxelizer::levelSetNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                                        const VoxelizeOptions& options, const NanoGridsOnDevice& use)
{
    if (options.region || options.gpuMemory || gl::runsOnCpu(device_, options))
        throw Unsupported("a field's NanoVDB grids stay on the GPU only on a GL backend, without a region or a GPU "
                          "memory budget");
    nanoCallOnDevice(device_, mesh, grid, options, kFieldTask, use,
                     [&](const Checkpoint& checkpoint, VoxelizeStats& stats, BuiltGrids& out) {
                         const gl::LevelSetBand band =
                             gl::levelSetBand(device_, mesh, grid, ls, options, checkpoint, stats);
                         checkpoint(0.85, "nanovdb grid");
                         fieldGridsOnGpu(*band.device, grid, ls, out); // on a GL backend, no region: on the device
                     });
}

void Voxelizer::unsignedFieldNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                                             const VoxelizeOptions& options, const NanoGridsOnDevice& use)
{
    if (!ls.unsignedDistance)
        throw Unsupported("unsignedFieldNanoVdbOnDevice takes an unsigned distance field; levelSetNanoVdbOnDevice "
                          "takes level sets too");
    levelSetNanoVdbOnDevice(mesh, grid, ls, options, use);
}

vdb::NanoHandle Voxelizer::bandNanoVdb(const TriangleMesh& mesh, const GridSpec& grid, double band,
                                       const VoxelizeOptions& options, GridOptions::Topology topology)
{
    const LevelSetOptions ls = detail::bandOptions(band);
    auto onHost = [&](const DistanceBricks& field, VoxelizeStats& stats) {
        return bandGridOnHost(field, grid, band, topology, stats);
    };
    auto inRegions = [&](bool pastOneBuffer) {
        return nanoCall(mesh, grid, options, kBandTask, [&](const Checkpoint& checkpoint, VoxelizeStats& stats) {
            auto fieldOf = [&](const VoxelizeOptions& part, const Checkpoint& progress) {
                return gl::bandTopologyBricks(device_, mesh, grid, band, part, progress, stats);
            };
            return fieldInRegions(fieldOf, grid, ls, options, pastOneBuffer, checkpoint, stats,
                                  [&](const DistanceBricks& field) { return onHost(field, stats); });
        });
    };
    if (options.gpuMemory || options.region) return std::move(inRegions(false).front());
    auto make = [&](const Checkpoint& checkpoint, VoxelizeStats& stats) {
        if (!gl::unsignedFieldOnDevice(device_, ls, options)) {
            const DistanceBricks field = gl::bandTopologyBricks(device_, mesh, grid, band, options, checkpoint, stats);
            checkpoint(0.85, "nanovdb grid");
            return onHost(field, stats);
        }
        const gl::DeviceField field = gl::bandTopologyLeaves(device_, mesh, grid, band, options, checkpoint, stats);
        checkpoint(0.85, "nanovdb grid");
        return readBack(device_.context(), stats, [&](BuiltGrids& out) { bandGridOnGpu(field, grid, topology, out); });
    };
    try {
        return std::move(nanoCall(mesh, grid, options, kBandTask, make).front());
    } catch (const BufferLimit&) {
        return std::move(inRegions(true).front());
    }
}

void Voxelizer::bandNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, double band,
                                    const VoxelizeOptions& options, GridOptions::Topology topology,
                                    const NanoGridsOnDevice& use)
{
    const LevelSetOptions ls = detail::bandOptions(band);
    if (!gl::unsignedFieldOnDevice(device_, ls, options) || options.gpuMemory)
        throw Unsupported("a band's NanoVDB grid stays on the GPU only on a GL backend, without a region or a GPU "
                          "memory budget");
    nanoCallOnDevice(device_, mesh, grid, options, kBandTask, use,
                     [&](const Checkpoint& checkpoint, VoxelizeStats& stats, BuiltGrids& out) {
                         const gl::DeviceField field =
                             gl::bandTopologyLeaves(device_, mesh, grid, band, options, checkpoint, stats);
                         checkpoint(0.85, "nanovdb grid");
                         bandGridOnGpu(field, grid, topology, out);
                     });
}

vdb::NanoHandle Voxelizer::solidNanoVdb(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                        const SignOptions& sign, GridOptions::Topology topology)
{
    auto bricksOf = [&](const VoxelizeOptions& part, const Checkpoint& checkpoint, VoxelizeStats& stats) {
        return gl::solidBricks(device_, mesh, grid, part, sign, checkpoint, stats);
    };
    auto gridOf = [&](const SolidBricks& bricks, const Checkpoint& checkpoint, VoxelizeStats& stats) {
        checkpoint(0.8, "nanovdb grid");
        if (!gl::runsOnCpu(device_, options))
            return readBack(device_.context(), stats,
                            [&](BuiltGrids& out) { solidGridOnGpu(bricks, grid, topology, stats, out); });
        const auto t0 = Clock::now();
        std::vector<vdb::NanoHandle> grids;
        grids.push_back(vdb::solidNanoGrid(bricks, grid, topology));
        stats.stages.push_back({"nanovdb grid", -1, msSince(t0)});
        return grids;
    };
    // On the call's region, past a budget or past one shader buffer: the
    // regions' bricks joined (bricksInRegions) and cut to the call's region, then the same grid.
    auto inRegions = [&](bool pastOneBuffer) {
        return std::move(nanoCall(mesh, grid, options, kSolidTask, [&](const Checkpoint& checkpoint, VoxelizeStats& stats) {
                             auto bricks = [&](const VoxelizeOptions& part, const Checkpoint& progress) {
                                 return bricksOf(part, progress, stats);
                             };
                             SolidBricks joined = bricksInRegions(bricks, joinSolids, options,
                                                                  detail::fieldBox(grid, detail::kSolidPad), pastOneBuffer,
                                                                  checkpoint.part(0.0, 0.8), stats);
                             if (options.region) clipSolid(joined, bricksMeeting(joined.grid, options.region));
                             return gridOf(joined, checkpoint, stats);
                         }).front());
    };
    if (options.gpuMemory || options.region) return inRegions(false);
    try {
        return std::move(nanoCall(mesh, grid, options, kSolidTask, [&](const Checkpoint& checkpoint, VoxelizeStats& stats) {
                             return gridOf(bricksOf(options, checkpoint, stats), checkpoint, stats);
                         }).front());
    } catch (const BufferLimit&) {
        return inRegions(true);
    }
}

void Voxelizer::solidNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                     const SignOptions& sign, GridOptions::Topology topology,
                                     const NanoGridsOnDevice& use)
{
    if (options.region || options.gpuMemory || gl::runsOnCpu(device_, options))
        throw Unsupported("a solid's NanoVDB grid stays on the GPU only on a GL backend, without a region or a GPU "
                          "memory budget");
    nanoCallOnDevice(device_, mesh, grid, options, kSolidTask, use,
                     [&](const Checkpoint& checkpoint, VoxelizeStats& stats, BuiltGrids& out) {
                         const SolidBricks bricks = gl::solidBricks(device_, mesh, grid, options, sign, checkpoint, stats);
                         checkpoint(0.8, "nanovdb grid");
                         solidGridOnGpu(bricks, grid, topology, stats, out);
                     });
}

} // namespace svo
