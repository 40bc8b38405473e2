// svo voxelize [MESH] -o out.vdb [--resolution N | --voxel-size h]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "progress.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/gl/raster_voxelizer.h"
#include "svo/vdb_io/vdb_file.h"

namespace svo::app {
namespace {

struct VoxelizeArgs {
    std::string mesh;
    std::string output;
    int64_t resolution = 0;
    double voxelSize = 0;
    std::string backend = "raster";
    std::string conservative = "auto";
    std::string device;
    bool fog = false;
    bool glDebug = false;
    int repeat = 1;
};

/// Per-stage medians over repeated runs (the voxels of the last run are kept).
Voxelization medianOf(std::vector<Voxelization> runs)
{
    std::vector<StageTime> stages = runs.back().stages;
    for (size_t s = 0; s < stages.size(); ++s) {
        std::vector<double> gpu, wall;
        for (const auto& r : runs) gpu.push_back(r.stages[s].gpuMs), wall.push_back(r.stages[s].wallMs);
        std::sort(gpu.begin(), gpu.end());
        std::sort(wall.begin(), wall.end());
        stages[s].gpuMs = gpu[gpu.size() / 2];
        stages[s].wallMs = wall[wall.size() / 2];
    }
    Voxelization out = std::move(runs.back());
    out.stages = std::move(stages);
    return out;
}

std::string thousands(uint64_t n)
{
    std::string s = std::to_string(n);
    for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
    return s;
}

void runVoxelize(const VoxelizeArgs& a, const CLI::App& cmd)
{
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const bool gotRes = cmd.count("--resolution") > 0, gotSize = cmd.count("--voxel-size") > 0;
    if (gotRes && a.resolution < 1) throw Error(fmt::format("--resolution must be at least 1, got {}", a.resolution));
    if (gotSize && !(a.voxelSize > 0)) throw Error(fmt::format("--voxel-size must be positive, got {}", a.voxelSize));
    GridRequest request;
    request.resolution = gotRes ? a.resolution : (gotSize ? 0 : 256);
    request.voxelSize = gotSize ? a.voxelSize : 0;

    // Load first: a bad mesh must fail before any output is considered.
    TriangleMesh mesh;
    {
        Progress p("loading " + (a.mesh.empty() ? std::string("built-in scene") : a.mesh));
        mesh = a.mesh.empty() ? cornellBox() : loadMesh(a.mesh);
    }
    for (const auto& w : mesh.warnings) fmt::print(stderr, "svo: warning: {}\n", w);
    const std::string scene = a.mesh.empty() ? mesh.source : std::filesystem::path(a.mesh).stem().string();
    const std::string output = a.output.empty() ? scene + ".vdb" : a.output;
    vdb::checkWritable(output);
    const GridSpec grid = makeGrid(mesh, request);

    Voxelization vox;
    std::string backendLine, renderer = "cpu";
    if (a.backend == "raster") {
        gl::ContextOptions co;
        co.device = a.device;
        co.debug = a.glDebug;
        gl::Context context(co);
        const auto& info = context.info();
        gl::RasterOptions ro;
        ro.conservative = a.conservative == "hardware" ? gl::ConservativeMode::Hardware
                          : a.conservative == "shader" ? gl::ConservativeMode::Shader
                                                       : gl::ConservativeMode::Auto;
        renderer = info.renderer;
        std::string exts = info.extensionsUsed.empty() ? "" : fmt::format(", {}", fmt::join(info.extensionsUsed, ", "));
        if (std::string(gl::conservativeModeName(context, ro)) == "hardware") exts += ", GL_NV_conservative_raster";
        backendLine = fmt::format("raster, {} dilation, on {} | {} | {} ({}{})", gl::conservativeModeName(context, ro),
                                  info.vendor, info.renderer, info.version, info.eglDevice, exts);
        Progress p("voxelizing on the GPU");
        if (a.repeat > 1) gl::voxelizeRaster(context, mesh, grid, ro); // warm-up
        std::vector<Voxelization> runs;
        for (int i = 0; i < std::max(a.repeat, 1); ++i) runs.push_back(gl::voxelizeRaster(context, mesh, grid, ro));
        vox = medianOf(std::move(runs));
    } else {
        backendLine = "cpu (double-precision reference)";
        Progress p("voxelizing on the CPU");
        std::vector<Voxelization> runs;
        for (int i = 0; i < std::max(a.repeat, 1); ++i) runs.push_back(voxelizeCpu(mesh, grid));
        vox = medianOf(std::move(runs));
    }

    vdb::WriteOptions wo;
    wo.fog = a.fog;
    wo.metadata = {{"svo:source", mesh.source},
                   {"svo:triangles", std::to_string(mesh.triangles.size())},
                   {"svo:grid", gotSize ? fmt::format("voxel size {}", grid.voxelSize)
                                        : fmt::format("resolution {}", request.resolution)},
                   {"svo:voxel_size", fmt::format("{}", grid.voxelSize)},
                   {"svo:backend", a.backend},
                   {"svo:renderer", renderer},
                   {"svo:epsilon", fmt::format("{:.3g}", grid.epsilon())},
                   {"svo:version", SVO_VERSION}};
    vdb::WriteStats ws;
    {
        Progress p("writing " + output);
        ws = vdb::writeVdb(output, vox, wo);
    }
    vox.stages.push_back({"vdb build (cpu)", -1, ws.buildMs});
    vox.stages.push_back({"vdb write", -1, ws.writeMs});
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

    fmt::print("svo voxelize\n");
    fmt::print("  {:<11} {}\n", "scene", scene);
    fmt::print("  {:<11} {}\n", "triangles", thousands(mesh.triangles.size()));
    fmt::print("  {:<11} {} x {} x {} local voxels, voxel size {:.6g}, {}\n", "grid", grid.dims[0], grid.dims[1],
               grid.dims[2], grid.voxelSize,
               gotSize ? std::string("from --voxel-size") : fmt::format("resolution {}", request.resolution));
    fmt::print("  {:<11} {}\n", "voxels", thousands(vox.keys.size()));
    fmt::print("  {:<11} {}\n", "backend", backendLine);
    fmt::print("  {:<11} {:.3g} voxels (cubes grown by half of it on the GPU)\n", "guard band", grid.epsilon());
    fmt::print("  {:<11} {} entries, {} overflow retries\n", "voxel list", thousands(vox.listEntries),
               vox.overflowRetries);
    fmt::print("  {:<11} {} ({:.2f} MB, {} leaves{})\n", "output", output, double(ws.bytes) / 1e6, thousands(ws.leaves),
               a.fog ? ", with fog grid" : "");
    fmt::print("\n  {:<20} {:>10} {:>10}{}\n", "stage", "GPU ms", "wall ms",
               a.repeat > 1 ? fmt::format("   (voxelize stages: median of {} runs after a warm-up)", a.repeat) : "");
    for (const auto& s : vox.stages)
        fmt::print("  {:<20} {:>10} {:>10.2f}\n", s.name, s.gpuMs < 0 ? std::string("-") : fmt::format("{:.3f}", s.gpuMs),
                   s.wallMs);
    fmt::print("  {:<20} {:>10} {:>10.2f}\n", "total", "", wall);
}

} // namespace

void addVoxelizeCommand(CLI::App& app)
{
    auto args = std::make_shared<VoxelizeArgs>();
    CLI::App* cmd = app.add_subcommand("voxelize", "Voxelize a mesh (default: the built-in Cornell box) into a .vdb");
    cmd->add_option("mesh", args->mesh, "Mesh file (.obj, .ply, .stl, .off); none = built-in Cornell box");
    cmd->add_option("-o,--output", args->output, "Output .vdb (default: <scene>.vdb)");
    auto* res = cmd->add_option("-r,--resolution", args->resolution,
                                "Voxels along the longest bounding-box side (default 256)");
    auto* size = cmd->add_option("--voxel-size", args->voxelSize, "Voxel size in world units");
    res->excludes(size);
    cmd->add_option("--backend", args->backend, "raster (GPU) or cpu (double-precision reference)")
        ->check(CLI::IsMember({"raster", "cpu"}))
        ->capture_default_str();
    cmd->add_option("--conservative", args->conservative,
                    "Raster dilation: auto, hardware (GL_NV_conservative_raster) or shader")
        ->check(CLI::IsMember({"auto", "hardware", "shader"}))
        ->capture_default_str();
    cmd->add_option("--device", args->device, "EGL device: auto, hardware, software or an index (env SVO_EGL_DEVICE)");
    cmd->add_flag("--fog", args->fog, "Also write a fog-volume FloatGrid 'density'");
    cmd->add_option("--repeat", args->repeat,
                    "Voxelize N times (after one warm-up on the GPU) and report per-stage medians")
        ->check(CLI::Range(1, 1000));
    cmd->add_flag("--gl-debug", args->glDebug, "Print GL debug messages");
    cmd->callback([args, cmd] { runVoxelize(*args, *cmd); });
}

} // namespace svo::app
