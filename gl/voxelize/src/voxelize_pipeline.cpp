#include "svo/gl/voxelize_pipeline.h"

#include <algorithm>
#include <chrono>

#include "svo/core/cpu_voxelizer.h"
#include "svo/core/error.h"
#include "svo/core/voxel_attributes.h"
#include "svo/gl/octree_builder.h"
#include "svo/gl/raster_voxelizer.h"

namespace svo {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

gl::ConservativeMode conservativeMode(Dilation d)
{
    switch (d) {
    case Dilation::Hardware: return gl::ConservativeMode::Hardware;
    case Dilation::Shader: return gl::ConservativeMode::Shader;
    case Dilation::CentroidPush: return gl::ConservativeMode::CentroidPush;
    case Dilation::Auto: break;
    }
    return gl::ConservativeMode::Auto;
}

/// The CPU reference: voxels, octree and channels, each a stage.
Octree voxelizeOnCpu(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeSettings& settings,
                     const Checkpoint& checkpoint, VoxelizeStats& stats, std::vector<uint64_t>* voxelList)
{
    auto t0 = Clock::now();
    const Checkpoint part = checkpoint.part(0.0, 0.6);
    const VoxelBox box = settings.region ? localBox(grid, *settings.region) : wholeBox(grid);
    Voxelization v = voxelizeCpu(mesh, grid, box, 0.0, settings.mode, [&](double f) { part(f, "voxelize (cpu)"); });
    stats.stages.push_back({"voxelize (cpu)", -1, msSince(t0)});
    checkpoint(0.6, "octree build");
    t0 = Clock::now();
    Octree octree = buildOctree(grid, v.keys);
    stats.stages.push_back({"octree build (cpu)", -1, msSince(t0)});
    if (settings.attributes) {
        checkpoint(0.8, "attribute channels");
        t0 = Clock::now();
        attachAttributesCpu(mesh, octree, settings.attributes, 0.0, settings.mode);
        stats.stages.push_back({"attributes (cpu)", -1, msSince(t0)});
    }
    stats.listEntries = v.keys.size();
    if (voxelList) *voxelList = std::move(v.keys);
    return octree;
}

/// The raster or compute backend with the octree built on the GPU.
Octree voxelizeOnGpu(gl::Context& context, const TriangleMesh& mesh, const GridSpec& grid, Backend backend,
                     const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats,
                     std::vector<uint64_t>* voxelList)
{
    gl::RasterOptions ro;
    ro.pipeline = backend == Backend::Compute ? gl::Pipeline::Compute : gl::Pipeline::Raster;
    ro.conservative = conservativeMode(settings.dilation);
    ro.mode = settings.mode;
    ro.attributes = settings.attributes;
    ro.checkpoint = checkpoint.part(0.0, 0.98);
    ro.voxelList = voxelList;
    ro.gpuMemory = settings.gpuMemory;
    if (settings.region) ro.box = localBox(grid, *settings.region);
    stats.dilation = gl::conservativeModeName(context, ro);
    RunStats report;
    Octree octree = gl::voxelizeToOctree(context, mesh, grid, ro, &report);
    stats.stages = std::move(report.stages);
    stats.listEntries = report.listEntries;
    stats.overflowRetries = report.overflowRetries;
    stats.gpuBytes = report.gpuBytes;
    stats.tiles = report.tiles;
    return octree;
}

} // namespace

double VoxelizeStats::gpuMs() const
{
    double sum = 0;
    for (const auto& s : stages) sum += std::max(s.gpuMs, 0.0);
    return sum;
}

VoxelizeStats medianStats(const std::vector<VoxelizeStats>& runs)
{
    if (runs.empty()) throw InvalidInput("medianStats needs at least one run");
    VoxelizeStats out = runs.back();
    for (size_t s = 0; s < out.stages.size(); ++s) {
        std::vector<double> gpu, wall;
        for (const auto& r : runs)
            if (s < r.stages.size()) gpu.push_back(r.stages[s].gpuMs), wall.push_back(r.stages[s].wallMs);
        std::sort(gpu.begin(), gpu.end());
        std::sort(wall.begin(), wall.end());
        out.stages[s].gpuMs = gpu[gpu.size() / 2];
        out.stages[s].wallMs = wall[wall.size() / 2];
    }
    return out;
}

namespace gl {

namespace {

/// Auto's rule (docs/design.md, "Which backend auto picks"): the GPU passes
/// on a GPU, the CPU ones where there is no GL or only a software renderer
/// (bench/results/cpu-2core-llvmpipe/auto_rule.md and cpu_fields.md: the CPU
/// wins there for every kind). A device the caller named keeps the GL work.
bool autoPicksCpu(Device& device, const VoxelizeSettings& settings, bool create)
{
    if (device.named()) return false;
    if (device.withoutGl(false)) return true; // no GL library, or a context failed before
    // A GPU memory budget asks for the GPU passes wherever there is GL, as a dilation mode asks for raster.
    if (settings.gpuMemory) return create && device.withoutGl(true);
    if (device.software(false)) return true; // EGL's device list says so without a context
    return create && (device.withoutGl(true) || device.software(true));
}

/// Options that name a backend they do not apply to (the library's rules, so
/// that every front end refuses them alike).
void checkBackendOptions(const VoxelizeSettings& settings)
{
    // A dilation mode is a raster option: asking for one picks the raster backend.
    if (settings.backend == Backend::Compute && settings.dilation != Dilation::Auto)
        throw InvalidInput("a dilation mode applies to the raster backend; the compute backend needs none");
    // A budget asked of the CPU would be ignored: the CPU backend allocates no GPU memory.
    if (settings.backend == Backend::Cpu && settings.gpuMemory)
        throw InvalidInput(std::vector<Error::Part>{Error::option("VoxelizeOptions::gpuMemory"),
                                                    " applies to the GPU backends, not to ",
                                                    Error::option("VoxelizeOptions::backend"), " cpu"});
}

} // namespace

Backend resolveBackend(Device& device, const VoxelizeSettings& settings, bool create)
{
    checkBackendOptions(settings);
    if (settings.backend != Backend::Auto) return settings.backend;
    if (settings.dilation != Dilation::Auto) return Backend::Raster;
    if (autoPicksCpu(device, settings, create)) return Backend::Cpu;
    // Measured (bench/results/nvidia-h100/compute.md): compute is the faster
    // on a hardware GPU; raster stays for a named software device, where the
    // two are close and raster is validated longest.
    return device.software(create) ? Backend::Raster : Backend::Compute;
}

bool runsOnCpu(Device& device, const VoxelizeSettings& settings, bool create)
{
    checkBackendOptions(settings);
    if (settings.backend == Backend::Cpu) return true;
    return settings.backend == Backend::Auto && settings.dilation == Dilation::Auto && autoPicksCpu(device, settings, create);
}

void describeBackend(Device& device, Backend backend, VoxelizeStats& stats)
{
    const bool cpu = backend == Backend::Cpu;
    stats.backend = nameOf(backend);
    stats.device = cpu ? "cpu" : device.describe();
    stats.renderer = cpu ? "cpu" : device.context().info().renderer;
}

Octree voxelizeMesh(Device& device, const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeSettings& settings,
                    const Checkpoint& checkpoint, VoxelizeStats& stats, std::vector<uint64_t>* voxelList)
{
    checkpoint(0.0, "start");
    if (settings.region) checkRegion(*settings.region);
    stats.grid = grid;
    stats.epsilon = grid.epsilon();
    if (availableChannels(mesh, settings.attributes) != settings.attributes)
        stats.warnings.push_back(mesh.source + " has no vertex colours; the color channel is left out");
    const Backend backend = resolveBackend(device, settings);
    describeBackend(device, backend, stats);
    stats.mode = voxelModeName(settings.mode);
    Octree octree = backend == Backend::Cpu
                        ? voxelizeOnCpu(mesh, grid, settings, checkpoint, stats, voxelList)
                        : voxelizeOnGpu(device.context(), mesh, grid, backend, settings, checkpoint, stats, voxelList);
    // The channels asked for, also where no voxel holds them (an empty region).
    octree.attributes.computed = availableChannels(mesh, settings.attributes);
    stats.startup = device.takeStartup(stats.warnings);
    stats.voxels = octree.voxelCount();
    stats.bricks = octree.bricks.size();
    return octree;
}

Octree bricksToOctree(Device& device, const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> bricks,
                      Backend backend, const Checkpoint& checkpoint, VoxelizeStats& stats)
{
    stats.grid = grid;
    describeBackend(device, backend, stats);
    Octree octree;
    if (backend == Backend::Cpu) {
        checkpoint(0.0, "octree build");
        const auto t0 = Clock::now();
        octree = buildOctreeFromBricks(grid, std::move(bricks));
        stats.stages.push_back({"octree build (cpu)", -1, msSince(t0)});
    } else {
        RunStats report;
        octree = buildOctreeGpu(device.context(), grid, bricks, checkpoint.part(0.0, 0.98), &report);
        stats.stages = std::move(report.stages);
        stats.gpuBytes = report.gpuBytes;
    }
    stats.startup = device.takeStartup(stats.warnings);
    stats.voxels = octree.voxelCount();
    stats.bricks = octree.bricks.size();
    return octree;
}

} // namespace gl
} // namespace svo
