#include "svo/gl/raster_voxelizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "objects.h"
#include "svo/core/error.h"

namespace svo::gl {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

bool useHardware(const Context& context, const RasterOptions& o)
{
    if (o.conservative == ConservativeMode::Hardware && !context.info().conservativeRasterNV)
        throw Error("--conservative hardware needs GL_NV_conservative_raster, which " + context.info().renderer +
                    " does not offer");
    return o.conservative != ConservativeMode::Shader && context.info().conservativeRasterNV;
}

/// Voxel-list entries a mesh is likely to need: each triangle covers about
/// (projected area + perimeter + 1) columns and up to 3 voxels per column.
uint64_t estimateEntries(const std::vector<Vec3f>& p, const TriangleMesh& mesh)
{
    double total = 0;
    for (const auto& f : mesh.triangles) {
        const Vec3d a{p[f[0]].x, p[f[0]].y, p[f[0]].z}, b{p[f[1]].x, p[f[1]].y, p[f[1]].z},
            c{p[f[2]].x, p[f[2]].y, p[f[2]].z};
        const Vec3d n = cross(b - a, c - a);
        const double area = 0.5 * std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
        auto len = [](Vec3d e) { return std::max({std::abs(e.x), std::abs(e.y), std::abs(e.z)}); };
        total += 1.5 * (area + len(b - a) + len(c - b) + len(a - c) + 1.0);
    }
    return uint64_t(std::min(total, 4.0e9)) + 1024;
}

} // namespace

const char* conservativeModeName(const Context& context, const RasterOptions& options)
{
    return useHardware(context, options) ? "hardware" : "shader";
}

Voxelization voxelizeRaster(Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                            const RasterOptions& options)
{
    const bool hardware = useHardware(context, options);
    const int maxTile = context.info().maxViewport;
    if (maxTile < 1) throw Error("the GL context reports no usable viewport size");
    Voxelization result;
    result.grid = grid;

    // Upload.
    auto t0 = Clock::now();
    TimerQuery uploadTimer;
    uploadTimer.begin();
    const std::vector<Vec3f> local = localPositionsFloat(mesh, grid);
    Buffer vertices("vertex buffer", local.size() * sizeof(Vec3f), local.data(), 0);
    Buffer indices("index buffer", mesh.triangles.size() * 3 * sizeof(uint32_t), mesh.triangles.data(), 0);
    VertexArray vao;
    vao.setPositions(vertices, 0);
    vao.setIndices(indices);
    uploadTimer.end();
    checkGl("mesh upload");
    const double uploadWall = msSince(t0);

    // Voxelize: one draw per tile (one tile unless the grid exceeds the viewport).
    t0 = Clock::now();
    const Program program({"raster.vert", "raster.geom", "raster.frag"});
    const uint32_t side = grid.maxDim();
    const int tile = int(std::min<uint32_t>(side, uint32_t(maxTile)));
    const int tiles = int((side + uint32_t(tile) - 1) / uint32_t(tile));
    const EmptyFramebuffer fbo(tile, tile);
    const float half = float(0.5 + 0.5 * grid.epsilon());
    const float dilate = hardware ? float(0.5 * grid.epsilon() + 1.0 / 128.0) : half + float(1.0 / 128.0);
    program.set("uHalf", half);
    program.set("uDilate", dilate);
    program.set("uTileSize", float(tile), float(tile));
    program.set("uDims", int(grid.dims[0]), int(grid.dims[1]), int(grid.dims[2]));
    Buffer counter("voxel counter", sizeof(uint32_t));
    uint64_t capacity = options.initialCapacity ? options.initialCapacity : estimateEntries(local, mesh);
    Buffer list;
    double voxelizeGpu = 0;
    uint64_t entries = 0;
    for (int attempt = 0;; ++attempt) {
        if (capacity > (uint64_t(1) << 32) - 1)
            throw Error(fmt::format("the voxel list would need {} entries, beyond the 2^32 an atomic counter "
                                    "can address; use a coarser grid",
                                    capacity));
        list = Buffer("voxel list", capacity * 8);
        counter.clearUint(0);
        program.set("uCapacity", uint32_t(capacity));
        TimerQuery timer;
        timer.begin();
        fbo.bind();
        glViewport(0, 0, tile, tile);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        if (hardware) glEnable(GL_CONSERVATIVE_RASTERIZATION_NV);
        program.use();
        vao.bind();
        counter.bindBase(GL_ATOMIC_COUNTER_BUFFER, 0);
        list.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
        for (int ty = 0; ty < tiles; ++ty)
            for (int tx = 0; tx < tiles; ++tx) {
                program.set("uTileOrigin", float(tx * tile), float(ty * tile));
                glDrawElements(GL_TRIANGLES, GLsizei(mesh.triangles.size() * 3), GL_UNSIGNED_INT, nullptr);
            }
        if (hardware) glDisable(GL_CONSERVATIVE_RASTERIZATION_NV);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
        timer.end();
        checkGl("rasterization");
        uint32_t count = 0;
        counter.read(0, sizeof count, &count);
        voxelizeGpu += timer.milliseconds();
        entries = count;
        if (count <= capacity) break;
        // The counter kept counting past the end, so it is the exact size needed.
        result.overflowRetries = attempt + 1;
        capacity = count;
    }
    result.stages.push_back({"voxelize", voxelizeGpu, msSince(t0)});
    result.stages.insert(result.stages.begin(), {"upload", uploadTimer.milliseconds(), uploadWall});
    result.listEntries = entries;

    // Read back.
    t0 = Clock::now();
    TimerQuery readTimer;
    readTimer.begin();
    result.keys.resize(entries);
    if (entries) list.read(0, entries * 8, result.keys.data());
    readTimer.end();
    checkGl("voxel list readback");
    result.stages.push_back({"readback", readTimer.milliseconds(), msSince(t0)});

    t0 = Clock::now();
    sortUniqueKeys(result.keys);
    result.stages.push_back({"sort+unique (cpu)", -1.0, msSince(t0)});
    return result;
}

} // namespace svo::gl
