// The GPU passes of distance_field.h: work items, the brick table, the
// distance and crossing passes, and the readback.
#include "svo/gl/distance_field.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "svo/gl/buffer.h"
#include "svo/gl/dispatch_looping.h"
#include "svo/gl/fill_words.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "svo/gl/timer_query.h"
#include "svo/gl/wait_for_gpu.h"
#include "svo/core/error.h"
#include "svo/core/parity_scan.h"
#include "field_layout.h"
#include "svo/gl/winding_number.h"
#include "fields_shaders.h"

namespace svo::gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// The brick table of field_layout.h: kTableWords uints per slot, at most half full.
std::vector<uint32_t> brickTable(const std::vector<std::array<uint32_t, 3>>& bricks, uint32_t& mask)
{
    uint64_t slots = 16;
    while (slots < 2 * uint64_t(bricks.size())) slots *= 2;
    if (slots > (uint64_t(1) << 30)) throw Unsupported(fmt::format("{} bricks are more than the brick table holds", bricks.size()));
    mask = uint32_t(slots - 1);
    std::vector<uint32_t> table(slots * gpu::kTableWords, 0);
    for (uint64_t s = 0; s < slots; ++s) table[s * gpu::kTableWords + 3] = gpu::kNoChild;
    for (uint32_t i = 0; i < bricks.size(); ++i) {
        const auto& b = bricks[i];
        uint32_t s = SVO_BRICK_HASH(b[0], b[1], b[2]) & mask;
        while (table[s * gpu::kTableWords + 3] != gpu::kNoChild) {
            const uint32_t* w = &table[s * gpu::kTableWords];
            if (w[0] == b[0] && w[1] == b[1] && w[2] == b[2])
                throw DeviceError(fmt::format("internal error: brick ({}, {}, {}) requested twice", b[0], b[1], b[2]));
            s = (s + 1) & mask;
        }
        uint32_t* w = &table[s * gpu::kTableWords];
        w[0] = b[0], w[1] = b[1], w[2] = b[2], w[3] = i;
    }
    return table;
}

/// Per triangle the voxel box its items cover (field_common.glsl): voxels
/// within `grow` of its bounding box, or with grow < 0 its columns only (a
/// box one voxel deep at z = 0). With `oneItemBoxes`, a box no wider than a
/// brick on every axis is one item; any other is an item per brick (or brick
/// column) it spans, so an item's box always fits in 8 x 8 x 8 voxels. Fills
/// the exclusive prefix sum of the items and returns their total. With
/// `whole`, the one-item triangles count no item but are listed there
/// instead (a thread each).
uint64_t workItems(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid, double grow,
                   bool oneItemBoxes, std::vector<uint32_t>& items, std::vector<uint32_t>* whole)
{
    const size_t n = mesh.triangles.size();
    items.assign(n * gpu::kItemWords, 0);
    std::vector<uint64_t> counts(n);
    const bool columns = grow < 0;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            uint64_t bricks = 1;
            bool small = oneItemBoxes;
            uint32_t* w = &items[t * gpu::kItemWords];
            for (int a = 0; a < 3; ++a) {
                if (columns && a == 2) {
                    w[3] = 0, w[6] = 1;
                    continue;
                }
                const double lo = std::min({local[f[0]][a], local[f[1]][a], local[f[2]][a]});
                const double hi = std::max({local[f[0]][a], local[f[1]][a], local[f[2]][a]});
                const double g = columns ? 0.0 : grow;
                const double first = std::max(std::ceil(lo - g), 0.0);
                const double last = std::min(std::floor(hi + g), double(grid.dims[a]) - 1);
                if (last < first) {
                    bricks = 0;
                    break;
                }
                const auto v0 = uint32_t(first), v1 = uint32_t(last);
                w[1 + a] = v0;
                w[4 + a] = v1 - v0 + 1;
                small = small && v1 - v0 < (1u << gpu::kBrickLog2);
                bricks *= (v1 >> gpu::kBrickLog2) - (v0 >> gpu::kBrickLog2) + 1;
            }
            w[7] = small ? 1 : 0;
            counts[t] = bricks == 0 ? 0 : small ? 1 : bricks;
        }
    });
    uint64_t total = 0;
    for (size_t t = 0; t < n; ++t) {
        items[t * gpu::kItemWords] = uint32_t(std::min<uint64_t>(total, 0xFFFFFFFFu));
        if (whole && items[t * gpu::kItemWords + 7] && counts[t]) whole->push_back(uint32_t(t));
        else total += counts[t];
    }
    return total;
}

/// Runs `program` over items [0, items): workgroups loop over them, enough
/// to fill a large GPU, few on a CPU rasterizer, where each group costs. A
/// thread of an item loops at most `iterations` times, for the driver's loop
/// limit.
void dispatchItems(const Context& context, const Program& program, uint64_t items, uint64_t iterations)
{
    const ContextInfo& info = context.info();
    const auto groups = uint32_t(std::min<uint64_t>(items, info.software ? 256 : 65535));
    dispatchLooping(program, items, groups, info.loopLimit, iterations, "uItemFirst", "uItems");
}

/// The work items of each pass computeField runs (workItems), and the
/// one-item triangles listed apart.
struct FieldItems {
    std::vector<uint32_t> distanceItems, crossingItems, distanceWhole, crossingWhole;
    uint64_t nDistance = 0, nCrossing = 0;
};

/// A thread per small triangle: for crossings everywhere (a few columns
/// each); for distances as FieldWork says. On an H100 a workgroup per
/// brick ran faster than a thread per small triangle (whose up to 512
/// centres run one after another) from 1024³ up
/// (bench/results/nvidia-h100/band_ab.md).
FieldItems fieldItems(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                      const FieldRequest& request, bool smallTriangles)
{
    const bool distances = request.band > 0;
    FieldItems w;
    w.nDistance = distances ? workItems(local, mesh, grid, request.band, smallTriangles, w.distanceItems,
                                        smallTriangles ? &w.distanceWhole : nullptr)
                            : 0;
    w.nCrossing = request.crossings ? workItems(local, mesh, grid, -1.0, true, w.crossingItems, &w.crossingWhole) : 0;
    return w;
}

/// Refuses work no pass holds, and arrays no shader buffer holds
/// (Context::shaderBufferLimit): refused, never cut short; the band's arrays
/// as a BufferLimit, since a smaller region of the grid fits.
void checkFieldLimits(const Context& context, const TriangleMesh& mesh, const FieldRequest& request,
                      const FieldItems& w)
{
    const uint64_t nb = request.bricks.size();
    const bool distances = request.band > 0;
    for (uint64_t n : {w.nDistance, w.nCrossing})
        if (n > 0xFFFFFFFFu)
            throw Unsupported(fmt::format("the distance field needs {} brick work items, more than one pass holds (2^32); "
                                          "use a coarser grid or a narrower band",
                                          n));
    if (distances && nb > (uint64_t(1) << 23))
        throw Unsupported(fmt::format("the band has {} bricks, more than one distance pass holds (2^23); use a coarser "
                                      "grid or a narrower band",
                                      nb));
    const uint64_t block = context.shaderBufferLimit();
    if (!block) return;
    const uint64_t corners = uint64_t(mesh.positions.size()) * sizeof(Vec3d);
    if (corners > block)
        throw DeviceError(fmt::format("the mesh's {} corners need {} bytes in one GPU buffer, more than the {} a shader "
                                      "addresses",
                                      mesh.positions.size(), corners, block));
    // The band's arrays shrink with the grid: a BufferLimit, which the front
    // door answers with smaller regions.
    const uint64_t largest = std::max(distances ? nb * 512 * 4 : 0, request.crossings ? nb * sizeof(Brick) : 0);
    if (largest > block)
        throw BufferLimit(fmt::format("the band's {} bricks need {} bytes in one GPU buffer, more than the {} a shader "
                                      "addresses; use a coarser grid or a narrower band",
                                      nb, largest, block));
}

/// The mesh, the brick table and the counters uploaded, and the per-brick
/// outputs of the passes (scratch buffers, cleared): distances, closest
/// triangles and crossings, each only when the request asks for it.
struct FieldBuffers {
    FieldBuffers(const Context& context, const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                 const std::vector<uint32_t>& table, const FieldRequest& request)
        : positions("field positions", local.size() * sizeof(Vec3d), local.data()),
          indices("field indices", mesh.triangles.size() * 12, mesh.triangles.data()),
          tableBuffer("brick table", table.size() * 4, table.data()), counters("field counters", 16)
    {
        const uint64_t nb = request.bricks.size();
        counters.clearUint(0);
        const uint32_t none = 0xFFFFFFFFu, inf = 0x7F800000u; // float +inf
        if (request.band > 0) {
            // Filled by a shader, not cleared: see fill_words.h.
            distances = &context.scratch("field distances", std::max<uint64_t>(nb, 1) * 512 * 4);
            fillWords(context, *distances, inf, nb * 512 * 4);
            if (request.closestTriangle) {
                closest = &context.scratch("field closest triangles", std::max<uint64_t>(nb, 1) * 512 * 4);
                fillWords(context, *closest, none, nb * 512 * 4);
            }
        }
        if (request.crossings) {
            flips = &context.scratch("field crossings", std::max<uint64_t>(nb, 1) * sizeof(Brick));
            flips->clearUint(0, nb * sizeof(Brick));
        }
    }
    /// The mesh's slots (and the table's), which band packing also uses.
    void bindMesh() const
    {
        positions.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_POSITIONS);
        indices.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_INDICES);
        tableBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_TABLE);
    }
    void bindAll() const
    {
        bindMesh();
        counters.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_COUNTERS);
        if (distances) distances->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_DISTANCES);
        if (closest) closest->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_CLOSEST);
        if (flips) flips->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_FLIPS);
    }

    const Buffer positions, indices, tableBuffer, counters;
    const Buffer* distances = nullptr;
    const Buffer* closest = nullptr;
    const Buffer* flips = nullptr;
};

/// Runs the distance and crossing passes over their work items, each timed
/// into `stats`, polling the request's checkpoint while the GPU works.
struct FieldPasses {
    const Context& context;
    const TriangleMesh& mesh;
    const FieldRequest& request;
    uint32_t tableMask;
    RunStats& stats;

    /// One pass over a set of items and one-item triangles, timed, by a
    /// program of `groupSize` threads a workgroup. A thread of an item loops
    /// at most `itemIterations` times, one of a one-item triangle at most
    /// `wholeIterations` (its columns, their centres and brick probes); a
    /// workgroup's threads share the units of its dispatch, with a margin
    /// for the loop around them.
    void run(const char* name, const Program& program, uint32_t groupSize, const std::vector<uint32_t>& items,
             uint64_t n, uint64_t itemIterations, const std::vector<uint32_t>* whole, uint64_t wholeIterations) const
    {
        const auto w0 = Clock::now();
        TimerQuery timer;
        const size_t records = items.size(), listed = whole ? whole->size() : 0;
        const Buffer itemBuffer("field work items", std::max<size_t>(records + listed, 1) * 4);
        if (records) itemBuffer.write(0, records * 4, items.data());
        if (listed) itemBuffer.write(records * 4, listed * 4, whole->data());
        timer.begin();
        itemBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_ITEMS);
        program.set("uTriangles", uint32_t(mesh.triangles.size()));
        program.set("uTableMask", tableMask);
        if (whole) {
            program.set("uWhole", 0u);
            program.set("uWholeStart", uint32_t(records));
        }
        dispatchItems(context, program, n, itemIterations);
        if (listed) {
            program.set("uWhole", 1u);
            const ContextInfo& info = context.info();
            const auto groups =
                uint32_t(std::min<uint64_t>((listed + groupSize - 1) / groupSize, info.software ? 256 : 65535));
            dispatchLooping(program, listed, groups, info.loopLimit, wholeIterations / groupSize + 4, "uItemFirst",
                            "uItems");
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        timer.end();
        checkGl(name);
        waitForGpu([&] { request.checkpoint(0.5, "distance field"); });
        stats.stages.push_back({name, timer.milliseconds(), msSince(w0)});
    }

    /// The band's distances, then (when asked) each voxel's closest triangle.
    void distances(const FieldItems& w, bool smallTriangles, bool closest) const
    {
        const Program& program =
            context.program(fieldsShaders(), {smallTriangles ? "band_distance_columns.comp" : "band_distance.comp"});
        program.set("uBand", float(request.band));
        program.set("uPass", 0u);
        // A band's topology: a voxel is in once a distance below the band the
        // leaves (or the host) compare with is kept.
        const float known = request.deviceLeaves ? request.leafBands[0] : float(request.band);
        program.set("uKnownBelow", request.bandOnly ? known : 0.0f);
        // band_distance.comp: 64 threads, an item's thread loops 1 + 64
        // (triangleOfItemFrom's gallop and search; the run's first item
        // searches all triangles, 32) + 8 (its column) times and probes the
        // brick table once, a short probe at half load. The columns: 8
        // threads (one SIMD vector of llvmpipe, which runs a workgroup's
        // vectors one after another, each through the whole loop), an item's
        // thread 1 + 64 (triangleOfItemFrom) + one probe + 8 columns of 8
        // centres; a one-item triangle's 8 probes, 64 columns and 512
        // centres.
        const uint32_t groupSize = smallTriangles ? 8 : 64;
        const uint64_t itemIterations = smallTriangles ? 512 : 256, wholeIterations = 1024;
        const std::vector<uint32_t>* whole = smallTriangles ? &w.distanceWhole : nullptr;
        run("band distance", program, groupSize, w.distanceItems, w.nDistance, itemIterations, whole, wholeIterations);
        if (closest) {
            program.set("uPass", 1u);
            run("closest triangle", program, groupSize, w.distanceItems, w.nDistance, itemIterations, whole,
                wholeIterations);
        }
    }

    void crossings(const GridSpec& grid, const FieldItems& w) const
    {
        const Program& program = context.program(fieldsShaders(), {"parity_flips.comp"});
        program.set("uDimZ", grid.dims[2]);
        // 64 threads; an item's thread loops 1 + 32 times and probes once,
        // a one-item triangle's thread takes 64 columns, a probe each.
        run("parity crossings", program, 64, w.crossingItems, w.nCrossing, 256, &w.crossingWhole, 256);
    }
};

/// The band packed: a mask, an offset and the kept values per brick.
struct PackedBand {
    const Buffer* masks = nullptr;
    const Buffer* offsets = nullptr;
    const Buffer* distances = nullptr;
    const Buffer* closest = nullptr;
};

/// Packs the band's distances (and closest triangles) into scratch buffers,
/// timed into `stats`; the mesh's slots are the field passes' again after.
PackedBand packBand(const Context& context, const FieldBuffers& buffers, const FieldRequest& request,
                    bool smallTriangles, RunStats& stats)
{
    const uint64_t nb = request.bricks.size();
    const bool software = context.info().software;
    PackedBand packed;
    packed.masks = &context.scratch("band masks", std::max<uint64_t>(nb, 1) * sizeof(Brick));
    packed.offsets = &context.scratch("band offsets", std::max<uint64_t>(nb, 1) * 4);
    packed.distances = &context.scratch("band packed distances", std::max<uint64_t>(nb, 1) * 2048);
    if (buffers.closest) packed.closest = &context.scratch("band packed closest", std::max<uint64_t>(nb, 1) * 2048);
    packed.masks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPACT_MASKS);
    packed.offsets->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPACT_OFFSETS);
    packed.distances->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPACT_DISTANCES);
    (packed.closest ? packed.closest : packed.distances)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPACT_CLOSEST);
    if (!buffers.closest) buffers.distances->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_CLOSEST);
    const auto w0 = Clock::now();
    TimerQuery timer;
    timer.begin();
    // With the CPU rasterizers' cut, a thread a brick, looping 1 + 16 *
    // 33 + 16 + 512 times at most (band_compact_bricks.comp), 8 threads
    // a workgroup sharing its bricks (so the limit a brick is an eighth
    // of that, with a margin); else a workgroup a brick, whose threads
    // loop 1 + 8 + 64 + 8 times (band_compact.comp).
    const Program& program =
        context.program(fieldsShaders(), {smallTriangles ? "band_compact_bricks.comp" : "band_compact.comp"});
    program.set("uBand", float(request.band));
    program.set("uClosest", buffers.closest ? 1u : 0u);
    const uint64_t groupSize = smallTriangles ? 8 : 1;
    dispatchLooping(program, nb, uint32_t(std::min<uint64_t>((nb + groupSize - 1) / groupSize, software ? 256 : 65535)),
                    context.info().loopLimit, smallTriangles ? 1058 / 8 + 8 : 96, "uBrickFirst", "uBricks");
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    timer.end();
    checkGl("band packing");
    waitForGpu([&] { request.checkpoint(0.5, "distance field"); });
    stats.stages.push_back({"band packing", timer.milliseconds(), msSince(w0)});
    buffers.bindMesh();
    return packed;
}

/// A field's band as leaves on the device (band_leaves.comp), in place of
/// packBand, timed into `stats`; the count is read with the field's counters
/// (readField). @a inside: per brick, the voxels inside (a signed field), or
/// null; with winding signs (FieldRequest::insideVoxels) a second dispatch
/// gives the bricks with inside voxels and none active their leaves. Every
/// pass's slots are bound again after.
FieldLeaves bandLeaves(const Context& context, const FieldBuffers& buffers, const GridSpec& grid,
                       const FieldRequest& request, uint32_t tableMask, const Buffer* inside, RunStats& stats)
{
    const uint64_t nb = std::max<uint64_t>(request.bricks.size(), 1);
    for (int a = 0; a < 3; ++a)
        if (grid.anchor[a] < std::numeric_limits<int32_t>::min() ||
            grid.anchor[a] + int64_t(grid.dims[a]) > std::numeric_limits<int32_t>::max())
            throw Unsupported("the field's grid reaches beyond 32-bit index coordinates");
    FieldLeaves leaves;
    const uint64_t capacity = nb + request.extraLeaves; // room for the caller's leaves after the band's
    leaves.origins = &context.scratch("band leaf origins", capacity * 12);
    leaves.masks = &context.scratch("band leaf masks", capacity * sizeof(Brick));
    leaves.values = &context.scratch("band leaf values", capacity * 2048);
    if (buffers.closest) leaves.closest = &context.scratch("band leaf closest", nb * 2048);
    leaves.origins->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_LEAVES_ORIGINS);
    leaves.masks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_LEAVES_MASKS);
    leaves.values->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_LEAVES_VALUES);
    // Bound, unused, without closest triangles.
    (leaves.closest ? leaves.closest : leaves.values)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_LEAVES_CLOSEST);
    (buffers.closest ? buffers.closest : buffers.distances)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_FIELD_CLOSEST);
    (inside ? inside : leaves.masks)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_LEAVES_INSIDE); // bound, unused, unsigned
    const auto w0 = Clock::now();
    TimerQuery timer;
    timer.begin();
    const Program& program = context.program(fieldsShaders(), {"band_leaves.comp"});
    uint32_t scale[2];
    std::memcpy(scale, &request.leafScale, 8);
    uint32_t background = 0;
    std::memcpy(&background, &request.leafBackground, 4);
    program.set("uBands", request.leafBands[0], request.leafBands[1]);
    program.set("uSigned", inside ? 1u : 0u);
    program.set("uScale", std::vector<uint32_t>{scale[0], scale[1]});
    program.set("uBackground", background);
    program.set("uAnchor", int(grid.anchor[0]), int(grid.anchor[1]), int(grid.anchor[2]));
    program.set("uClosest", buffers.closest ? 1u : 0u);
    program.set("uValues", request.bandOnly ? 0u : 1u);
    // A workgroup a table slot, its threads looping 1 + 8 + 16 + 16 + 8 times.
    const uint64_t slots = uint64_t(tableMask) + 1;
    for (const uint32_t insideOnly : {0u, 1u}) {
        if (insideOnly && !request.insideVoxels) break;
        program.set("uInsideOnly", insideOnly);
        dispatchLooping(program, slots, uint32_t(std::min<uint64_t>(slots, context.info().software ? 256 : 65535)),
                        context.info().loopLimit, 112, "uSlotFirst", "uSlots");
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    timer.end();
    checkGl("band leaves");
    waitForGpu([&] { request.checkpoint(0.5, "distance field"); });
    stats.stages.push_back({"band leaves", timer.milliseconds(), msSince(w0)});
    buffers.bindAll();
    return leaves;
}

/// A field signed by parity whose leaves stay on the device: the crossings
/// read back (into `result`) and scanned on the host (scanParity), the voxels
/// inside uploaded in place of the crossings, whose buffer they fit, for
/// band_leaves.comp; timed into `stats`.
const Buffer* insideVoxels(const FieldBuffers& buffers, const FieldRequest& request, FieldResult& result,
                           RunStats& stats)
{
    auto t0 = Clock::now();
    const uint64_t nb = request.bricks.size();
    result.crossings.resize(nb);
    buffers.flips->readBulk(0, nb * sizeof(Brick), result.crossings.data());
    checkGl("crossings readback");
    stats.stages.push_back({"crossings readback", -1, msSince(t0)});
    t0 = Clock::now();
    const ParityScan scan = scanParity(request.bricks, result.crossings);
    result.openColumns = scan.openColumns;
    buffers.flips->write(0, nb * sizeof(Brick), scan.inside.data());
    checkGl("inside voxels");
    stats.stages.push_back({"parity scan", -1, msSince(t0)});
    return buffers.flips;
}

/// Winding signs' inside voxels uploaded for band_leaves.comp.
const Buffer* uploadInside(const Context& context, const std::vector<Brick>& inside)
{
    const uint64_t bytes = std::max<uint64_t>(inside.size(), 1) * sizeof(Brick);
    const Buffer& buffer = context.scratch("field inside voxels", bytes);
    if (!inside.empty()) buffer.write(0, inside.size() * sizeof(Brick), inside.data());
    checkGl("inside voxels");
    return &buffer;
}

/// The GPU bytes the passes held: the uploads, the per-brick buffers and the larger item list.
uint64_t fieldGpuBytes(const FieldBuffers& buffers, const FieldItems& w, uint64_t nb)
{
    return buffers.positions.bytes() + buffers.indices.bytes() + buffers.tableBuffer.bytes() +
           buffers.counters.bytes() + (buffers.distances ? nb * (2048 + 2048 + sizeof(Brick) + 4) : 0) +
           (buffers.closest ? nb * 2048 * 2 : 0) + (buffers.flips ? nb * sizeof(Brick) : 0) +
           std::max(w.distanceItems.size() + w.distanceWhole.size(), w.crossingItems.size() + w.crossingWhole.size()) *
               4;
}

/// Reads the counters and the packed band and crossings back into `result`, timed into `stats`.
void readField(const FieldBuffers& buffers, const PackedBand& packed, uint64_t nb, FieldResult& result,
               RunStats& stats)
{
    const auto t0 = Clock::now();
    TimerQuery readTimer;
    readTimer.begin();
    uint32_t count[4] = {0, 0, 0, 0}; // lost crossings, packed band values, band leaves, of which inside only
    buffers.counters.read(0, 16, count);
    result.leaves.count = count[2];
    result.leaves.activeCount = count[2] - count[3];
    if (packed.masks) {
        result.bandMasks.resize(nb);
        packed.masks->readBulk(0, nb * sizeof(Brick), result.bandMasks.data());
        result.bandOffsets.resize(nb);
        packed.offsets->readBulk(0, nb * 4, result.bandOffsets.data());
        result.distances.resize(count[1]);
        packed.distances->readBulk(0, uint64_t(count[1]) * 4, result.distances.data());
    }
    if (packed.closest) {
        result.closest.resize(count[1]);
        packed.closest->readBulk(0, uint64_t(count[1]) * 4, result.closest.data());
    }
    if (buffers.flips && result.crossings.empty()) { // (signed device leaves read them already)
        result.crossings.resize(nb);
        buffers.flips->readBulk(0, nb * sizeof(Brick), result.crossings.data());
    }
    const uint32_t lost = count[0];
    readTimer.end();
    checkGl("field readback");
    result.lostCrossings = lost;
    stats.stages.push_back({"field readback", readTimer.milliseconds(), msSince(t0)});
}

} // namespace

FieldResult computeField(Context& context, const TriangleMesh& mesh, const GridSpec& grid, const FieldRequest& request,
                         RunStats* report)
{
    const Context::Scope scope(context);
    FieldResult result;
    RunStats stats;
    const uint64_t nb = request.bricks.size();
    const bool distances = request.band > 0;
    if (request.bandOnly && (request.closestTriangle || request.crossings || request.insideVoxels))
        throw InvalidInput("internal error: a band's topology is unsigned and has no closest triangles");
    request.checkpoint(0.0, "field upload");

    // Upload: local double positions, indices, items, the brick table.
    const auto t0 = Clock::now();
    const std::vector<Vec3d> local = localPositions(mesh, grid);
    const bool smallTriangles =
        request.work == FieldWork::SmallTriangles || (request.work == FieldWork::Auto && context.info().software);
    const FieldItems items = fieldItems(local, mesh, grid, request, smallTriangles);
    checkFieldLimits(context, mesh, request, items);
    uint32_t tableMask = 0;
    const std::vector<uint32_t> table = brickTable(request.bricks, tableMask);
    TimerQuery uploadTimer;
    uploadTimer.begin();
    const FieldBuffers buffers(context, local, mesh, table, request);
    uploadTimer.end();
    stats.stages.push_back({"field upload", -1, msSince(t0)});
    buffers.bindAll();

    const FieldPasses passes{context, mesh, request, tableMask, stats};
    if (distances) passes.distances(items, smallTriangles, buffers.closest != nullptr);
    const bool leaves = distances && request.deviceLeaves;
    const PackedBand packed =
        distances && !leaves ? packBand(context, buffers, request, smallTriangles, stats) : PackedBand{};
    if (request.crossings) passes.crossings(grid, items);
    if (leaves) {
        const Buffer* inside = request.crossings      ? insideVoxels(buffers, request, result, stats)
                               : request.insideVoxels ? uploadInside(context, *request.insideVoxels)
                                                      : nullptr;
        result.leaves = bandLeaves(context, buffers, grid, request, tableMask, inside, stats);
    }
    stats.stages.front().gpuMs = uploadTimer.milliseconds();
    stats.gpuBytes = fieldGpuBytes(buffers, items, nb);
    request.checkpoint(0.8, "field readback");

    readField(buffers, packed, nb, result, stats);
    if (leaves) { // the leaves hold the band now: the per-brick field's memory goes to what the caller builds next
        context.releaseScratch("field distances");
        context.releaseScratch("field closest triangles");
        context.releaseScratch("field inside voxels");
    }
    if (report) *report = std::move(stats);
    return result;
}

} // namespace svo::gl
