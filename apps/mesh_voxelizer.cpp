#include "mesh_voxelizer.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>

#include "progress.h"
#include "svo/core/error.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_attributes.h"
#include "svo/gl/raster_voxelizer.h"

namespace svo::app {
namespace {

/// Per-stage medians over repeated runs (the result of the last run is kept).
gl::OctreeVoxelization medianOf(std::vector<gl::OctreeVoxelization> runs)
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
    gl::OctreeVoxelization out = std::move(runs.back());
    out.stages = std::move(stages);
    return out;
}

gl::OctreeVoxelization cpuOctree(const TriangleMesh& mesh, const GridSpec& grid, uint32_t attributes)
{
    using Clock = std::chrono::steady_clock;
    Voxelization v = voxelizeCpu(mesh, grid);
    gl::OctreeVoxelization out;
    static_cast<RunStats&>(out) = v;
    const auto t0 = Clock::now();
    out.octree = buildOctree(grid, v.keys);
    out.stages.push_back({"octree build (cpu)", -1, std::chrono::duration<double, std::milli>(Clock::now() - t0).count()});
    if (attributes) {
        const auto t1 = Clock::now();
        attachAttributesCpu(mesh, out.octree, attributes, 0.0);
        out.stages.push_back({"attributes (cpu)", -1, std::chrono::duration<double, std::milli>(Clock::now() - t1).count()});
    }
    return out;
}

} // namespace

void addBackendOptions(CLI::App& cmd, BackendSettings& s)
{
    cmd.add_option("--backend", s.backend, "raster (GPU) or cpu (double-precision reference)")
        ->check(CLI::IsMember({"raster", "cpu"}))
        ->capture_default_str();
    cmd.add_option("--conservative", s.conservative,
                   "Raster dilation: auto, hardware (GL_NV_conservative_raster), shader, or centroid (the seed "
                   "report's vertex push; a benchmark baseline that misses voxels)")
        ->check(CLI::IsMember({"auto", "hardware", "shader", "centroid"}))
        ->capture_default_str();
    cmd.add_option("--device", s.device, "EGL device: auto, hardware, software or an index (env SVO_EGL_DEVICE)");
    cmd.add_flag("--gl-debug", s.glDebug, "Print GL debug messages");
}

void addAttributeOption(CLI::App& cmd, BackendSettings& s)
{
    cmd.add_option_function<std::vector<std::string>>(
           "--attributes",
           [&s](const std::vector<std::string>& names) {
               for (const auto& n : names)
                   s.attributes |= n == "normal" ? kNormals : n == "triangle" ? kTriangles : kColors;
           },
           "Per-voxel channels: normal, triangle (smallest triangle id), color (needs vertex colours)")
        ->delimiter(',')
        ->check(CLI::IsMember({"normal", "triangle", "color"}));
}

MeshVoxelization voxelizeMesh(const TriangleMesh& mesh, const GridSpec& grid, const BackendSettings& s)
{
    MeshVoxelization out;
    if (availableChannels(mesh, s.attributes) != s.attributes)
        fmt::print(stderr, "svo: warning: {} has no vertex colours; the color channel is left out\n", mesh.source);
    std::vector<gl::OctreeVoxelization> runs;
    const int n = std::max(s.repeat, 1);
    if (s.backend == "cpu") {
        out.backendLine = "cpu (double-precision reference)";
        out.renderer = "cpu";
        Progress p("voxelizing on the CPU");
        for (int i = 0; i < n; ++i) runs.push_back(cpuOctree(mesh, grid, s.attributes));
    } else {
        gl::ContextOptions co;
        co.device = s.device;
        co.debug = s.glDebug;
        gl::Context context(co);
        const auto& info = context.info();
        gl::RasterOptions ro;
        ro.conservative = s.conservative == "hardware" ? gl::ConservativeMode::Hardware
                          : s.conservative == "shader" ? gl::ConservativeMode::Shader
                          : s.conservative == "centroid" ? gl::ConservativeMode::CentroidPush
                                                       : gl::ConservativeMode::Auto;
        ro.attributes = s.attributes;
        out.renderer = info.renderer;
        const std::string mode = gl::conservativeModeName(context, ro);
        std::string exts = info.extensionsUsed.empty() ? "" : fmt::format(", {}", fmt::join(info.extensionsUsed, ", "));
        if (mode == "hardware") exts += ", GL_NV_conservative_raster";
        out.backendLine = fmt::format("raster, {} dilation, on {} | {} | {} ({}{})", mode, info.vendor, info.renderer,
                                      info.version, info.eglDevice, exts);
        Progress p("voxelizing on the GPU");
        if (n > 1) gl::voxelizeToOctree(context, mesh, grid, ro); // warm-up
        for (int i = 0; i < n; ++i) runs.push_back(gl::voxelizeToOctree(context, mesh, grid, ro));
    }
    out.result = medianOf(std::move(runs));
    return out;
}

std::string jsonEscape(const std::string& text)
{
    std::string out;
    for (const unsigned char c : text) {
        if (c == '"' || c == '\\') out += '\\', out += char(c);
        else if (c < 0x20) out += fmt::format("\\u{:04x}", c);
        else out += char(c);
    }
    return out;
}

void checkDistinctOutputs(const std::vector<std::string>& paths)
{
    for (size_t i = 0; i < paths.size(); ++i)
        for (size_t j = i + 1; j < paths.size(); ++j)
            if (!paths[i].empty() && std::filesystem::weakly_canonical(paths[i]) == std::filesystem::weakly_canonical(paths[j]))
                throw Error(fmt::format("{}: given for two outputs; each output needs its own file", paths[i]));
}

std::string thousands(uint64_t n)
{
    std::string s = std::to_string(n);
    for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
    return s;
}

} // namespace svo::app
