// svo voxelize [MESH] -o out.vdb|out.nvdb|out.svo [--resolution N | --voxel-size h]
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "progress.h"
#include "svo/core/atomic_file.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/voxelizer.h"

namespace svo::app {
namespace {

struct VoxelizeArgs {
    std::string mesh;
    std::string output;
    std::string json;
    int64_t resolution = 0;
    double voxelSize = 0;
    int repeat = 1;
    BackendArgs backend;
    OutputArgs out;
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

    // No output may be the input or another output: refused before any work.
    checkOutputs({a.mesh}, {a.output, a.json});
    // Then load: a bad mesh must fail before any output is considered.
    TriangleMesh mesh;
    {
        Progress p("loading " + (a.mesh.empty() ? std::string("built-in scene") : a.mesh));
        mesh = a.mesh.empty() ? cornellBox() : loadMesh(a.mesh);
    }
    printWarnings(mesh.warnings);
    const std::string scene = a.mesh.empty() ? mesh.source : std::filesystem::path(a.mesh).stem().string();
    // --repeat without -o is a timing run and writes nothing; otherwise the
    // default name is used, but never over a file the user did not name.
    const bool timingOnly = a.repeat > 1 && a.output.empty();
    const std::string output = timingOnly ? std::string() : a.output.empty() ? scene + ".vdb" : a.output;
    if (a.output.empty() && !timingOnly) {
        checkOutputs({a.mesh}, {output, a.json}); // the default name is known only now
        std::error_code ec;
        if (std::filesystem::exists(output, ec))
            throw Error(fmt::format("{}: exists, and svo does not replace a file it was not told to write; give "
                                    "-o {} to replace it",
                                    output, output));
    }
    if (!timingOnly) checkOutputPath(output);
    if (!a.json.empty()) checkWritable(a.json);
    const GridSpec grid = makeGrid(mesh, request);
    const GridOptions grids = a.out.gridOptions();
    if (!timingOnly && outputFormat(output) == OutputFormat::Svo && (cmd.count("--fog") || cmd.count("--topology")))
        throw Error(fmt::format("{}: --fog and --topology apply to .vdb and .nvdb output, not .svo", output));

    // Voxelize: with --repeat, one warm-up on the GPU, then per-stage medians.
    LibraryCall call(a.backend, "voxelizing");
    std::vector<VoxelizeStats> runs(size_t(a.repeat));
    Octree octree;
    if (a.repeat > 1 && call.options.backend != Backend::Cpu) call.voxelizer.voxelize(mesh, grid, call.options);
    for (auto& run : runs) {
        octree = call.voxelizer.voxelize(mesh, grid, call.options);
        run = call.stats;
    }
    VoxelizeStats stats = medianStats(runs);
    printWarnings(stats.warnings);

    const std::map<std::string, std::string> meta = {
        {"svo:source", mesh.source},
        {"svo:triangles", std::to_string(mesh.triangles.size())},
        {"svo:grid", request.voxelSize > 0 ? fmt::format("voxel size {}", grid.voxelSize)
                                           : fmt::format("resolution {}", request.resolution)},
        {"svo:voxel_size", fmt::format("{}", grid.voxelSize)},
        {"svo:backend", stats.backend},
        {"svo:mode", stats.mode},
        {"svo:renderer", stats.renderer},
        {"svo:epsilon", fmt::format("{:.3g}", grid.epsilon())},
        {"svo:version", SVO_VERSION}};
    WriteReport written;
    if (!timingOnly) {
        Progress p("writing " + output);
        written = writeOctree(output, octree, grids, meta);
    }
    for (const auto& s : written.stages) stats.stages.push_back(s);
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

    const auto st = octreeStats(octree);
    fmt::print("svo voxelize\n");
    fmt::print("  {:<11} {}\n", "scene", scene);
    fmt::print("  {:<11} {}\n", "triangles", thousands(mesh.triangles.size()));
    fmt::print("  {:<11} {} x {} x {} local voxels, voxel size {:.6g}, {}\n", "grid", grid.dims[0], grid.dims[1],
               grid.dims[2], grid.voxelSize,
               request.voxelSize > 0 ? std::string("from --voxel-size") : fmt::format("resolution {}", request.resolution));
    fmt::print("  {:<11} {}\n", "voxels", thousands(st.voxels));
    fmt::print("  {:<11} {} levels, {} nodes, {} bricks, {:.2f} bytes/voxel, brick fill {:.2f}\n", "octree",
               octree.brickLevel + 1, thousands(octree.nodes.size()), thousands(st.bricks), st.bytesPerVoxel(),
               st.fillRatio());
    const uint32_t ch = octree.channels();
    if (ch)
        fmt::print("  {:<11} {}{}{}\n", "attributes", ch & kNormals ? "normal " : "", ch & kTriangles ? "triangle_id " : "",
                   ch & kColors ? "color" : "");
    fmt::print("  {:<11} {}\n", "mode", stats.mode);
    fmt::print("  {:<11} {}\n", "backend", backendLine(stats));
    fmt::print("  {:<11} {:.3g} voxels ({} grown by half of it on the GPU)\n", "guard band", grid.epsilon(),
               stats.mode == "thin" ? "centre segments" : "cubes");
    fmt::print("  {:<11} {} entries, {} overflow retries, {:.1f} MB of GPU buffers\n", "voxel list",
               thousands(stats.listEntries), stats.overflowRetries, double(stats.gpuBytes) / 1e6);
    fmt::print("  {:<11} {}\n", "output",
               timingOnly ? std::string("none (--repeat without -o times the runs only)")
                          : describeOutput(output, written, grids));
    fmt::print("\n  {:<20} {:>10} {:>10}{}\n", "stage", "GPU ms", "wall ms",
               a.repeat > 1 ? fmt::format("   (voxelize stages: median of {} runs after a warm-up)", a.repeat) : "");
    printStages(stats.stages);
    fmt::print("  {:<20} {:>10} {:>10.2f}\n", "total", "", wall);

    if (!a.json.empty()) {
        nlohmann::json stages = nlohmann::json::array();
        for (const auto& s : stats.stages)
            stages.push_back({{"name", s.name},
                              {"gpu_ms", s.gpuMs < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.gpuMs)},
                              {"wall_ms", s.wallMs}});
        const nlohmann::json report = {
            {"scene", scene},
            {"triangles", mesh.triangles.size()},
            {"dims", grid.dims},
            {"voxel_size", grid.voxelSize},
            {"resolution", request.resolution},
            {"backend", stats.backend},
            {"mode", stats.mode},
            {"conservative", a.backend.conservative},
            {"dilation", stats.dilation},
            {"renderer", stats.renderer},
            {"epsilon", grid.epsilon()},
            {"voxels", st.voxels},
            {"bricks", st.bricks},
            {"nodes", octree.nodes.size()},
            {"nodes_per_level", st.nodesPerLevel},
            {"octree_bytes", st.bytes},
            {"list_entries", stats.listEntries},
            {"overflow_retries", stats.overflowRetries},
            {"gpu_bytes", stats.gpuBytes},
            {"repeat", a.repeat},
            {"peak_rss_mb", peakRssMb()},
            {"stages", stages},
            {"total_wall_ms", wall}};
        writeFileAtomically(a.json, report.dump(2) + "\n");
    }
}

} // namespace

void addVoxelizeCommand(CLI::App& app)
{
    auto args = std::make_shared<VoxelizeArgs>();
    CLI::App* cmd = app.add_subcommand(
        "voxelize", "Voxelize a mesh (default: the built-in Cornell box) into a .vdb or .nvdb grid or a .svo octree");
    cmd->add_option("mesh", args->mesh,
                    fmt::format("Mesh file ({}); none = built-in Cornell box", supportedMeshExtensions()));
    addOutputPath(*cmd, "-o,--output", args->output, "Output .vdb, .nvdb (NanoVDB) or .svo (default: <scene>.vdb)");
    addOutputPath(*cmd, "--json", args->json, "Also write the summary (counts, bytes, stage times) as JSON");
    addGridOptions(*cmd, args->resolution, args->voxelSize);
    addBackendOptions(*cmd, args->backend);
    addAttributeOption(*cmd, args->backend);
    addModeOption(*cmd, args->backend);
    addOutputOptions(*cmd, args->out);
    cmd->add_option("--repeat", args->repeat,
                    "Voxelize N times (after one warm-up on the GPU) and report per-stage medians; without -o, "
                    "nothing is written")
        ->check(CLI::Range(1, 1000));
    cmd->callback([args, cmd] { runVoxelize(*args, *cmd); });
}

} // namespace svo::app
