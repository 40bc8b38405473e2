// The compute backend's list writer (voxelize.comp): triangle-parallel
// compute shaders instead of the raster pipeline, with the same column walk.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <chrono>

#include "list_writer.h"
#include "octree_builder.h"
#include "svo/core/error.h"

namespace svo::gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

constexpr uint64_t kSmall = 64, kChunk = 64; // as in voxelize.comp
constexpr uint32_t kMaxGroups = 65535;       // per dispatch dimension, the least GL guarantees
/// Pass-1 workgroups, each looping over the queue: on a GPU enough to fill the
/// largest (132 SMs x 2048 threads); on llvmpipe few, as each group costs
/// (the elephant at 256^3: 46 ms with 256 groups, 70-90 ms with 4096).
uint32_t queueGroups(const Context& context) { return context.info().software ? 256 : 4096; }

struct WorkBound {
    uint64_t items = 0;      ///< work items pass 0 can queue, at most
    uint64_t maxColumns = 0; ///< the largest column box of one triangle
};

/// Upper bounds on the work pass 0 queues: for every triangle, the chunks of
/// its column box on whichever axis gives most (the GPU picks the dominant
/// axis in float, which near ties may differ from the host's), with a column
/// of margin for rounding on each side.
WorkBound workBound(const std::vector<Vec3f>& p, const TriangleMesh& mesh, float half, std::array<uint32_t, 3> dims)
{
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, mesh.triangles.size(), 4096), WorkBound{},
        [&](const tbb::blocked_range<size_t>& r, WorkBound sum) {
            for (size_t t = r.begin(); t != r.end(); ++t) {
                const auto& f = mesh.triangles[t];
                std::array<double, 3> lo, hi;
                for (int k = 0; k < 3; ++k) {
                    const double a = (&p[f[0]].x)[k], b = (&p[f[1]].x)[k], c = (&p[f[2]].x)[k];
                    lo[k] = std::min({a, b, c});
                    hi[k] = std::max({a, b, c});
                }
                uint64_t most = 0;
                for (int w = 0; w < 3; ++w) {
                    const int u = (w + 1) % 3, v = (w + 2) % 3;
                    auto span = [&](int a) -> uint64_t {
                        const double first = std::max(std::ceil(lo[a] - half) - 2, 0.0);
                        const double last = std::min(std::floor(hi[a] + half) + 2, double(dims[a]) - 1);
                        return last < first ? 0 : uint64_t(last - first) + 1;
                    };
                    const uint64_t columns = span(u) * span(v);
                    sum.maxColumns = std::max(sum.maxColumns, columns);
                    if (columns > kSmall) most = std::max(most, (columns + kChunk - 1) / kChunk);
                }
                sum.items += most;
            }
            return sum;
        },
        [](WorkBound a, WorkBound b) { return WorkBound{a.items + b.items, std::max(a.maxColumns, b.maxColumns)}; });
}

class ComputeWriter final : public ListWriter {
public:
    ComputeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid, const RasterOptions& options)
        : ListWriter(context, mesh, grid, options), program_(context.program({"voxelize.comp"})),
          queueGroups_(queueGroups(context))
    {
        if (triangles_ > uint64_t(kMaxGroups) * kMaxGroups * 64)
            throw Error(fmt::format("{} triangles are more than one compute dispatch can cover", triangles_));
        const WorkBound bound = workBound(local_, mesh, half_, dims_);
        bound_ = bound.items;
        // The shader counts one triangle's columns in 32 bits.
        if (bound.maxColumns >= (uint64_t(1) << 32) - kChunk)
            throw Error(fmt::format("a triangle spans {} voxel columns, more than the compute backend counts; use "
                                    "--backend raster or a coarser grid",
                                    bound.maxColumns));
        // Each item is 8 bytes; a queue past 2^31 items (16 GB) is refused, not truncated.
        if (bound_ >= (uint64_t(1) << 31))
            throw Error(fmt::format("the compute backend would queue up to {} column chunks, more than one pass "
                                    "holds; use --backend raster or a coarser grid",
                                    bound_));
        work_ = &context.scratch("compute work queue", 8 + std::max<uint64_t>(bound_, 1) * 8);
        program_.set("uHalf", half_);
        program_.set("uDims", int(dims_[0]), int(dims_[1]), int(dims_[2]));
        program_.set("uTriangles", uint32_t(triangles_));
        program_.set("uWorkCapacity", uint32_t(bound_));
        program_.set("uTableMask", 0u);
    }

    void write(const Buffer& list, const Buffer& counter, uint64_t capacity, const Buffer* triangles) const override
    {
        program_.set("uBricks", 0u);
        program_.set("uCapacity", uint32_t(capacity));
        program_.set("uWriteTriangles", triangles ? 1u : 0u);
        (triangles ? *triangles : list).bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_TRIANGLES);
        list.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_LIST);
        list.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_TABLE); // unused in list mode, but bound
        list.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_TABLE_MASKS);
        run(counter);
    }

    /// Brick mode: sets each kept voxel's bit in `tableMasks` through the hash
    /// table `table` (`slots` keys, a power of two, cleared to 0xFFFFFFFF; masks
    /// cleared to 0). `counter` gets the bricks inserted and the voxels that
    /// found the table full. No wait.
    void writeBricks(const Buffer& table, const Buffer& tableMasks, const Buffer& counter, uint64_t slots) const
    {
        program_.set("uBricks", 1u);
        program_.set("uTableMask", uint32_t(slots - 1));
        program_.set("uCapacity", 0u);
        program_.set("uWriteTriangles", 0u);
        table.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_TABLE);
        tableMasks.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_TABLE_MASKS);
        table.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_LIST); // unused in brick mode, but bound
        table.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_TRIANGLES);
        run(counter);
    }

    void checkAfterWrite() const override
    {
        uint32_t header[2] = {0, 0};
        work_->read(0, sizeof header, header);
        if (header[1] || header[0] > bound_)
            throw Error(fmt::format("internal error: the compute backend queued {} column chunks{}, beyond its "
                                    "bound of {}",
                                    header[0], header[1] ? " (wrapped)" : "", bound_));
    }

    uint64_t bytes() const override { return ListWriter::bytes() + work_->bytes(); }

private:
    /// Passes 0 and 1 with the outputs already bound.
    void run(const Buffer& counter) const
    {
        counter.clearUint(0);
        work_->clearUint(0, 8);
        counter.bindBase(GL_ATOMIC_COUNTER_BUFFER, SVO_BIND_RASTER_COUNTER);
        vertices_->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_POSITIONS);
        indices_->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_INDICES);
        work_->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_WORK);
        checkpoint_(0.0, "compute voxelization");
        program_.set("uPass", 0u);
        const uint64_t groups = (triangles_ + 63) / 64;
        if (groups) dispatch(groups);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
        checkpoint_(0.5, "compute voxelization");
        program_.set("uPass", 1u);
        if (bound_) program_.dispatch(uint32_t(std::min<uint64_t>(bound_, queueGroups_)), 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        checkGl("compute voxelization");
    }

    /// `groups` workgroups as x by y, each at most kMaxGroups.
    void dispatch(uint64_t groups) const
    {
        const uint64_t y = (groups + kMaxGroups - 1) / kMaxGroups;
        program_.dispatch(uint32_t(std::min<uint64_t>(groups, kMaxGroups)), uint32_t(y));
    }

    const Program& program_;
    uint32_t queueGroups_;
    const Buffer* work_ = nullptr;
    uint64_t bound_ = 0;
};

uint64_t powerOfTwoAtLeast(uint64_t n)
{
    uint64_t p = 1;
    while (p < n) p <<= 1;
    return p;
}

} // namespace

bool computeWritesBricks(const RasterOptions& options, const GridSpec& grid)
{
    // Bricks carry no per-entry triangles, and the table's keys hold 10 bits of brick per axis.
    return options.pipeline == Pipeline::Compute && !options.attributes && !options.voxelList &&
           grid.maxDim() <= 8192;
}

OctreeVoxelization voxelizeComputeBricks(Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                         const RasterOptions& options)
{
    const Checkpoint& checkpoint = options.checkpoint;
    checkpoint(0.0, "mesh upload");
    RasterOptions writerOptions = options;
    writerOptions.checkpoint = checkpoint.part(0.05, 0.6);
    const ComputeWriter writer(context, mesh, grid, writerOptions);
    const OctreeBuilder builder(context);
    const Program& compact = context.program({"brick_compact.comp"});
    const uint32_t L = brickLevelFor(grid);
    const Buffer& counter = context.scratch("voxel counter", 2 * sizeof(uint32_t)); // bricks, voxels lost
    const Buffer& brickCount = context.scratch("brick count", 2 * sizeof(uint32_t));

    // The table starts at twice the bricks the list estimate implies (so probes
    // stay short) and grows fourfold if it fills; the octree buffers start
    // from the same estimate and grow from the counts if they overflow.
    const uint64_t estimatedBricks = writer.estimatedEntries() / 48 + 64;
    uint64_t slots = powerOfTwoAtLeast(std::max<uint64_t>(1024, 2 * estimatedBricks));
    uint64_t brickCapacity = options.initialBrickCapacity ? options.initialBrickCapacity : estimatedBricks * 2;
    uint64_t nodeCapacity = 0;
    OctreeVoxelization result;
    OctreeBuilder::Build build;
    double fillGpu = 0, fillWall = 0, buildGpu = 0, buildWall = 0;
    uint32_t bricks = 0;
    bool filled = false;
    const Buffer *keys = nullptr, *masks = nullptr;
    for (int attempt = 0;; ++attempt) {
        if (slots > (uint64_t(1) << 31))
            throw Error(fmt::format("the brick table would need {} slots; use a coarser grid", slots));
        auto t0 = Clock::now();
        TimerQuery fillTimer, buildTimer;
        if (!filled) {
            const Buffer& table = context.scratch("brick table", slots * 4);
            const Buffer& tableMasks = context.scratch("brick table masks", slots * sizeof(Brick));
            keys = &context.scratch("brick keys", slots * 8);
            masks = &context.scratch("brick masks", slots * sizeof(Brick));
            fillTimer.begin();
            table.clearUint(0xFFFFFFFFu, slots * 4);
            tableMasks.clearUint(0, slots * sizeof(Brick));
            brickCount.clearUint(0);
            writer.writeBricks(table, tableMasks, counter, slots);
            table.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_TABLE);
            tableMasks.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPUTE_TABLE_MASKS);
            keys->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPACT_KEYS);
            masks->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPACT_MASKS);
            brickCount.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_COMPACT_COUNT);
            compact.set("uSlots", uint32_t(slots));
            compact.dispatch(uint32_t(std::min<uint64_t>((slots + 255) / 256, 4096)));
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
            checkGl("brick compaction");
            fillTimer.end();
        }
        fillWall += msSince(t0);
        t0 = Clock::now();
        checkpoint(0.6, "octree build");
        OctreeInput in;
        in.entries = keys;
        in.listCounter = &brickCount;
        in.entryCapacity = slots;
        in.masks = masks;
        if (!nodeCapacity) nodeCapacity = std::min(OctreeBuilder::nodeBound(L, brickCapacity), 12 * brickCapacity + 1);
        buildTimer.begin();
        build = builder.record(grid, in, nodeCapacity, brickCapacity, [&] { checkpoint(0.6, "octree build"); });
        buildTimer.end();
        waitForGpu([&] { checkpoint(0.6, "voxelization on the GPU"); });
        OctreeBuilder::readCounts(build);
        buildWall += msSince(t0);
        if (!filled) fillGpu += fillTimer.milliseconds();
        buildGpu += buildTimer.milliseconds();
        result.gpuBytes = std::max(result.gpuBytes, writer.bytes() + counter.bytes() + brickCount.bytes() +
                                                        slots * (4 + 2 * sizeof(Brick) + 8) + build.bytes());
        if (!filled) {
            uint32_t c[2] = {0, 0};
            counter.read(0, sizeof c, c);
            writer.checkAfterWrite();
            bricks = c[0];
            if (c[1]) { // the table filled up: voxels were lost, so fill again
                slots *= 4;
                result.overflowRetries = attempt + 1;
                continue;
            }
            filled = true;
        }
        if (!build.overflowed()) break;
        // Every brick is known now: the exact brick count, and nodes from the counts.
        brickCapacity = bricks;
        nodeCapacity = std::max<uint64_t>(build.counts.nodeCount, nodeCapacity) * 2;
        nodeCapacity = std::min(nodeCapacity, OctreeBuilder::nodeBound(L, bricks));
        result.overflowRetries = attempt + 1;
    }
    result.stages.push_back(writer.uploadStage());
    result.stages.push_back({"voxelize", fillGpu, fillWall});
    result.stages.push_back({"octree build", buildGpu, buildWall});
    result.listEntries = 0; // no list: bricks were written directly

    checkpoint(0.85, "octree readback");
    auto t0 = Clock::now();
    TimerQuery readTimer;
    readTimer.begin();
    result.octree = OctreeBuilder::readOctree(build, grid);
    readTimer.end();
    result.stages.push_back({"readback", readTimer.milliseconds(), msSince(t0)});
    return result;
}

std::unique_ptr<ListWriter> makeComputeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                              const RasterOptions& options)
{
    return std::make_unique<ComputeWriter>(context, mesh, grid, options);
}

} // namespace svo::gl
