// svo voxelize [MESH] -o out.vdb|out.svo [--resolution N | --voxel-size h]
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <sys/resource.h>

#include "commands.h"
#include "mesh_voxelizer.h"
#include "octree_output.h"
#include "progress.h"
#include "svo/core/atomic_file.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"

namespace svo::app {
namespace {

struct VoxelizeArgs {
    std::string mesh;
    std::string output;
    std::string json;
    int64_t resolution = 0;
    double voxelSize = 0;
    BackendSettings backend;
    OutputSettings out;
};

double peakRssMb()
{
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_maxrss) / 1024.0; // kilobytes on Linux
}

void runVoxelize(const VoxelizeArgs& a, const CLI::App& cmd)
{
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const GridRequest request = gridRequest(cmd, a.resolution, a.voxelSize);

    // Load first: a bad mesh must fail before any output is considered.
    TriangleMesh mesh;
    {
        Progress p("loading " + (a.mesh.empty() ? std::string("built-in scene") : a.mesh));
        mesh = a.mesh.empty() ? cornellBox() : loadMesh(a.mesh);
    }
    for (const auto& w : mesh.warnings) fmt::print(stderr, "svo: warning: {}\n", w);
    const std::string scene = a.mesh.empty() ? mesh.source : std::filesystem::path(a.mesh).stem().string();
    const std::string output = a.output.empty() ? scene + ".vdb" : a.output;
    checkOutputPath(output);
    if (!a.json.empty()) checkWritable(a.json);
    checkDistinctOutputs({output, a.json});
    const GridSpec grid = makeGrid(mesh, request);

    MeshVoxelization mv = voxelizeMesh(mesh, grid, a.backend);
    auto& vox = mv.result;
    std::map<std::string, std::string> meta = {
        {"svo:source", mesh.source},
        {"svo:triangles", std::to_string(mesh.triangles.size())},
        {"svo:grid", request.voxelSize > 0 ? fmt::format("voxel size {}", grid.voxelSize)
                                           : fmt::format("resolution {}", request.resolution)},
        {"svo:voxel_size", fmt::format("{}", grid.voxelSize)},
        {"svo:backend", a.backend.backend},
        {"svo:renderer", mv.renderer},
        {"svo:epsilon", fmt::format("{:.3g}", grid.epsilon())},
        {"svo:version", SVO_VERSION}};
    const OutputReport written = writeOctreeOutput(output, vox.octree, a.out, meta);
    for (const auto& s : written.stages) vox.stages.push_back(s);
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

    const auto stats = octreeStats(vox.octree);
    fmt::print("svo voxelize\n");
    fmt::print("  {:<11} {}\n", "scene", scene);
    fmt::print("  {:<11} {}\n", "triangles", thousands(mesh.triangles.size()));
    fmt::print("  {:<11} {} x {} x {} local voxels, voxel size {:.6g}, {}\n", "grid", grid.dims[0], grid.dims[1],
               grid.dims[2], grid.voxelSize,
               request.voxelSize > 0 ? std::string("from --voxel-size") : fmt::format("resolution {}", request.resolution));
    fmt::print("  {:<11} {}\n", "voxels", thousands(stats.voxels));
    fmt::print("  {:<11} {} levels, {} nodes, {} bricks, {:.2f} bytes/voxel, brick fill {:.2f}\n", "octree",
               vox.octree.brickLevel + 1, thousands(vox.octree.nodes.size()), thousands(stats.bricks),
               stats.bytesPerVoxel(), stats.fillRatio());
    const uint32_t ch = vox.octree.channels();
    if (ch)
        fmt::print("  {:<11} {}{}{}\n", "attributes", ch & kNormals ? "normal " : "", ch & kTriangles ? "triangle_id " : "",
                   ch & kColors ? "color" : "");
    fmt::print("  {:<11} {}\n", "backend", mv.backendLine);
    fmt::print("  {:<11} {:.3g} voxels (cubes grown by half of it on the GPU)\n", "guard band", grid.epsilon());
    fmt::print("  {:<11} {} entries, {} overflow retries, {:.1f} MB of GPU buffers\n", "voxel list",
               thousands(vox.listEntries), vox.overflowRetries, double(vox.gpuBytes) / 1e6);
    fmt::print("  {:<11} {}\n", "output", written.description);
    fmt::print("\n  {:<20} {:>10} {:>10}{}\n", "stage", "GPU ms", "wall ms",
               a.backend.repeat > 1
                   ? fmt::format("   (voxelize stages: median of {} runs after a warm-up)", a.backend.repeat)
                   : "");
    for (const auto& s : vox.stages)
        fmt::print("  {:<20} {:>10} {:>10.2f}\n", s.name, s.gpuMs < 0 ? std::string("-") : fmt::format("{:.3f}", s.gpuMs),
                   s.wallMs);
    fmt::print("  {:<20} {:>10} {:>10.2f}\n", "total", "", wall);

    if (!a.json.empty()) {
        std::string stages;
        for (const auto& s : vox.stages)
            stages += fmt::format("{}{{\"name\": \"{}\", \"gpu_ms\": {}, \"wall_ms\": {:.4f}}}", stages.empty() ? "" : ", ",
                                  s.name, s.gpuMs < 0 ? std::string("null") : fmt::format("{:.4f}", s.gpuMs), s.wallMs);
        std::string levels;
        for (auto n : stats.nodesPerLevel) levels += fmt::format("{}{}", levels.empty() ? "" : ", ", n);
        const std::string text = fmt::format(
            "{{\n  \"scene\": \"{}\", \"triangles\": {}, \"dims\": [{}, {}, {}], \"voxel_size\": {},\n"
            "  \"resolution\": {}, \"backend\": \"{}\", \"conservative\": \"{}\", \"renderer\": \"{}\", \"epsilon\": {},\n"
            "  \"voxels\": {}, \"bricks\": {}, \"nodes\": {}, \"nodes_per_level\": [{}], \"octree_bytes\": {},\n"
            "  \"list_entries\": {}, \"overflow_retries\": {}, \"gpu_bytes\": {}, \"repeat\": {}, \"peak_rss_mb\": {:.1f},\n"
            "  \"stages\": [{}],\n  \"total_wall_ms\": {:.4f}\n}}\n",
            jsonEscape(scene), mesh.triangles.size(), grid.dims[0], grid.dims[1], grid.dims[2], grid.voxelSize,
            request.resolution, a.backend.backend, a.backend.conservative, jsonEscape(mv.renderer), grid.epsilon(), stats.voxels, stats.bricks, vox.octree.nodes.size(), levels,
            stats.bytes, vox.listEntries, vox.overflowRetries, vox.gpuBytes, a.backend.repeat, peakRssMb(), stages, wall);
        writeFileAtomically(a.json, text);
    }
}

} // namespace

void addVoxelizeCommand(CLI::App& app)
{
    auto args = std::make_shared<VoxelizeArgs>();
    CLI::App* cmd = app.add_subcommand(
        "voxelize", "Voxelize a mesh (default: the built-in Cornell box) into a .vdb grid or a .svo octree");
    cmd->add_option("mesh", args->mesh,
                    fmt::format("Mesh file ({}); none = built-in Cornell box", supportedMeshExtensions()));
    cmd->add_option("-o,--output", args->output, "Output .vdb or .svo (default: <scene>.vdb)");
    cmd->add_option("--json", args->json, "Also write the summary (counts, bytes, stage times) as JSON");
    addGridOptions(*cmd, args->resolution, args->voxelSize);
    addBackendOptions(*cmd, args->backend);
    addAttributeOption(*cmd, args->backend);
    addOutputOptions(*cmd, args->out);
    cmd->add_option("--repeat", args->backend.repeat,
                    "Voxelize N times (after one warm-up on the GPU) and report per-stage medians")
        ->check(CLI::Range(1, 1000));
    cmd->callback([args, cmd] { runVoxelize(*args, *cmd); });
}

} // namespace svo::app
