// The compute backend's list writer (voxelize.comp): triangle-parallel
// compute shaders instead of the raster pipeline, with the same column walk.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "list_writer.h"
#include "svo/core/error.h"

namespace svo::gl {
namespace {

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
          queueGroups_(queueGroups(context)), loopLimit_(context.info().loopLimit)
    {
        if (triangles_ > uint64_t(kMaxGroups) * kMaxGroups * 64)
            throw Error(fmt::format("{} triangles are more than one compute dispatch can cover", triangles_));
        const WorkBound bound = workBound(local_, mesh, half_, dims_);
        bound_ = bound.items;
        // The shader counts one triangle's columns in 32 bits.
        if (bound.maxColumns >= (uint64_t(1) << 32) - kChunk)
            throw Error(fmt::format("a triangle spans {} voxel columns, more than the compute backend counts; use the "
                                    "raster backend or a coarser grid",
                                    bound.maxColumns));
        // Each item is 8 bytes; a queue past 2^31 items (16 GB) is refused, not truncated.
        if (bound_ >= (uint64_t(1) << 31))
            throw Error(fmt::format("the compute backend would queue up to {} column chunks, more than one pass "
                                    "holds; use the raster backend or a coarser grid",
                                    bound_));
        const uint64_t block = context.shaderBufferLimit();
        if (block && std::max<uint64_t>(local_.size(), triangles_) * 12 > block)
            throw Error(fmt::format("{} vertices and {} triangles are more than one shader buffer of {} bytes holds; "
                                    "use the raster backend",
                                    local_.size(), triangles_, block));
        if (block && 8 + bound_ * 8 > block)
            throw Error(fmt::format("the compute backend would queue up to {} column chunks, more than one shader "
                                    "buffer of {} bytes holds; use the raster backend or a coarser grid",
                                    bound_, block));
        work_ = &context.scratch("compute work queue", 8 + std::max<uint64_t>(bound_, 1) * 8);
        program_.set("uHalf", half_);
        program_.set("uThin", thin_ ? 1u : 0u);
        program_.set("uThickness", thickness_);
        program_.set("uTriangles", uint32_t(triangles_));
        program_.set("uWorkCapacity", uint32_t(bound_));
    }

    void write(const Buffer& list, const Buffer& counter, uint64_t capacity, const Buffer* triangles) const override
    {
        counter.clearUint(0);
        work_->clearUint(0, 8);
        program_.set("uCapacity", uint32_t(capacity));
        program_.set("uWriteTriangles", triangles ? 1u : 0u);
        setClipUniforms(program_);
        (triangles ? *triangles : list).bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_TRIANGLES);
        counter.bindBase(GL_ATOMIC_COUNTER_BUFFER, SVO_BIND_RASTER_COUNTER);
        list.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_LIST);
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
        // An item loops at most 1 + its column's voxels (a few: the dominant
        // axis keeps the triangle's slope at most 1) times the overlap test's
        // 3-step loops: 64 iterations an item are allowed for the driver's limit.
        dispatchLooping(program_, bound_, uint32_t(std::min<uint64_t>(bound_, queueGroups_)), loopLimit_, 64,
                        "uItemFirst", "uItemEnd");
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        checkGl("compute voxelization");
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
    /// `groups` workgroups as x by y, each at most kMaxGroups.
    void dispatch(uint64_t groups) const
    {
        const uint64_t y = (groups + kMaxGroups - 1) / kMaxGroups;
        program_.dispatch(uint32_t(std::min<uint64_t>(groups, kMaxGroups)), uint32_t(y));
    }

    const Program& program_;
    uint32_t queueGroups_;
    uint64_t loopLimit_; ///< ContextInfo::loopLimit
    const Buffer* work_ = nullptr;
    uint64_t bound_ = 0;
};

} // namespace

std::unique_ptr<ListWriter> makeComputeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                              const RasterOptions& options)
{
    return std::make_unique<ComputeWriter>(context, mesh, grid, options);
}

} // namespace svo::gl
