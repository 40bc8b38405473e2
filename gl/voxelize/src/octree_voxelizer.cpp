// The octree voxelization (voxelizeToOctree): the list writer's voxels built
// into an octree on the GPU, in one pass when the grid fits the GPU budget and
// the 32-bit and shader-buffer limits, else in tiles of whole bricks merged
// on the host. The list writers themselves are raster_voxelizer.cpp's and
// compute_voxelizer.cpp's.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <tbb/parallel_sort.h>

#include "list_writer.h"
#include "svo/gl/buffer.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "svo/gl/timer_query.h"
#include "svo/gl/wait_for_gpu.h"
#include "octree_passes.h"
#include "svo/core/byte_size.h"
#include "svo/core/error.h"
#include "svo/core/host_memory.h"
#include "svo/core/voxel_attributes.h"
#include "svo/core/voxel_key.h"
#include "svo/gl/raster_voxelizer.h"
#include "voxelize_shaders.h"

namespace svo::gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// Octree buffer sizes from the voxel-list size. The benchmark scenes hold
/// 68-317 list entries and 2.6-2.7 nodes per brick; these estimates leave room
/// for sparser scenes, and an overflow only costs a rebuild.
uint64_t bricksFor(uint64_t listEntries) { return listEntries / 48 + 64; }
uint64_t nodesFor(uint32_t brickLevel, uint64_t bricks)
{
    return std::min(OctreeBuilder::nodeBound(brickLevel, bricks), 12 * bricks + 1);
}

/// Sums every list entry's triangle values into its voxel (octree_attributes.comp)
/// and turns the sums into the asked-for channels on the octree.
void attachAttributes(const Program& program, const TriangleMesh& mesh, uint32_t channels,
                      const OctreeBuilder::Build& build, const Buffer& list, const Buffer& triangleList,
                      uint32_t entries, Octree& octree)
{
    const uint64_t voxels = octree.voxelCount();
    if (voxels > (uint64_t(1) << 28))
        throw Unsupported(fmt::format("{} voxels are too many for attribute channels in one pass", voxels));
    const auto offsets64 = brickVoxelOffsets(octree);
    const std::vector<uint32_t> offsets(offsets64.begin(), offsets64.end());
    const TriangleValues tv = triangleValues(mesh, true);
    std::vector<float> values(6 * mesh.triangles.size(), 0.0f);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        values[6 * t] = tv.normals[t].x, values[6 * t + 1] = tv.normals[t].y, values[6 * t + 2] = tv.normals[t].z;
        if (!tv.colors.empty())
            values[6 * t + 3] = tv.colors[t].x, values[6 * t + 4] = tv.colors[t].y, values[6 * t + 5] = tv.colors[t].z;
    }
    const Buffer offsetBuffer("brick voxel offsets", offsets.size() * 4, offsets.data(), 0);
    const Buffer valueBuffer("triangle values", values.size() * 4, values.data(), 0);
    const Buffer sums("attribute sums", voxels * sizeof(AttributeSums));
    sums.clearUint(0);
    build.state->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BUILD_STATE);
    build.nodes->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NODES);
    build.bricks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BRICKS);
    list.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_ENTRIES);
    triangleList.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_ENTRY_TRIANGLES);
    offsetBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BRICK_VOXEL_OFFSETS);
    valueBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_TRIANGLE_VALUES);
    sums.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_ATTRIBUTE_SUMS);
    program.set("uBrickLevel", octree.brickLevel);
    program.set("uEntries", entries);
    program.dispatch(std::clamp<uint32_t>((entries + 255) / 256, 1, 65535));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    checkGl("attribute pass");
    std::vector<AttributeSums> host(voxels);
    if (voxels) sums.readBulk(0, voxels * sizeof(AttributeSums), host.data());
    octree.attributes = finishAttributes(host, availableChannels(mesh, channels));
}

/// What one pass asks the GPU for, besides the writer's mesh and work list.
struct PassSize {
    uint64_t list = 0, bricks = 0, nodes = 0;
};

/// The GPU memory a call may use (RasterOptions::gpuMemory) and the 32-bit
/// limits of the list counter and octree indices, as one test of a pass's size.
class Budget {
public:
    /// `maxBlock`: the most bytes of one buffer a shader addresses (0: no limit).
    Budget(uint64_t bytes, uint64_t fixed, bool attributes, uint32_t brickLevel, uint64_t triangles, uint64_t maxBlock)
        : bytes_(bytes), fixed_(fixed + (attributes ? 24 * triangles : 0) + OctreeBuilder::bitmapBytes(brickLevel)),
          brickLevel_(brickLevel),
          perEntry_(8 + (attributes ? 4 + sizeof(AttributeSums) : 0)), perBrick_(64 + (attributes ? 4 : 0))
    {
        if (attributes) maxEntries_ = uint64_t(1) << 28; // the attribute pass's voxels (at most one per entry)
        if (!maxBlock) return;
        // The list's keys (and with channels, one sum per voxel: at most one per entry), bricks and nodes.
        maxEntries_ = std::min(maxEntries_, maxBlock / (attributes ? sizeof(AttributeSums) : 8));
        maxBricks_ = std::min(maxBricks_, maxBlock / sizeof(Brick));
        maxNodes_ = std::min(maxNodes_, maxBlock / sizeof(OctreeNode) - 16);
    }

    uint64_t limit() const { return bytes_; }
    uint64_t fixed() const { return fixed_; }
    /// The pass's buffers: list (and triangle list, attribute sums: at most
    /// one voxel per entry), nodes, bricks (and voxel offsets), the readback's
    /// staging buffer, and room for scratch buffers' rounding, state and counter.
    uint64_t bytes(const PassSize& s) const
    {
        const uint64_t nodes = (s.nodes + 8) * sizeof(OctreeNode);
        const uint64_t largestRead = std::max({s.list * perEntry_, s.bricks * sizeof(Brick), nodes});
        const uint64_t staging = std::min<uint64_t>(uint64_t(64) << 20, largestRead); // Buffer::readBulk
        return fixed_ + s.list * perEntry_ + s.bricks * perBrick_ + nodes + staging + (uint64_t(1) << 19);
    }
    bool withinLimits(const PassSize& s) const
    {
        return s.list <= maxEntries_ && s.bricks <= maxBricks_ && s.nodes <= maxNodes_;
    }
    bool fits(const PassSize& s) const { return withinLimits(s) && (!bytes_ || bytes(s) <= bytes_); }
    /// After the device could not allocate a pass of size `s` (a budget can
    /// promise more than a driver gives): the limit halves below it, so the
    /// passes that follow are tiles of what it can.
    void lowerBelow(const PassSize& s)
    {
        const uint64_t failed = bytes(s);
        bytes_ = fixed_ + std::max<uint64_t>(1, (failed - fixed_) / 2);
    }
    /// How many times over the budget or the limits a pass of this size is.
    double excess(const PassSize& s) const
    {
        double r = std::max({double(s.list) / double(maxEntries_), double(s.bricks) / double(maxBricks_),
                             double(s.nodes) / double(maxNodes_)});
        if (bytes_) r = std::max(r, double(bytes(s) - fixed_) / double(bytes_ - fixed_));
        return r;
    }
    /// The size a list of `entries` is expected to need.
    PassSize sizeFor(uint64_t entries) const { return {entries, bricksFor(entries), nodesFor(brickLevel_, bricksFor(entries))}; }
    /// The largest expected size that fits; list 0 when not even an empty one does.
    PassSize largest() const
    {
        if (!fits(sizeFor(1))) return {};
        uint64_t lo = 1, hi = maxEntries_;
        while (lo < hi) {
            const uint64_t mid = lo + (hi - lo + 1) / 2;
            if (fits(sizeFor(mid))) lo = mid;
            else hi = mid - 1;
        }
        return sizeFor(lo);
    }

private:
    uint64_t maxEntries_ = 0xFFFFFFFFull;          // the list's 32-bit counter
    uint64_t maxBricks_ = uint64_t(1) << 28;       // 16 words each, 32-bit word indices
    uint64_t maxNodes_ = (uint64_t(1) << 31) - 16; // 2 words each
    uint64_t bytes_, fixed_;
    uint32_t brickLevel_;
    uint64_t perEntry_, perBrick_;
};

/// The list's entry count; 2^32 when the counter wrapped (at least that many).
uint64_t readCountOrWrap(const Buffer& counter)
{
    uint32_t c[2] = {0, 0};
    counter.read(0, sizeof c, c);
    return c[1] ? uint64_t(1) << 32 : c[0];
}

/// `box` cut into at least `pieces` boxes (fewer only when they are single
/// bricks) by halving the longest side at a multiple of 8.
std::vector<VoxelBox> splitBox(const VoxelBox& box, uint64_t pieces)
{
    std::vector<VoxelBox> boxes = {box};
    while (boxes.size() < pieces) {
        std::vector<VoxelBox> next;
        for (const VoxelBox& b : boxes) {
            int axis = 0;
            for (int k = 1; k < 3; ++k)
                if (b.hi[k] - b.lo[k] > b.hi[axis] - b.lo[axis]) axis = k;
            const uint32_t side = b.hi[axis] - b.lo[axis];
            if (side <= 8) {
                next.push_back(b);
                continue;
            }
            const uint32_t mid = b.lo[axis] + (side / 2 + 7) / 8 * 8; // b.lo is a multiple of 8
            VoxelBox first = b, second = b;
            first.hi[axis] = second.lo[axis] = mid;
            next.push_back(first), next.push_back(second);
        }
        if (next.size() == boxes.size()) break; // single bricks
        boxes = std::move(next);
    }
    return boxes;
}

/// One call's passes over boxes of the grid: each fills the list for its box,
/// builds that box's octree and reads it back, within the budget.
class OctreePasses {
public:
    OctreePasses(Context& context, const TriangleMesh& mesh, const GridSpec& grid, const RasterOptions& options,
                 ListWriter& writer, const OctreeBuilder& builder, const Program* attributeProgram,
                 Budget& budget)
        : context_(context), mesh_(mesh), grid_(grid), options_(options), writer_(writer), builder_(builder),
          attributeProgram_(attributeProgram), budget_(budget), L_(brickLevelFor(grid)),
          counter_(context.scratch("voxel counter", 2 * sizeof(uint32_t))) // entries, and wraps past 2^32
    {
    }

    struct Outcome {
        bool fits = false;
        PassSize needed;          ///< when it did not fit: the size it needed (list exact, octree at least)
        uint64_t entries = 0;     ///< list entries of the box
        Octree octree;            ///< the box's voxels (with attributes when asked)
        std::vector<uint64_t> list; ///< options.voxelList only: the box's keys, sorted and unique
    };

    /// Voxelizes the voxels of `box`, first with room for `size`; returns
    /// fits = false, having built nothing, when the box needs more than the budget.
    Outcome run(const VoxelBox& box, PassSize size, const Checkpoint& checkpoint)
    {
        writer_.setClip(box, checkpoint.part(0.0, 0.6));
        Outcome out;
        const Buffer* list = nullptr;
        const Buffer* triangles = nullptr;
        OctreeBuilder::Build build;
        uint64_t count = 0;
        bool drawn = false;
        for (int attempt = 0;; ++attempt) {
            if (!budget_.fits(size)) {
                out.needed = size;
                return out;
            }
            auto t0 = Clock::now();
            TimerQuery drawTimer, buildTimer;
            try {
                if (!drawn) {
                    list = &makeList(context_, size.list);
                    if (options_.attributes) triangles = &context_.scratch("triangle list", size.list * 4);
                    drawTimer.begin();
                    writer_.write(*list, counter_, size.list, triangles);
                    drawTimer.end();
                }
                voxelizeWall += msSince(t0);
                t0 = Clock::now();
                checkpoint(0.6, "octree build");
                OctreeInput in;
                in.entries = list;
                in.listCounter = &counter_;
                in.entryCapacity = size.list;
                buildTimer.begin();
                build = builder_.record(grid_, in, size.nodes, size.bricks, [&] { checkpoint(0.6, "octree build"); });
                buildTimer.end();
            } catch (const OutOfMemory&) {
                // More than the driver gives: a smaller budget from here on, and this box in tiles.
                budget_.lowerBelow(size);
                out.needed = size;
                return out;
            }
            // The GPU works now; wait for it in slices so an interrupter is heard meanwhile.
            waitForGpu([&] { checkpoint(0.6, "voxelization on the GPU"); });
            OctreeBuilder::readCounts(build);
            count = readCountOrWrap(counter_);
            buildWall += msSince(t0);
            if (!drawn) voxelizeGpu += drawTimer.milliseconds();
            buildGpu += buildTimer.milliseconds();
            gpuBytes = std::max(gpuBytes, writer_.bytes() + list->bytes() + (triangles ? triangles->bytes() : 0) +
                                              counter_.bytes() + build.bytes());
            if (count > size.list) {
                // The counter kept counting: the exact size (or, past 2^32, at least that).
                size.list = count;
                size.bricks = std::max(size.bricks, bricksFor(count));
                size.nodes = std::max(size.nodes, nodesFor(L_, size.bricks));
            } else if (build.overflowed()) {
                drawn = true; // the list is complete; only the octree needs room
                if (build.exactCounts) {
                    size.bricks = build.counts.brickCount;
                    size.nodes = build.counts.nodeCount;
                } else if (build.counts.nodeCount <= build.nodeCapacity) {
                    size.bricks = build.counts.brickCount; // every brick node was reached: exact
                } else {
                    size.bricks = std::max<uint64_t>(build.counts.brickCount, size.bricks) * 2;
                    // Counts past an overflowed level are lower bounds: double, never shrink.
                    size.nodes = std::max<uint64_t>(build.counts.nodeCount, size.nodes) * 2;
                }
            } else {
                break;
            }
            ++retries;
        }
        out.fits = true;
        out.entries = count;

        checkpoint(0.85, "octree readback");
        auto t0 = Clock::now();
        TimerQuery readTimer;
        readTimer.begin();
        out.octree = OctreeBuilder::readOctree(build, grid_);
        readTimer.end();
        readGpu += readTimer.milliseconds();
        readWall += msSince(t0);
        if (options_.voxelList) out.list = readList(*list, uint32_t(count));

        if (options_.attributes) {
            checkpoint(0.95, "attribute channels");
            t0 = Clock::now();
            TimerQuery attrTimer;
            attrTimer.begin();
            attachAttributes(*attributeProgram_, mesh_, options_.attributes, build, *list, *triangles, uint32_t(count),
                             out.octree);
            attrTimer.end();
            attrGpu += attrTimer.milliseconds();
            attrWall += msSince(t0);
        }
        return out;
    }

    double voxelizeGpu = 0, buildGpu = 0, voxelizeWall = 0, buildWall = 0, readGpu = 0, readWall = 0;
    double attrGpu = 0, attrWall = 0;
    int retries = 0;
    uint64_t gpuBytes = 0;

private:
    Context& context_;
    const TriangleMesh& mesh_;
    const GridSpec& grid_;
    const RasterOptions& options_;
    ListWriter& writer_;
    const OctreeBuilder& builder_;
    const Program* attributeProgram_;
    Budget& budget_;
    uint32_t L_;
    const Buffer& counter_;
};

/// The budget a call works within: the caller's, else what the device has
/// free (with the scratch buffers this context already holds, which the call
/// reuses) less a tenth for the driver; 0 (no budget) when unknown.
uint64_t budgetBytes(const Context& context, const RasterOptions& options)
{
    if (options.gpuMemory) return options.gpuMemory;
    const uint64_t free = context.availableMemory();
    if (!free) return 0;
    const uint64_t usable = free / 10 * 9 + context.scratchBytes();
    return context.info().software ? usable / 2 : usable; // llvmpipe: the host also holds the result
}

/// Out of core, the host holds the merged octree: refuses, before any tile
/// runs, a list of `entries` whose octree would not fit in the host's free
/// memory (at about 150 list entries and 88 bytes a brick with its nodes, as
/// on the benchmark scenes).
void refuseBeyondHostMemory(uint64_t entries)
{
    const uint64_t hostFree = availableHostMemory();
    const double hostNeed = double(entries) / 150.0 * 88.0;
    if (hostFree && hostNeed > double(hostFree))
        throw OutOfMemory(fmt::format("the octree would need about {:.1f} GiB of host memory (estimated from the "
                                      "triangles' areas), more than the {:.1f} GiB free; use a coarser grid",
                                      hostNeed / double(1 << 30), double(hostFree) / double(1 << 30)));
}

/// The tiles' octrees as one: bricks merged by origin (no two tiles share a
/// brick), the octree built on the host in canonical order, attribute values
/// moved to their bricks' new places.
Octree mergeTiles(const GridSpec& grid, std::vector<Octree>& tiles, uint32_t attributes)
{
    size_t total = 0;
    for (const Octree& t : tiles) total += t.bricks.size();
    if (total >= (uint64_t(1) << 32) - 1)
        throw Unsupported(fmt::format("{} bricks are more than one octree indexes (2^32); use a coarser grid", total));
    struct Source {
        uint64_t key;
        uint32_t tile, brick;
    };
    std::vector<std::pair<uint64_t, Brick>> bricks;
    std::vector<Source> sources;
    bricks.reserve(total);
    if (attributes) sources.reserve(total);
    for (uint32_t t = 0; t < tiles.size(); ++t) {
        for (const BrickRef& b : occupiedBricks(tiles[t])) {
            const uint64_t key = packVoxelKey(b.origin[0], b.origin[1], b.origin[2]);
            bricks.emplace_back(key, tiles[t].bricks[b.index]);
            if (attributes) sources.push_back({key, t, b.index});
        }
        if (!attributes) tiles[t] = Octree(); // free as we go
    }
    Octree merged = buildOctreeFromBricks(grid, std::move(bricks));
    if (!attributes) return merged;

    tbb::parallel_sort(sources.begin(), sources.end(), [](const Source& a, const Source& b) { return a.key < b.key; });
    std::vector<std::vector<uint64_t>> offsets;
    for (const Octree& t : tiles) offsets.push_back(brickVoxelOffsets(t));
    VoxelAttributes& out = merged.attributes;
    const VoxelAttributes& first = tiles.front().attributes;
    const bool normals = !first.normals.empty(), ids = !first.triangles.empty(), colors = !first.colors.empty();
    const uint64_t voxels = merged.voxelCount();
    if (normals) out.normals.resize(voxels);
    if (ids) out.triangles.resize(voxels);
    if (colors) out.colors.resize(voxels);
    const std::vector<uint64_t> at = brickVoxelOffsets(merged);
    for (const BrickRef& b : occupiedBricks(merged)) {
        const uint64_t key = packVoxelKey(b.origin[0], b.origin[1], b.origin[2]);
        const auto it = std::lower_bound(sources.begin(), sources.end(), key,
                                         [](const Source& s, uint64_t k) { return s.key < k; });
        const uint64_t from = offsets[it->tile][it->brick], n = offsets[it->tile][it->brick + 1] - from;
        const VoxelAttributes& src = tiles[it->tile].attributes;
        const uint64_t to = at[b.index];
        if (normals) std::copy_n(src.normals.begin() + from, n, out.normals.begin() + to);
        if (ids) std::copy_n(src.triangles.begin() + from, n, out.triangles.begin() + to);
        if (colors) std::copy_n(src.colors.begin() + from, n, out.colors.begin() + to);
    }
    return merged;
}

} // namespace

Octree voxelizeToOctree(Context& context, const TriangleMesh& mesh, const GridSpec& grid, const RasterOptions& options,
                        RunStats* report)
{
    const Context::Scope scope(context);
    const Checkpoint& checkpoint = options.checkpoint;
    checkpoint(0.0, "mesh upload");
    RunStats stats;
    RasterOptions rasterOptions = options;
    rasterOptions.checkpoint = checkpoint.part(0.05, 0.6);
    const auto writer = makeWriter(context, mesh, grid, rasterOptions);
    // Every program the call needs, and no other, made before the stages are timed.
    const OctreeBuilder builder(context);
    const Program* attributeProgram = options.attributes ? &context.program(voxelizeShaders(), {"octree_attributes.comp"}) : nullptr;
    const uint32_t L = brickLevelFor(grid);
    Budget budget(budgetBytes(context, options), writer->bytes(), options.attributes != 0, L,
                        mesh.triangles.size(), context.shaderBufferLimit());
    const PassSize largest = budget.largest();
    if (!largest.list)
        throw OutOfMemory(fmt::format("a GPU memory budget of {} cannot hold the mesh ({}: vertices, indices, work "
                                      "list) and the smallest pass ({} in all); raise the budget",
                                      byteSize(budget.limit()), byteSize(budget.fixed()), byteSize(budget.bytes(budget.sizeFor(1)))));
    OctreePasses passes(context, mesh, grid, options, *writer, builder, attributeProgram, budget);

    // The whole grid first, rasterized and built without waiting, with room
    // for the estimate (or, past the budget, for as much as fits).
    PassSize size = budget.sizeFor(writer->estimatedEntries());
    if (options.initialBrickCapacity) size.bricks = options.initialBrickCapacity;
    if (!budget.fits(size)) {
        // Tiles ahead: first make sure the host can hold what they make.
        refuseBeyondHostMemory(writer->estimatedEntries());
        size = largest;
    }
    // The whole grid, or the asked-for box of it (tiled within the box past the budget).
    const VoxelBox whole = options.box ? *options.box : VoxelBox{{0, 0, 0}, grid.dims};
    if (whole.empty()) {
        if (report) *report = std::move(stats);
        return buildOctreeFromBricks(grid, {});
    }
    OctreePasses::Outcome first = passes.run(whole, size, checkpoint.part(0.05, 0.95));

    std::vector<Octree> tiles;
    std::vector<uint64_t> lists;
    uint64_t entries = first.entries;
    if (!first.fits) {
        refuseBeyondHostMemory(first.needed.list);
        struct Pending {
            VoxelBox box;
            PassSize needed;
        };
        std::vector<Pending> stack = {{whole, first.needed}};
        stats.tiles = 0;
        const double volume = double(whole.volume());
        double done = 0;
        while (!stack.empty()) {
            const Pending p = stack.back();
            stack.pop_back();
            const uint64_t pieces = uint64_t(std::ceil(budget.excess(p.needed) * 1.25)) + 1;
            const std::vector<VoxelBox> boxes = splitBox(p.box, pieces);
            if (boxes.size() == 1)
                throw OutOfMemory(fmt::format("one brick of the grid (local {}, {}, {}) needs {} voxel-list entries, "
                                              "more than a GPU budget of {} holds; raise the budget or use a coarser grid",
                                              p.box.lo[0], p.box.lo[1], p.box.lo[2], p.needed.list, byteSize(budget.limit())));
            for (const VoxelBox& box : boxes) {
                const Checkpoint part = checkpoint.part(0.05 + 0.8 * done / volume, 0.05 + 0.8 * (done + box.volume()) / volume);
                // A box holds at most its parent's entries (each entry lies in one box).
                PassSize room = budget.largest(); // lowered where the device could not allocate
                if (!room.list)
                    throw OutOfMemory(fmt::format("the GPU cannot allocate even the smallest pass ({}) beside the mesh "
                                                  "({}); use a smaller mesh or another device",
                                                  byteSize(budget.bytes(budget.sizeFor(1)) - budget.fixed()),
                                                  byteSize(budget.fixed())));
                if (p.needed.list < room.list) room = budget.sizeFor(p.needed.list);
                OctreePasses::Outcome o = passes.run(box, room, part);
                if (!o.fits) {
                    stack.push_back({box, o.needed});
                    continue;
                }
                done += double(box.volume());
                ++stats.tiles;
                entries += o.entries;
                if (o.octree.bricks.empty()) continue;
                tiles.push_back(std::move(o.octree));
                lists.insert(lists.end(), o.list.begin(), o.list.end());
            }
        }
    }

    stats.stages.push_back(writer->uploadStage());
    stats.stages.push_back({"voxelize", passes.voxelizeGpu, passes.voxelizeWall});
    stats.stages.push_back({"octree build", passes.buildGpu, passes.buildWall});
    stats.stages.push_back({"readback", passes.readGpu, passes.readWall});
    if (options.attributes) stats.stages.push_back({"attributes", passes.attrGpu, passes.attrWall});
    stats.overflowRetries = passes.retries;
    stats.gpuBytes = passes.gpuBytes;
    if (first.fits) {
        stats.listEntries = first.entries;
        if (options.voxelList) *options.voxelList = std::move(first.list);
        if (report) *report = std::move(stats);
        return std::move(first.octree);
    }
    stats.listEntries = entries;
    checkpoint(0.9, "merging tiles");
    const auto t0 = Clock::now();
    Octree octree = tiles.empty() ? buildOctreeFromBricks(grid, {}) : mergeTiles(grid, tiles, options.attributes);
    stats.stages.push_back({"tile merge (cpu)", -1.0, msSince(t0)});
    if (options.voxelList) {
        sortUniqueKeys(lists);
        *options.voxelList = std::move(lists);
    }
    if (report) *report = std::move(stats);
    return octree;
}

} // namespace svo::gl
