#include "svo/gl/raster_voxelizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "list_writer.h"
#include "svo/gl/buffer.h"
#include "svo/gl/empty_framebuffer.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "svo/gl/timer_query.h"
#include "svo/gl/vertex_array.h"
#include "svo/core/error.h"
#include "voxelize_shaders.h"

namespace svo::gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

bool useHardware(const Context& context, const RasterOptions& o)
{
    if (o.conservative == ConservativeMode::Hardware && !context.info().conservativeRasterNV)
        throw DeviceError("hardware dilation needs GL_NV_conservative_raster, which " + context.info().renderer +
                          " does not offer");
    return o.conservative != ConservativeMode::Shader && o.conservative != ConservativeMode::CentroidPush &&
           context.info().conservativeRasterNV;
}

/// Voxel-list entries a mesh is likely to need. A triangle's voxels number
/// about its projected area times the voxels per column, 1 + (|nu| + |nv|) / |nw|,
/// which is half the L1 norm of its (unnormalized) normal; the conservative
/// fringe adds about its perimeter plus one.
uint64_t estimateEntries(const std::vector<Vec3f>& p, const TriangleMesh& mesh)
{
    // Deterministic: the same mesh always gets the same first capacity.
    const double total = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, mesh.triangles.size(), 4096), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double sum) {
            for (size_t t = r.begin(); t != r.end(); ++t) {
                const auto& f = mesh.triangles[t];
                const Vec3d a{p[f[0]].x, p[f[0]].y, p[f[0]].z}, b{p[f[1]].x, p[f[1]].y, p[f[1]].z},
                    c{p[f[2]].x, p[f[2]].y, p[f[2]].z};
                const Vec3d n = cross(b - a, c - a);
                const double area = 0.5 * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
                auto len = [](Vec3d e) { return std::max({std::abs(e.x), std::abs(e.y), std::abs(e.z)}); };
                sum += 1.5 * (area + len(b - a) + len(c - b) + len(a - c) + 1.0);
            }
            return sum;
        },
        std::plus<double>());
    return uint64_t(std::min(total, 1.0e18)) + 1024; // beyond 2^32 - 1 is refused by makeList
}

/// The raster backend: the program that rasterizes the mesh into the voxel list.
class Rasterizer final : public ListWriter {
public:
    Rasterizer(const Context& context, const TriangleMesh& mesh, const GridSpec& grid, const RasterOptions& options)
        : ListWriter(context, mesh, grid, options), hardware_(useHardware(context, options)),
          program_(context.program(voxelizeShaders(), {"raster.vert", "raster.geom", "raster.frag"}))
    {
        const int maxTile = context.info().maxViewport;
        if (maxTile < 1) throw DeviceError("the GL context reports no usable viewport size");
        vao_.setPositions(*vertices_, 0);
        vao_.setIndices(*indices_);
        checkGl("vertex array");
        const uint32_t side = grid.maxDim();
        tile_ = int(std::min<uint32_t>(side, uint32_t(maxTile)));
        tiles_ = int((side + uint32_t(tile_) - 1) / uint32_t(tile_));
        fbo_ = EmptyFramebuffer(tile_, tile_);
        const double eps = options.guardBand >= 0 ? options.guardBand : grid.epsilon();
        const float dilate = hardware_ ? float(0.5 * eps + 1.0 / 128.0) : half_ + float(1.0 / 128.0);
        program_.set("uCentroidPush", options.conservative == ConservativeMode::CentroidPush ? 1u : 0u);
        program_.set("uHalf", half_);
        program_.set("uThin", thin_ ? 1u : 0u);
        program_.set("uThickness", thickness_);
        program_.set("uDilate", dilate);
        program_.set("uTileSize", float(tile_), float(tile_));
    }

    void write(const Buffer& list, const Buffer& counter, uint64_t capacity, const Buffer* triangles) const override
    {
        counter.clearUint(0);
        program_.set("uCapacity", uint32_t(capacity));
        program_.set("uWriteTriangles", triangles ? 1u : 0u);
        setClipUniforms(program_);
        (triangles ? *triangles : list).bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_TRIANGLES);
        fbo_.bind();
        glViewport(0, 0, tile_, tile_);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        if (hardware_) glEnable(GL_CONSERVATIVE_RASTERIZATION_NV);
        program_.use();
        vao_.bind();
        counter.bindBase(GL_ATOMIC_COUNTER_BUFFER, SVO_BIND_RASTER_COUNTER);
        list.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_RASTER_LIST);
        for (int ty = 0; ty < tiles_; ++ty)
            for (int tx = 0; tx < tiles_; ++tx) {
                checkpoint_(double(ty * tiles_ + tx) / double(tiles_ * tiles_), "rasterization");
                program_.set("uTileOrigin", float(tx * tile_), float(ty * tile_));
                glDrawElements(GL_TRIANGLES, GLsizei(triangles_ * 3), GL_UNSIGNED_INT, nullptr);
            }
        if (hardware_) glDisable(GL_CONSERVATIVE_RASTERIZATION_NV);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        checkGl("rasterization");
    }

private:
    bool hardware_;
    const Program& program_;
    VertexArray vao_;
    EmptyFramebuffer fbo_{1, 1};
    int tile_ = 1, tiles_ = 1;
};

/// The entries a draw produced; an error if the 32-bit counter wrapped.
uint32_t readCount(const Buffer& counter)
{
    uint32_t c[2] = {0, 0};
    counter.read(0, sizeof c, c);
    if (c[1])
        throw Unsupported("the voxel list passed 2^32 entries, more than an atomic counter can address; use a coarser grid");
    return c[0];
}

} // namespace

/// The writer the options ask for.
std::unique_ptr<ListWriter> makeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                       const RasterOptions& options)
{
    if (options.pipeline == Pipeline::Compute) return makeComputeWriter(context, mesh, grid, options);
    return makeRasterWriter(context, mesh, grid, options);
}

const Buffer& makeList(const Context& context, uint64_t capacity)
{
    if (capacity > (uint64_t(1) << 32) - 1)
        throw Unsupported(fmt::format("the voxel list would need {} entries, beyond the 2^32 an atomic counter "
                                      "can address; use a coarser grid",
                                      capacity));
    return context.scratch("voxel list", capacity * 8);
}

/// The list's entries read back, sorted and unique.
std::vector<uint64_t> readList(const Buffer& list, uint32_t count)
{
    std::vector<uint64_t> keys(count);
    if (count) list.readBulk(0, uint64_t(count) * 8, keys.data());
    sortUniqueKeys(keys);
    return keys;
}

ListWriter::ListWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                       const RasterOptions& options)
    : triangles_(mesh.triangles.size()), dims_(grid.dims), checkpoint_(options.checkpoint)
{
    auto t0 = Clock::now();
    uploadTimer_.begin();
    local_ = localPositionsFloat(mesh, grid);
    const uint64_t vertexBytes = local_.size() * sizeof(Vec3f), indexBytes = mesh.triangles.size() * 12;
    vertices_ = &context.scratch("vertex buffer", vertexBytes);
    indices_ = &context.scratch("index buffer", indexBytes);
    vertices_->write(0, vertexBytes, local_.data());
    indices_->write(0, indexBytes, mesh.triangles.data());
    meshBytes_ = vertices_->bytes() + indices_->bytes();
    uploadTimer_.end();
    checkGl("mesh upload");
    uploadWallMs_ = msSince(t0);
    estimate_ = options.initialCapacity ? options.initialCapacity : estimateEntries(local_, mesh);
    const double eps = options.guardBand >= 0 ? options.guardBand : grid.epsilon();
    half_ = float(0.5 + 0.5 * eps);
    thickness_ = float(0.5 * eps);
    thin_ = options.mode == VoxelMode::Thin;
    clip_.hi = grid.dims;
}

void ListWriter::setClipUniforms(const Program& program) const
{
    program.set("uClipLo", int(clip_.lo[0]), int(clip_.lo[1]), int(clip_.lo[2]));
    program.set("uClipHi", int(clip_.hi[0]), int(clip_.hi[1]), int(clip_.hi[2]));
}

std::unique_ptr<ListWriter> makeRasterWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                             const RasterOptions& options)
{
    return std::make_unique<Rasterizer>(context, mesh, grid, options);
}

const char* conservativeModeName(const Context& context, const RasterOptions& options)
{
    if (options.pipeline == Pipeline::Compute) return "";
    if (options.conservative == ConservativeMode::CentroidPush) return "centroid-push (baseline)";
    return useHardware(context, options) ? "hardware" : "shader";
}

Voxelization voxelizeRaster(Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                            const RasterOptions& options, RunStats* report)
{
    const Context::Scope scope(context);
    Voxelization result;
    result.grid = grid;
    RunStats stats;
    const auto writer = makeWriter(context, mesh, grid, options);
    const ListWriter& raster = *writer;

    // Voxelize; if the list overflowed, the counter holds the exact size needed.
    auto t0 = Clock::now();
    const Buffer& counter = context.scratch("voxel counter", 2 * sizeof(uint32_t)); // entries, and wraps past 2^32
    uint64_t capacity = raster.estimatedEntries();
    const Buffer* listBuffer = nullptr;
    double voxelizeGpu = 0;
    uint32_t count = 0;
    const uint64_t block = context.shaderBufferLimit();
    for (int attempt = 0;; ++attempt) {
        // One pass, no tiles (validation reads the whole list): past what a
        // shader addresses, refuse. The estimate runs high, so try with less first.
        if (block && capacity * 8 > block) {
            if (attempt > 0)
                throw DeviceError(fmt::format("the voxel list needs {} entries, more than one shader buffer of {} bytes "
                                              "holds; voxelizeRaster has no tiles: use voxelizeToOctree or a coarser grid",
                                              capacity, block));
            capacity = block / 8;
        }
        listBuffer = &makeList(context, capacity);
        const Buffer& list = *listBuffer;
        TimerQuery timer;
        timer.begin();
        raster.write(list, counter, capacity);
        timer.end();
        count = readCount(counter);
        voxelizeGpu += timer.milliseconds();
        if (count <= capacity) break;
        stats.overflowRetries = attempt + 1;
        capacity = count;
    }
    stats.stages.push_back(raster.uploadStage());
    stats.stages.push_back({"voxelize", voxelizeGpu, msSince(t0)});
    stats.listEntries = count;
    stats.gpuBytes = raster.bytes() + listBuffer->bytes() + counter.bytes();

    t0 = Clock::now();
    TimerQuery readTimer;
    readTimer.begin();
    result.keys.resize(count);
    if (count) listBuffer->readBulk(0, uint64_t(count) * 8, result.keys.data());
    readTimer.end();
    checkGl("voxel list readback");
    stats.stages.push_back({"readback", readTimer.milliseconds(), msSince(t0)});

    t0 = Clock::now();
    sortUniqueKeys(result.keys);
    stats.stages.push_back({"sort+unique (cpu)", -1.0, msSince(t0)});
    if (report) *report = std::move(stats);
    return result;
}

} // namespace svo::gl
