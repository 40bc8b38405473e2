// The compute backend's list writer (voxelize.comp): triangle-parallel
// compute shaders instead of the raster pipeline, with the same column walk.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <tbb/parallel_for.h>

#include "list_writer.h"
#include "svo/gl/buffer.h"
#include "svo/gl/dispatch_looping.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "svo/core/error.h"
#include "voxelize_shaders.h"

namespace svo::gl {
namespace {

constexpr uint64_t kSmall = 64, kChunk = 64; // as in voxelize.comp
constexpr uint32_t kMaxGroups = 65535;       // per dispatch dimension, the least GL guarantees
/// Pass-1 workgroups, each looping over its dispatch's items: on a GPU enough to fill the
/// largest (132 SMs x 2048 threads); on llvmpipe few, as each group costs
/// (the elephant at 256^3: 46 ms with 256 groups, 70-90 ms with 4096).
uint32_t queueGroups(const Context& context) { return context.info().software ? 256 : 4096; }

/// The most columns voxelize.comp's alongLine walks in one row, over any
/// projection axis: its reach with |slope| <= 1 (the row axis is the line's
/// major one), delta from the exact normal plus the float normal's error
/// bound, and margins beyond the shader's for its float arithmetic.
double rowWidthBound(const Vec3d& a, const Vec3d& b, const Vec3d& c, float half)
{
    const Vec3d e[3] = {b - a, c - a, c - b};
    double E = 0, mag = 0;
    for (const Vec3d& d : e) E = std::max({E, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    for (const Vec3d& q : {a, b, c}) mag = std::max({mag, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
    if (!(E > 0)) return std::numeric_limits<double>::infinity();
    const double ulp = std::ldexp(1.0, -24), dn = 8 * ulp * E * E;
    const Vec3d n = cross(e[0], e[1]);
    const double delta = (std::abs(n.x) + std::abs(n.y) + std::abs(n.z) + 6 * dn) / (E * (1 - 1e-6)) * (1 + 1e-5);
    const double reach = (half + delta) * 2 + 1.0 / 64 + 64 * ulp * (mag + 1);
    return std::floor(2 * reach) + 3;
}

/// The chunks of 64 columns one triangle can need in pass 1, at most: the
/// columns voxelize.comp walks on whichever axis gives most (the GPU picks
/// its projection axis in float, which near ties may differ from the
/// host's), its box with a column of margin for rounding on each side, or
/// fewer along a thin triangle's line; 0 when every axis has at most kSmall
/// columns, which pass 0 walks itself. `maxColumns` gets the largest box.
uint64_t chunkBound(const std::vector<Vec3f>& p, const std::array<uint32_t, 3>& f, float half,
                    std::array<uint32_t, 3> dims, uint64_t& maxColumns)
{
    std::array<double, 3> lo, hi;
    for (int k = 0; k < 3; ++k) {
        const double a = (&p[f[0]].x)[k], b = (&p[f[1]].x)[k], c = (&p[f[2]].x)[k];
        lo[k] = std::min({a, b, c});
        hi[k] = std::max({a, b, c});
    }
    auto corner = [&](uint32_t i) { return Vec3d{p[i].x, p[i].y, p[i].z}; };
    const double rowWidth = rowWidthBound(corner(f[0]), corner(f[1]), corner(f[2]), half);
    uint64_t most = 0;
    for (int w = 0; w < 3; ++w) {
        const int u = (w + 1) % 3, v = (w + 2) % 3;
        auto span = [&](int a) -> uint64_t {
            const double first = std::max(std::ceil(lo[a] - half) - 2, 0.0);
            const double last = std::min(std::floor(hi[a] + half) + 2, double(dims[a]) - 1);
            return last < first ? 0 : uint64_t(last - first) + 1;
        };
        const uint64_t box = span(u) * span(v);
        maxColumns = std::max(maxColumns, box);
        const double alongLine = double(std::max(span(u), span(v))) * rowWidth;
        const uint64_t columns = alongLine < double(box) ? uint64_t(alongLine) : box;
        if (columns > kSmall) most = std::max(most, (columns + kChunk - 1) / kChunk);
    }
    return most;
}

/// Pass 1's work, laid out on the host so that no shader loops over a
/// triangle's chunks: every triangle with a chunk bound, as (triangle, its
/// first item), in triangle order; item i belongs to the last entry whose
/// first item is at most i. Two parallel passes: count per block, then fill.
struct WorkList {
    std::vector<std::array<uint32_t, 2>> large;
    uint64_t items = 0;      ///< all triangles' chunk bounds
    uint64_t maxColumns = 0; ///< the largest column box of one triangle
};

WorkList workList(const std::vector<Vec3f>& p, const TriangleMesh& mesh, float half, std::array<uint32_t, 3> dims)
{
    constexpr size_t kBlock = 1 << 14;
    const size_t n = mesh.triangles.size(), blocks = (n + kBlock - 1) / kBlock;
    struct Block {
        uint64_t large = 0, items = 0, maxColumns = 0;
    };
    std::vector<Block> block(blocks);
    tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
        for (size_t t = b * kBlock; t < std::min(n, (b + 1) * kBlock); ++t)
            if (const uint64_t items = chunkBound(p, mesh.triangles[t], half, dims, block[b].maxColumns)) {
                ++block[b].large;
                block[b].items += items;
            }
    });
    WorkList list;
    std::vector<Block> first(blocks); // exclusive prefix sums
    uint64_t large = 0;
    for (size_t b = 0; b < blocks; ++b) {
        first[b] = {large, list.items, 0};
        large += block[b].large;
        list.items += block[b].items;
        list.maxColumns = std::max(list.maxColumns, block[b].maxColumns);
    }
    // Item indices are 32 bits; refused before they could wrap (checked by the caller).
    if (list.items >= (uint64_t(1) << 31)) return list;
    list.large.resize(large);
    tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
        uint64_t slot = first[b].large, item = first[b].items, unused = 0;
        for (size_t t = b * kBlock; t < std::min(n, (b + 1) * kBlock); ++t)
            if (const uint64_t items = chunkBound(p, mesh.triangles[t], half, dims, unused)) {
                list.large[slot++] = {uint32_t(t), uint32_t(item)};
                item += items;
            }
    });
    return list;
}

class ComputeWriter final : public ListWriter {
public:
    ComputeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid, const RasterOptions& options)
        : ListWriter(context, mesh, grid, options), program_(context.program(voxelizeShaders(), {"voxelize.comp"})),
          queueGroups_(queueGroups(context)), loopLimit_(context.info().loopLimit)
    {
        if (triangles_ >= (uint64_t(1) << 32))
            throw Unsupported(fmt::format("{} triangles are more than the compute backend indexes; use the raster backend",
                                          triangles_));
        const WorkList list = workList(local_, mesh, half_, dims_);
        items_ = list.items;
        // The shader counts one triangle's columns in 32 bits.
        if (list.maxColumns >= (uint64_t(1) << 32) - kChunk)
            throw Unsupported(fmt::format("a triangle spans {} voxel columns, more than the compute backend counts; use the "
                                          "raster backend or a coarser grid",
                                          list.maxColumns));
        if (items_ >= (uint64_t(1) << 31))
            throw Unsupported(fmt::format("the compute backend would need {} column chunks, more than one pass indexes; "
                                          "use the raster backend or a coarser grid",
                                          items_));
        const uint64_t block = context.shaderBufferLimit();
        const uint64_t workBytes = std::max<size_t>(list.large.size(), 1) * sizeof list.large[0];
        if (block && std::max<uint64_t>({local_.size() * 12, triangles_ * 12, workBytes}) > block)
            throw DeviceError(fmt::format("{} vertices and {} triangles are more than one shader buffer of {} bytes holds; "
                                          "use the raster backend",
                                          local_.size(), triangles_, block));
        work_ = &context.scratch("compute work list", workBytes);
        work_->write(0, list.large.size() * sizeof list.large[0], list.large.data());
        program_.set("uHalf", half_);
        program_.set("uThin", thin_ ? 1u : 0u);
        program_.set("uThickness", thickness_);
        program_.set("uTriangles", uint32_t(triangles_));
        program_.set("uLarge", uint32_t(list.large.size()));
    }

    void write(const Buffer& list, const Buffer& counter, uint64_t capacity, const Buffer* triangles) const override
    {
        counter.clearUint(0);
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
        // An item costs its search of the work list (32 steps at most) and a
        // column walk of a few voxels (the projection axis keeps a column's
        // range to a few voxels, needles included), each with the overlap
        // test's 3-step loops: 96 iterations an item for the driver's limit.
        dispatchLooping(program_, items_, uint32_t(std::min<uint64_t>(items_, queueGroups_)), loopLimit_, 96,
                        "uItemFirst", "uItemEnd");
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        checkGl("compute voxelization");
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
    uint64_t items_ = 0; ///< pass 1's work items: every large triangle's chunk bound
};

} // namespace

std::unique_ptr<ListWriter> makeComputeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                              const RasterOptions& options)
{
    return std::make_unique<ComputeWriter>(context, mesh, grid, options);
}

} // namespace svo::gl
