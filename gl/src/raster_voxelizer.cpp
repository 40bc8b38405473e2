#include "svo/gl/raster_voxelizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "list_writer.h"
#include "objects.h"
#include "octree_builder.h"
#include "svo/core/error.h"
#include "svo/core/voxel_attributes.h"

namespace svo::gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

bool useHardware(const Context& context, const RasterOptions& o)
{
    if (o.conservative == ConservativeMode::Hardware && !context.info().conservativeRasterNV)
        throw Error("hardware dilation needs GL_NV_conservative_raster, which " + context.info().renderer +
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
          program_(context.program({"raster.vert", "raster.geom", "raster.frag"}))
    {
        const int maxTile = context.info().maxViewport;
        if (maxTile < 1) throw Error("the GL context reports no usable viewport size");
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
        program_.set("uDims", int(grid.dims[0]), int(grid.dims[1]), int(grid.dims[2]));
    }

    void write(const Buffer& list, const Buffer& counter, uint64_t capacity, const Buffer* triangles) const override
    {
        counter.clearUint(0);
        program_.set("uCapacity", uint32_t(capacity));
        program_.set("uWriteTriangles", triangles ? 1u : 0u);
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

/// The writer the options ask for.
std::unique_ptr<ListWriter> makeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                       const RasterOptions& options)
{
    if (options.pipeline == Pipeline::Compute) return makeComputeWriter(context, mesh, grid, options);
    return makeRasterWriter(context, mesh, grid, options);
}

/// Octree buffer sizes from the voxel-list size. The benchmark scenes hold
/// 68-317 list entries and 2.6-2.7 nodes per brick; these estimates leave room
/// for sparser scenes, and an overflow only costs a rebuild.
uint64_t bricksFor(uint64_t listEntries) { return listEntries / 48 + 64; }
uint64_t nodesFor(uint32_t brickLevel, uint64_t bricks)
{
    return std::min(OctreeBuilder::nodeBound(brickLevel, bricks), 12 * bricks + 1);
}

/// The entries a draw produced; an error if the 32-bit counter wrapped.
uint32_t readCount(const Buffer& counter)
{
    uint32_t c[2] = {0, 0};
    counter.read(0, sizeof c, c);
    if (c[1])
        throw Error("the voxel list passed 2^32 entries, more than an atomic counter can address; use a coarser grid");
    return c[0];
}

const Buffer& makeList(const Context& context, uint64_t capacity)
{
    if (capacity > (uint64_t(1) << 32) - 1)
        throw Error(fmt::format("the voxel list would need {} entries, beyond the 2^32 an atomic counter "
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

/// Sums every list entry's triangle values into its voxel (octree_attributes.comp)
/// and turns the sums into the asked-for channels on the octree.
void attachAttributes(const Program& program, const TriangleMesh& mesh, uint32_t channels,
                      const OctreeBuilder::Build& build, const Buffer& list, const Buffer& triangleList,
                      uint32_t entries, Octree& octree)
{
    const uint64_t voxels = octree.voxelCount();
    if (voxels > (uint64_t(1) << 28))
        throw Error(fmt::format("{} voxels are too many for attribute channels in one pass", voxels));
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

} // namespace

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
                            const RasterOptions& options)
{
    const Context::Scope scope(context);
    Voxelization result;
    result.grid = grid;
    const auto writer = makeWriter(context, mesh, grid, options);
    const ListWriter& raster = *writer;

    // Voxelize; if the list overflowed, the counter holds the exact size needed.
    auto t0 = Clock::now();
    const Buffer& counter = context.scratch("voxel counter", 2 * sizeof(uint32_t)); // entries, and wraps past 2^32
    uint64_t capacity = raster.estimatedEntries();
    const Buffer* listBuffer = nullptr;
    double voxelizeGpu = 0;
    uint32_t count = 0;
    for (int attempt = 0;; ++attempt) {
        listBuffer = &makeList(context, capacity);
        const Buffer& list = *listBuffer;
        TimerQuery timer;
        timer.begin();
        raster.write(list, counter, capacity);
        timer.end();
        count = readCount(counter);
        raster.checkAfterWrite();
        voxelizeGpu += timer.milliseconds();
        if (count <= capacity) break;
        result.overflowRetries = attempt + 1;
        capacity = count;
    }
    result.stages.push_back(raster.uploadStage());
    result.stages.push_back({"voxelize", voxelizeGpu, msSince(t0)});
    result.listEntries = count;
    result.gpuBytes = raster.bytes() + listBuffer->bytes() + counter.bytes();

    t0 = Clock::now();
    TimerQuery readTimer;
    readTimer.begin();
    result.keys.resize(count);
    if (count) listBuffer->readBulk(0, uint64_t(count) * 8, result.keys.data());
    readTimer.end();
    checkGl("voxel list readback");
    result.stages.push_back({"readback", readTimer.milliseconds(), msSince(t0)});

    t0 = Clock::now();
    sortUniqueKeys(result.keys);
    result.stages.push_back({"sort+unique (cpu)", -1.0, msSince(t0)});
    return result;
}

OctreeVoxelization voxelizeToOctree(Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                    const RasterOptions& options)
{
    const Context::Scope scope(context);
    const Checkpoint& checkpoint = options.checkpoint;
    checkpoint(0.0, "mesh upload");
    OctreeVoxelization result;
    RasterOptions rasterOptions = options;
    rasterOptions.checkpoint = checkpoint.part(0.05, 0.6);
    const auto writer = makeWriter(context, mesh, grid, rasterOptions);
    const ListWriter& raster = *writer;
    // Every program the call needs, and no other, made before the stages are timed.
    const OctreeBuilder builder(context);
    const Program* attributeProgram = options.attributes ? &context.program({"octree_attributes.comp"}) : nullptr;
    const uint32_t L = brickLevelFor(grid);
    const Buffer& counter = context.scratch("voxel counter", 2 * sizeof(uint32_t)); // entries, and wraps past 2^32

    // Rasterize and build without waiting; read the counters once. A full
    // voxel list means rasterizing again at the counted size; full node or
    // brick buffers mean building again with room for what was counted.
    uint64_t listCapacity = raster.estimatedEntries();
    uint64_t brickCapacity = options.initialBrickCapacity ? options.initialBrickCapacity : bricksFor(listCapacity);
    uint64_t nodeCapacity = nodesFor(L, bricksFor(listCapacity));
    const Buffer* listBuffer = nullptr;
    const Buffer* triangleBuffer = nullptr;
    OctreeBuilder::Build build;
    double voxelizeGpu = 0, buildGpu = 0, voxelizeWall = 0, buildWall = 0;
    uint32_t count = 0;
    bool drawn = false;
    for (int attempt = 0;; ++attempt) {
        auto t0 = Clock::now();
        TimerQuery drawTimer, buildTimer;
        if (!drawn) {
            listBuffer = &makeList(context, listCapacity);
            if (options.attributes) triangleBuffer = &context.scratch("triangle list", listCapacity * 4);
            drawTimer.begin();
            raster.write(*listBuffer, counter, listCapacity, triangleBuffer);
            drawTimer.end();
        }
        voxelizeWall += msSince(t0);
        t0 = Clock::now();
        checkpoint(0.6, "octree build");
        OctreeInput in;
        in.entries = listBuffer;
        in.listCounter = &counter;
        in.entryCapacity = listCapacity;
        buildTimer.begin();
        build = builder.record(grid, in, nodeCapacity, brickCapacity, [&] { checkpoint(0.6, "octree build"); });
        buildTimer.end();
        // The GPU works now; wait for it in slices so an interrupter is heard meanwhile.
        waitForGpu([&] { checkpoint(0.6, "voxelization on the GPU"); });
        OctreeBuilder::readCounts(build);
        count = readCount(counter);
        if (!drawn) raster.checkAfterWrite();
        buildWall += msSince(t0);
        if (!drawn) voxelizeGpu += drawTimer.milliseconds();
        buildGpu += buildTimer.milliseconds();
        result.gpuBytes =
            std::max(result.gpuBytes, raster.bytes() + listBuffer->bytes() +
                                          (triangleBuffer ? triangleBuffer->bytes() : 0) + counter.bytes() + build.bytes());
        if (count > listCapacity) {
            listCapacity = count; // the counter kept counting: the exact size
            brickCapacity = std::max<uint64_t>(brickCapacity, bricksFor(listCapacity));
            nodeCapacity = std::max(nodeCapacity, nodesFor(L, brickCapacity));
        } else if (build.overflowed()) {
            drawn = true; // the list is complete; only the octree needs room
            if (build.counts.nodeCount <= build.nodeCapacity) {
                brickCapacity = build.counts.brickCount; // every brick node was reached: exact
            } else {
                brickCapacity = std::max<uint64_t>(build.counts.brickCount, brickCapacity) * 2;
                // Counts past an overflowed level are lower bounds: double, never shrink.
                nodeCapacity = std::max<uint64_t>(build.counts.nodeCount, nodeCapacity) * 2;
            }
        } else {
            break;
        }
        result.overflowRetries = attempt + 1;
    }
    result.stages.push_back(raster.uploadStage());
    result.stages.push_back({"voxelize", voxelizeGpu, voxelizeWall});
    result.stages.push_back({"octree build", buildGpu, buildWall});
    result.listEntries = count;

    checkpoint(0.85, "octree readback");
    auto t0 = Clock::now();
    TimerQuery readTimer;
    readTimer.begin();
    result.octree = OctreeBuilder::readOctree(build, grid);
    readTimer.end();
    result.stages.push_back({"readback", readTimer.milliseconds(), msSince(t0)});
    if (options.voxelList) *options.voxelList = readList(*listBuffer, count);

    if (options.attributes) {
        checkpoint(0.95, "attribute channels");
        t0 = Clock::now();
        TimerQuery attrTimer;
        attrTimer.begin();
        attachAttributes(*attributeProgram, mesh, options.attributes, build, *listBuffer, *triangleBuffer, count,
                         result.octree);
        attrTimer.end();
        result.stages.push_back({"attributes", attrTimer.milliseconds(), msSince(t0)});
    }
    return result;
}

} // namespace svo::gl
