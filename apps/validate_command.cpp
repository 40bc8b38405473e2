// svo validate [MESH]: the GPU voxelization against CGAL's exact reference.
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "progress.h"
#include "svo/core/atomic_file.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/core/voxel_key.h"
#include "svo/validate/classify.h"
#include "svo/validate/hole_check.h"
#include "svo/validate/report.h"
#include "svo/vdb_io/vdb_file.h"
#include "svo/voxelizer.h"

namespace svo::app {
namespace {

struct ValidateArgs {
    std::string mesh, json, errors;
    int64_t resolution = 0;
    double voxelSize = 0;
    BackendArgs backend;
    bool noHoles = false;
    bool strict = false;
    size_t worst = 5;
};


std::string idx(const std::array<int64_t, 3>& p) { return fmt::format("[{}, {}, {}]", p[0], p[1], p[2]); }

void runValidate(const ValidateArgs& a, const CLI::App& cmd)
{
    const GridRequest request = gridRequest(cmd, a.resolution, a.voxelSize);
    checkOutputs({a.mesh}, {a.json, a.errors}); // before any work
    TriangleMesh mesh;
    {
        Progress p("loading " + (a.mesh.empty() ? std::string("built-in scene") : a.mesh));
        mesh = a.mesh.empty() ? cornellBox() : loadMesh(a.mesh);
    }
    printWarnings(mesh.warnings);
    if (!a.json.empty()) checkWritable(a.json);
    if (!a.errors.empty()) checkWritable(a.errors);
    const GridSpec grid = makeGrid(mesh, request);
    const std::string scene = a.mesh.empty() ? mesh.source : std::filesystem::path(a.mesh).stem().string();

    // The voxelization under test, and the voxel list it was built from (the
    // same run, read back apart), to check every level of the octree against.
    LibraryCall call(a.backend, "voxelizing");
    const VoxelizeStats& stats = call.stats;
    std::vector<uint64_t> list;
    const Octree octree = call.voxelizer.voxelize(mesh, grid, call.options, &list);
    printWarnings(stats.warnings);
    const double gpuMs = stats.gpuMs();

    // The checks: the octree against the list, the exact reference, the classification, the holes.
    validate::ReportOptions ro;
    ro.mode = call.options.mode;
    ro.holes = !a.noHoles;
    ro.strict = a.strict;
    ro.worst = a.worst;
    std::unique_ptr<Progress> step;
    ro.onStep = [&step](const std::string& s) {
        step.reset(); // the previous step's line ends first
        step = std::make_unique<Progress>(s);
    };
    const validate::Report report = validate::validateVoxelization(mesh, octree, list, ro);
    step.reset();
    const validate::Classification& c = report.classification;
    const validate::HoleCheck& holes = report.holes;
    const std::string& consistency = report.consistency;
    const double eps = report.epsilon;
    const double validateSeconds = report.seconds;

    auto rate = [](uint64_t n, uint64_t of) { return of ? double(n) / double(of) : 0.0; };
    fmt::print("svo validate\n");
    fmt::print("  {:<12} {} ({} triangles, {} degenerate)\n", "scene", scene, thousands(mesh.triangles.size()),
               thousands(report.degenerate));
    fmt::print("  {:<12} {} x {} x {} local voxels, voxel size {:.6g}\n", "grid", grid.dims[0], grid.dims[1],
               grid.dims[2], grid.voxelSize);
    fmt::print("  {:<12} {}\n", "backend", backendLine(stats));
    fmt::print("  {:<12} {}\n", "mode", voxelModeName(report.mode));
    if (report.mode == VoxelMode::Thin)
        fmt::print("  {:<12} {:.3g} voxels: R = centre segments shortened by it, A = segments grown by it, E = the "
                   "segments themselves (exact CGAL tests)\n",
                   "guard band", eps);
    else
        fmt::print("  {:<12} {:.3g} voxels: R = cubes shrunk by it, A = cubes grown by it, E = the cubes themselves "
                   "(exact CGAL tests)\n",
                   "guard band", eps);
    fmt::print("  {:<12} {} voxels; R {} , E {} , A {}\n", "sets", thousands(c.voxels), thousands(c.required),
               thousands(c.exact), thousands(c.allowed));
    fmt::print("  {:<12} {:>10}  ({:.3g} of R)\n", "missed (R)", thousands(c.missed.size()),
               rate(c.missed.size(), c.required));
    fmt::print("  {:<12} {:>10}  ({:.3g} of E, the exact {} set)\n", "missed (E)", thousands(c.missedExact.size()),
               rate(c.missedExact.size(), c.exact), voxelModeName(report.mode));
    fmt::print("  {:<12} {:>10}  ({:.3g} of the voxels; allowed)\n", "boundary", thousands(c.boundary.size()),
               rate(c.boundary.size(), c.voxels));
    fmt::print("  {:<12} {:>10}  ({:.3g} of the voxels)\n", "extra", thousands(c.extra.size()), rate(c.extra.size(), c.voxels));
    for (const auto& w : c.worstMissed)
        fmt::print("    missed {} : triangle {}, centre {:.4g} voxels from it\n", idx(w.index), w.triangle, w.distance);
    for (const auto& w : c.worstExtra)
        fmt::print("    extra  {} : nearest triangle {}, centre {:.4g} voxels from it\n", idx(w.index), w.triangle,
                   w.distance);
    if (holes.applies)
        fmt::print("  {:<12} {} ({}-connected fill reached {} empty voxels; {} frontier voxels tested for inside)\n",
                   "holes", holes.leak ? "LEAK" : "none", holes.connectivity, thousands(holes.filled),
                   thousands(holes.frontier));
    else
        fmt::print("  {:<12} not checked: {}\n", "holes", a.noHoles ? "skipped (--no-holes)" : holes.reason);
    if (holes.leak) {
        fmt::print("    leak path ({} voxels, outside -> inside):", holes.leakPath.size());
        const size_t n = holes.leakPath.size();
        for (size_t i = n > 8 ? n - 8 : 0; i < n; ++i) fmt::print(" {}", idx(holes.leakPath[i]));
        fmt::print("\n");
    }
    fmt::print("  {:<12} {}\n", "octree", consistency.empty() ? "consistent with the voxel list at every level" : consistency);
    fmt::print("  {:<12} validation {:.2f} s, voxelization {:.3f} GPU ms\n", "time", validateSeconds, gpuMs);

    if (!a.errors.empty()) {
        std::vector<std::pair<std::string, Octree>> grids = {{"missed", buildOctree(grid, c.missedExact)},
                                                             {"extra", buildOctree(grid, c.extra)}};
        if (holes.leak) {
            std::vector<uint64_t> path;
            for (const auto& p : holes.leakPath)
                if (p[0] >= grid.anchor[0] && p[1] >= grid.anchor[1] && p[2] >= grid.anchor[2] &&
                    p[0] < grid.anchor[0] + grid.dims[0] && p[1] < grid.anchor[1] + grid.dims[1] &&
                    p[2] < grid.anchor[2] + grid.dims[2])
                    path.push_back(packVoxelKey(uint32_t(p[0] - grid.anchor[0]), uint32_t(p[1] - grid.anchor[1]),
                                                uint32_t(p[2] - grid.anchor[2])));
            grids.emplace_back("leak_path", buildOctree(grid, path));
        }
        vdb::writeVdbMasks(a.errors, grids, {{"svo:source", mesh.source}});
        fmt::print("  {:<12} {} (grids missed, extra{})\n", "errors", a.errors, holes.leak ? ", leak_path" : "");
    }

    if (!a.json.empty()) {
        nlohmann::json j = nlohmann::json::parse(validate::reportJson(report)); // the library's numbers
        j["scene"] = scene;
        j["triangles"] = mesh.triangles.size();
        j["dims"] = grid.dims;
        j["voxel_size"] = grid.voxelSize;
        j["backend"] = backendLine(stats);
        j["gpu_ms"] = gpuMs;
        writeFileAtomically(a.json, j.dump(2) + "\n");
    }
    if (!report.passed) throw Failure("validation failed: " + report.reason);
    fmt::print("  {:<12} passed: nothing missed{}\n", "verdict", holes.applies ? ", no leak" : "");
}

} // namespace

void addValidateCommand(CLI::App& app)
{
    auto args = std::make_shared<ValidateArgs>();
    CLI::App* cmd = app.add_subcommand(
        "validate", "Check a voxelization against exact CGAL tests (triangle-box, or triangle-segment for "
                    "--mode thin): nothing missed, no holes (exit 0 pass, 3 fail, 1 error)");
    cmd->add_option("mesh", args->mesh,
                    fmt::format("Mesh file ({}); none = built-in Cornell box", supportedMeshExtensions()));
    addGridOptions(*cmd, args->resolution, args->voxelSize);
    addBackendOptions(*cmd, args->backend);
    addModeOption(*cmd, args->backend);
    addOutputPath(*cmd, "--json", args->json, "Write the report as JSON");
    addOutputPath(*cmd, "--errors", args->errors, "Write the missed and extra voxels (and any leak path) as MaskGrids in a .vdb",
                  {".vdb"});
    cmd->add_flag("--no-holes", args->noHoles, "Skip the flood-fill hole check");
    cmd->add_flag("--strict", args->strict, "Fail on extra voxels too");
    cmd->add_option("--worst", args->worst, "Worst cases to list of each kind")->capture_default_str();
    cmd->callback([args, cmd] { runValidate(*args, *cmd); });
}

} // namespace svo::app
