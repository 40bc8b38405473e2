#include "octree_passes.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fmt/format.h>

#include "svo/core/error.h"
#include "svo/core/voxel_key.h"
#include "svo/gl/octree_builder.h"
#include "svo/gl/buffer.h"
#include "svo/gl/fill_words.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "svo/gl/timer_query.h"
#include "voxelize_shaders.h"

namespace svo::gl {
namespace {

void passBarrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT); }

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

} // namespace

OctreeBuilder::OctreeBuilder(const Context& context)
    : context_(context), prepare_(context.program(voxelizeShaders(), {"octree_prepare.comp"})),
      fill_(context.program(voxelizeShaders(), {"octree_fill.comp"}))
{
}

bool OctreeBuilder::bitmapBuild(uint32_t brickLevel) { return brickLevel <= SVO_BUILD_BITMAP_MAX_LEVEL; }

std::vector<uint32_t> OctreeBuilder::levelBlocks(uint32_t brickLevel)
{
    // Level l holds 8^l bits, at least one block.
    std::vector<uint32_t> first(SVO_BUILD_BITMAP_MAX_LEVEL + 2, 0);
    for (uint32_t l = 0; l <= brickLevel && l <= SVO_BUILD_BITMAP_MAX_LEVEL; ++l)
        first[l + 1] = first[l] + std::max<uint32_t>(1, uint32_t((uint64_t(1) << 3 * l) >> gpu::kBitmapBlockShift));
    for (uint32_t l = brickLevel + 2; l < first.size(); ++l) first[l] = first[brickLevel + 1];
    return first;
}

uint64_t OctreeBuilder::bitmapBytes(uint32_t brickLevel)
{
    if (!bitmapBuild(brickLevel)) return 0;
    const uint64_t blocks = levelBlocks(brickLevel)[brickLevel + 1];
    return blocks * gpu::kBitmapBlockWords * 4 + 2 * blocks * 4;
}

uint64_t OctreeBuilder::nodeBound(uint32_t brickLevel, uint64_t bricks)
{
    // Occupied nodes at level l are at most min(8^l, bricks); each owns 8 children.
    uint64_t total = 1, perLevel = 1;
    for (uint32_t l = 0; l < brickLevel; ++l) {
        total += 8 * std::min(perLevel, bricks);
        perLevel = std::min<uint64_t>(perLevel * 8, uint64_t(1) << 40);
    }
    return total;
}

OctreeBuilder::Build OctreeBuilder::record(const GridSpec& grid, const OctreeInput& in, uint64_t nodeCapacity,
                                           uint64_t brickCapacity, const std::function<void()>& poll) const
{
    const uint32_t L = brickLevelFor(grid);
    // The shaders index uint words: 2 per node and 16 per brick, in 32 bits.
    if (nodeCapacity > (uint64_t(1) << 31) - 16 || brickCapacity > (uint64_t(1) << 28))
        throw Unsupported(fmt::format("the octree would need {} nodes and {} bricks, beyond 32-bit indices; use a coarser grid",
                                      nodeCapacity, brickCapacity));
    Build b;
    b.nodeCapacity = 1 + (std::max<uint64_t>(nodeCapacity, 1) - 1 + 7) / 8 * 8; // root + whole blocks
    b.brickCapacity = std::max<uint64_t>(brickCapacity, 1);
    BuildState init{};
    init.entryCount = in.listCounter ? 0 : in.entryCount;
    init.entryDispatch[0] = std::clamp<uint32_t>((init.entryCount + 255) / 256, 1, 65535);
    init.entryDispatch[1] = init.entryDispatch[2] = 1;
    init.nodeCount = 1;
    init.levelStart[1] = 1;
    b.state = &context_.scratch("octree build state", sizeof init);
    b.nodes = &context_.scratch("octree nodes", b.nodeCapacity * sizeof(OctreeNode));
    b.bricks = &context_.scratch("octree bricks", b.brickCapacity * sizeof(Brick));
    b.state->write(0, sizeof init, &init);
    fillWords(context_, *b.bricks, 0, b.brickCapacity * sizeof(Brick));

    b.state->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BUILD_STATE);
    b.nodes->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_NODES);
    b.bricks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BRICKS);
    in.entries->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_ENTRIES);
    if (in.listCounter) {
        in.listCounter->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_LIST_COUNTER);
        prepare_.set("uMode", 0u);
        prepare_.set("uEntryCapacity", uint32_t(std::min<uint64_t>(in.entryCapacity, 0xFFFFFFFFu)));
        glMemoryBarrier(GL_ATOMIC_COUNTER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        prepare_.dispatch(1);
        passBarrier();
    }
    const bool bitmap = bitmapBuild(L);
    b.exactCounts = bitmap;
    if (bitmap) recordBitmap(b, L, poll);
    else recordDescent(b, L, poll);

    fill_.set("uBrickLevel", L);
    fill_.set("uBitmapBuild", bitmap ? 1u : 0u);
    fill_.set("uNodeCapacity", uint32_t(b.nodeCapacity));
    fill_.set("uBrickCapacity", uint32_t(b.brickCapacity));
    if (bitmap) fill_.set("uLevelBlock", levelBlocks(L));
    fill_.set("uBrickMasks", in.masks ? 1u : 0u);
    if (in.masks) in.masks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_ENTRY_MASKS);
    else in.entries->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_ENTRY_MASKS); // unused, but bound
    fill_.dispatchIndirect(*b.state, offsetof(BuildState, entryDispatch));
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT); // readback, attribute pass
    checkGl("octree build");
    return b;
}

void OctreeBuilder::recordBitmap(Build& b, uint32_t L, const std::function<void()>& poll) const
{
    // Mark every level's occupancy, rank the nodes of each level in Morton
    // order, write each block of children: four passes whatever the depth
    // (the descent's three per level cost more in dispatch chain than in work).
    const std::vector<uint32_t> first = levelBlocks(L);
    const uint64_t blocks = first[L + 1];
    b.bitmap = &context_.scratch("octree bitmaps", blocks * gpu::kBitmapBlockWords * 4);
    b.blocks = &context_.scratch("octree bitmap blocks", 2 * blocks * 4);
    fillWords(context_, *b.bitmap, 0, blocks * gpu::kBitmapBlockWords * 4);
    fillWords(context_, *b.blocks, 0, blocks * 4);
    b.bitmap->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BUILD_BITMAP);
    b.blocks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BUILD_BLOCKS);
    const Program& mark = context_.program(voxelizeShaders(), {"octree_mark.comp"});
    const Program& scan = context_.program(voxelizeShaders(), {"octree_scan.comp"});
    const Program& nodePass = context_.program(voxelizeShaders(), {"octree_nodes.comp"});
    for (const Program* p : {&mark, &scan, &nodePass}) {
        p->set("uBrickLevel", L);
        p->set("uLevelBlock", first);
    }
    nodePass.set("uNodeCapacity", uint32_t(b.nodeCapacity));
    nodePass.set("uBrickCapacity", uint32_t(b.brickCapacity));
    mark.dispatchIndirect(*b.state, offsetof(BuildState, entryDispatch));
    passBarrier();
    if (poll) poll();
    scan.dispatch(1);
    passBarrier();
    const uint64_t words = uint64_t(first[L]) * gpu::kBitmapBlockWords;
    nodePass.dispatch(std::clamp<uint32_t>(uint32_t((words + 255) / 256), 1, 65535));
    // The fill reads the bitmap and blocks, written before the last barrier;
    // it writes bricks, which the node pass does not touch.
}

void OctreeBuilder::recordDescent(Build& b, uint32_t L, const std::function<void()>& poll) const
{
    fillWords(context_, *b.nodes, 0, b.nodeCapacity * sizeof(OctreeNode));
    const Program& flag = context_.program(voxelizeShaders(), {"octree_flag.comp"});
    const Program& alloc = context_.program(voxelizeShaders(), {"octree_alloc.comp"});
    for (const Program* p : {&flag, &alloc}) p->set("uBrickLevel", L); // prepare_ does not read it
    prepare_.set("uNodeCapacity", uint32_t(b.nodeCapacity));
    alloc.set("uNodeCapacity", uint32_t(b.nodeCapacity));
    alloc.set("uBrickCapacity", uint32_t(b.brickCapacity));
    prepare_.set("uMode", 1u);
    for (uint32_t level = 0; level <= L; ++level) {
        if (poll) poll();
        for (const Program* p : {&prepare_, &flag, &alloc}) p->set("uLevel", level);
        flag.dispatchIndirect(*b.state, offsetof(BuildState, entryDispatch));
        prepare_.dispatch(1);
        passBarrier();
        alloc.dispatchIndirect(*b.state, offsetof(BuildState, levelDispatch));
        passBarrier();
    }
}

void OctreeBuilder::readCounts(Build& b) { b.state->read(0, sizeof b.counts, &b.counts); }

Octree OctreeBuilder::readOctree(const Build& b, const GridSpec& grid)
{
    Octree o;
    o.grid = grid;
    o.brickLevel = brickLevelFor(grid);
    o.levelStart.assign(b.counts.levelStart, b.counts.levelStart + o.brickLevel + 2);
    o.nodes.resize(b.counts.nodeCount);
    o.bricks.resize(b.counts.brickCount);
    if (!o.nodes.empty()) b.nodes->readBulk(0, o.nodes.size() * sizeof(OctreeNode), o.nodes.data());
    if (!o.bricks.empty()) b.bricks->readBulk(0, o.bricks.size() * sizeof(Brick), o.bricks.data());
    checkGl("octree readback");
    return o;
}

Octree buildOctreeGpu(Context& context, const GridSpec& grid, const std::vector<std::pair<uint64_t, Brick>>& bricks,
                      const Checkpoint& checkpoint, RunStats* report)
{
    if (bricks.size() > 0xFFFFFFF0u) throw Unsupported(fmt::format("{} bricks exceed one GPU build", bricks.size()));
    const Context::Scope scope(context);
    checkpoint(0.0, "brick upload");
    RunStats stats;
    auto t0 = Clock::now();
    TimerQuery uploadTimer;
    uploadTimer.begin();
    std::vector<uint64_t> keys;
    std::vector<Brick> masks;
    keys.reserve(bricks.size());
    masks.reserve(bricks.size());
    const uint32_t L = brickLevelFor(grid);
    for (const auto& [key, mask] : bricks) {
        if (!mask.count()) continue;
        const auto p = unpackVoxelKey(key);
        if (std::max({p[0], p[1], p[2]}) >> 3 >> L)
            throw InvalidInput(fmt::format("brick at local ({}, {}, {}) lies outside the grid {} x {} x {}", p[0] & ~7u,
                                           p[1] & ~7u, p[2] & ~7u, grid.dims[0], grid.dims[1], grid.dims[2]));
        keys.push_back(brickOfKey(key)), masks.push_back(mask);
    }
    const Buffer& entries = context.scratch("brick keys", keys.size() * 8);
    const Buffer& maskBuffer = context.scratch("brick masks", masks.size() * sizeof(Brick));
    entries.write(0, keys.size() * 8, keys.data());
    maskBuffer.write(0, masks.size() * sizeof(Brick), masks.data());
    uploadTimer.end();
    stats.stages.push_back({"upload", -1, msSince(t0)});
    checkpoint(0.3, "octree build");

    const OctreeBuilder builder(context); // programs: start-up, not the build's time
    t0 = Clock::now();
    OctreeInput in;
    in.entries = &entries;
    in.entryCapacity = in.entryCount = uint32_t(keys.size());
    in.masks = &maskBuffer;
    TimerQuery timer;
    timer.begin();
    auto build = builder.record(grid, in, OctreeBuilder::nodeBound(L, keys.size()), keys.size());
    timer.end();
    OctreeBuilder::readCounts(build);
    if (build.overflowed()) throw DeviceError("internal error: the octree build overflowed its upper bound");
    stats.stages.front().gpuMs = uploadTimer.milliseconds();
    stats.stages.push_back({"octree build", timer.milliseconds(), msSince(t0)});
    stats.gpuBytes = entries.bytes() + maskBuffer.bytes() + build.bytes();
    checkpoint(0.7, "octree readback");

    t0 = Clock::now();
    TimerQuery readTimer;
    readTimer.begin();
    Octree octree = OctreeBuilder::readOctree(build, grid);
    readTimer.end();
    stats.stages.push_back({"readback", readTimer.milliseconds(), msSince(t0)});
    if (report) *report = std::move(stats);
    return octree;
}

} // namespace svo::gl
