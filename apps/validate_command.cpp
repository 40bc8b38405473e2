// svo validate [MESH]: the GPU voxelization against CGAL's exact reference;
// with --sdf, the GPU level set against CGAL's exact distances and sides and
// against OpenVDB's meshToLevelSet.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
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
#include "svo/validate/level_set_report.h"
#include "svo/validate/report.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/vdb_file.h"
#include "svo/result_metadata.h"
#include "svo/voxelizer.h"

namespace svo::app {
namespace {

struct ValidateArgs {
    std::string mesh, json, errors;
    GridRequest grid; ///< -r/--resolution or --voxel-size
    BackendArgs backend;
    validate::ReportOptions report; ///< --no-holes, --strict, --worst (its mode is the voxelization's)
    bool sdf = false;
    FieldArgs levelSet; ///< bands and sign, with --sdf
    OutputHabits habits; ///< --no-clobber
    OutputArgs out;      ///< --topology of the --errors grids: bool by default, as every output
};

/// Refuses options that have no meaning with (or without) --sdf, before any work.
void checkSdfArgs(const ValidateArgs& a, const CLI::App& cmd)
{
    if (cmd.count("--topology") && !cmd.count("--errors"))
        throw InvalidInput("--topology applies to --errors (the grid type of the missed and extra voxels)");
    if (!a.sdf) {
        if (bandsGiven(cmd)) throw InvalidInput("--band, --exterior-band and --interior-band apply to --sdf");
        if (cmd.count("--sign")) throw InvalidInput("--sign applies to --sdf");
        if (cmd.count("--winding-accuracy")) throw InvalidInput("--winding-accuracy applies to --sdf");
        return;
    }
    if (cmd.count("--band") && (cmd.count("--exterior-band") || cmd.count("--interior-band")))
        throw InvalidInput("--band sets both bands; give it or --exterior-band/--interior-band, not both");
    if (cmd.count("--winding-accuracy") && a.levelSet.options.sign.method == SignMethod::Parity)
        throw InvalidInput("--winding-accuracy applies to winding-number signs, not to --sign parity");
    checkFieldMode(a.backend.voxelizeOptions()); // the library's rule, as svo voxelize --sdf checks it
    if (cmd.count("--errors")) throw InvalidInput("--errors writes missed and extra surface voxels; it does not apply to --sdf");
    if (cmd.count("--no-holes") || cmd.count("--strict"))
        throw InvalidInput("--no-holes and --strict apply to surface voxels, not to --sdf");
    if (cmd.count("--conservative") || a.backend.settings.backend == Backend::Raster)
        throw InvalidInput("--sdf runs compute passes only: --backend raster and --conservative do not apply");
}


/// The library's report (JSON text) with what the run was, written atomically.
void writeJson(const std::string& path, const std::string& libraryJson, const std::string& scene,
               const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeStats& stats, double gpuMs)
{
    nlohmann::json j = nlohmann::json::parse(libraryJson);
    j["scene"] = scene;
    j["triangles"] = mesh.triangles.size();
    j["dims"] = grid.dims;
    j["voxel_size"] = grid.voxelSize;
    j["backend"] = backendLine(stats);
    j["gpu_ms"] = gpuMs;
    writeFileAtomically(path, j.dump(2) + "\n");
}

std::string idx(const std::array<int64_t, 3>& p) { return fmt::format("[{}, {}, {}]", p[0], p[1], p[2]); }

std::string voxelsText(double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : std::string("none"); }

void printCases(const char* what, const std::vector<validate::LevelSetCase>& cases)
{
    for (const auto& c : cases)
        fmt::print("    {:<8} {} : svo {}, exact {:.6g} voxels ({}){}, triangle {}\n", what, idx(c.index),
                   std::isnan(c.value) ? std::string("inactive") : fmt::format("{:.6g}", c.value), c.exact,
                   c.side == 1 ? "inside" : c.side == 0 ? "outside" : "side unknown",
                   std::isnan(c.value) ? std::string()
                                       : fmt::format(", error {:.3g}", std::abs(std::abs(c.value) - std::abs(c.exact))),
                   c.triangle);
}

/// svo validate --sdf: the level set against CGAL, and beside OpenVDB's.
void runValidateSdf(const ValidateArgs& a, const LevelSetOptions& ls, const TriangleMesh& mesh, const GridSpec& grid, const std::string& scene,
                    OutputBatch& outputs)
{
    LibraryCall call(a.backend, "computing the distance field");
    const VoxelizeStats& stats = call.stats;
    const auto sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(call.voxelizer.levelSet(mesh, grid, ls, call.options).front());
    printWarnings(stats.warnings);
    const double gpuMs = stats.gpuMs();
    const std::vector<validate::LevelSetVoxel> voxels = validate::activeLevelSetVoxels(*sdf);

    validate::LevelSetReportOptions ro;
    ro.check.exteriorBand = ls.exteriorBand;
    ro.check.interiorBand = ls.interiorBand;
    ro.check.worst = a.report.worst; // --worst, one flag for both reports
    ro.sign = stats.sign;
    StepProgress steps;
    ro.onStep = steps.onStep();
    const validate::LevelSetReport report = validate::validateLevelSet(mesh, grid, voxels, ro);
    steps.finish();
    const validate::LevelSetCheck& c = report.check;
    const validate::OpenVdbComparison& o = report.openvdb;

    fmt::print("svo validate --sdf\n");
    fmt::print("  {:<12} {} ({} triangles)\n", "scene", scene, thousands(mesh.triangles.size()));
    fmt::print("  {:<12} {} x {} x {} local voxels, voxel size {:.6g}\n", "grid", grid.dims[0], grid.dims[1],
               grid.dims[2], grid.voxelSize);
    fmt::print("  {:<12} {}\n", "backend", backendLine(stats));
    fmt::print("  {:<12} exterior band {} voxels, interior band {} voxels; {} active voxels\n", "level set",
               ls.exteriorBand, ls.interiorBand, thousands(c.voxels));
    fmt::print("  {:<12} {}\n", "sign", stats.sign);
    fmt::print("  {:<12} {:.3g} voxels: the distance error allowed, the sign margin and the band-edge slack\n",
               "tolerance", c.tolerance);
    fmt::print("  {:<12} max error {} voxels, RMS {}; {} above the tolerance (against CGAL's AABB-tree distance)\n",
               "distance", voxelsText(c.maxError), voxelsText(c.rmsError), thousands(c.overTolerance));
    if (c.signChecked)
        fmt::print("  {:<12} {} differ from CGAL's Side_of_triangle_mesh farther than {:.3g} voxels from the surface "
                   "({} within it, allowed)\n",
                   "signs", thousands(c.signDisagreements), c.tolerance, thousands(c.signNearSurface));
    else
        fmt::print("  {:<12} not checked against CGAL: {}\n", "signs", c.signReason);
    fmt::print("  {:<12} {} missing, {} extra ({} inactive voxels near the surface examined{})\n", "band",
               thousands(c.missing), thousands(c.extra), thousands(c.candidates),
               c.bandUnjudged ? fmt::format("; {} between the two bands not judged: side unknown",
                                            thousands(c.bandUnjudged))
                              : std::string());
    printCases("error", c.worstError);
    printCases("sign", c.worstSign);
    printCases("missing", c.worstMissing);
    printCases("extra", c.worstExtra);
    if (report.compared) {
        fmt::print("  {:<12} meshToLevelSet, {} active voxels: {} in both, {} only in svo's band, {} only in "
                   "OpenVDB's; largest | |svo| - |OpenVDB| | {:.3g} voxels\n",
                   "openvdb", thousands(o.openvdb), thousands(o.common), thousands(o.onlyOurs),
                   thousands(o.onlyOpenVdb), o.maxDifference);
        fmt::print("  {:<12} {} sign disagreements on common voxels{}\n", "", thousands(o.signDisagreements),
                   o.signDisagreements == 0 ? std::string()
                   : o.signJudged
                       ? fmt::format(" (all within {:.3g} voxels of the surface): CGAL sides with svo at {}, with "
                                     "OpenVDB at {}",
                                     o.signFarthest, thousands(o.signOursRight),
                                     thousands(o.signDisagreements - o.signOursRight))
                       : fmt::format(" (all within {:.3g} voxels of the surface)", o.signFarthest));
        fmt::print("  {:<12} on common voxels, largest error against CGAL: svo {} voxels, OpenVDB {:.3g}; svo "
                   "farther than OpenVDB at {} voxels\n",
                   "", voxelsText(o.maxErrorOurs), o.maxErrorOpenVdb, thousands(o.oursFarther));
        if (o.onlyOurs)
            fmt::print("  {:<12} only in svo's band: exact distances {:.4g} to {:.4g} voxels\n", "",
                       o.onlyOursExact[0], o.onlyOursExact[1]);
        if (o.onlyOpenVdb)
            fmt::print("  {:<12} only in OpenVDB's band: exact distances {:.4g} to {:.4g} voxels\n", "",
                       o.onlyOpenVdbExact[0], o.onlyOpenVdbExact[1]);
    }
    fmt::print("  {:<12} validation {:.2f} s, level set {:.3f} GPU ms\n", "time", report.seconds, gpuMs);

    if (!a.json.empty())
        writeJson(a.json, validate::levelSetReportJson(report), scene, mesh, grid, stats, gpuMs);
    outputs.commit(); // the reports are written whether it passed or not
    if (!report.passed) throw Failure("validation failed: " + report.reason);
    fmt::print("  {:<12} passed: distances within {:.3g} voxels, {}, no band voxel missing or extra\n", "verdict",
               c.tolerance, c.signChecked ? "CGAL's signs" : "signs not checked (open mesh)");
}

void runValidate(const ValidateArgs& a, const CLI::App& cmd)
{
    checkSdfArgs(a, cmd);
    const GridRequest request = gridRequest(a.grid);
    checkOutputs({a.mesh}, {a.json, a.errors}); // before any work
    checkClobber(a.habits, {a.json, a.errors});
    OutputBatch outputs({a.json, a.errors});     // both in place together, or neither
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
    if (a.sdf) return runValidateSdf(a, a.levelSet.levelSetOptions(cmd), mesh, grid, scene, outputs);

    // The voxelization under test, and the voxel list it was built from (the
    // same run, read back apart), to check every level of the octree against.
    LibraryCall call(a.backend, "voxelizing");
    const VoxelizeStats& stats = call.stats;
    std::vector<uint64_t> list;
    const Octree octree = call.voxelizer.voxelize(mesh, grid, call.options, &list);
    printWarnings(stats.warnings);
    const double gpuMs = stats.gpuMs();

    // The checks: the octree against the list, the exact reference, the classification, the holes.
    validate::ReportOptions ro = a.report;
    ro.mode = call.options.mode;
    StepProgress steps;
    ro.onStep = steps.onStep();
    const validate::Report report = validate::validateVoxelization(mesh, octree, list, ro);
    steps.finish();
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
        fmt::print("  {:<12} not checked: {}\n", "holes", a.report.holes ? holes.reason : "skipped (--no-holes)");
    if (holes.leak) {
        fmt::print("    leak path ({} voxels, outside -> inside):", holes.leakPath.size());
        const size_t n = holes.leakPath.size();
        for (size_t i = n > 8 ? n - 8 : 0; i < n; ++i) fmt::print(" {}", idx(holes.leakPath[i]));
        fmt::print("\n");
    }
    fmt::print("  {:<12} {}\n", "octree", consistency.empty() ? "consistent with the voxel list at every level" : consistency);
    fmt::print("  {:<12} validation {:.2f} s, voxelization {:.3f} GPU ms\n", "time", validateSeconds, gpuMs);

    if (!a.errors.empty()) {
        std::vector<std::pair<std::string, Octree>> named = {{"missed", buildOctree(grid, c.missedExact)},
                                                             {"extra", buildOctree(grid, c.extra)}};
        if (holes.leak) {
            std::vector<uint64_t> path;
            for (const auto& p : holes.leakPath)
                if (p[0] >= grid.anchor[0] && p[1] >= grid.anchor[1] && p[2] >= grid.anchor[2] &&
                    p[0] < grid.anchor[0] + grid.dims[0] && p[1] < grid.anchor[1] + grid.dims[1] &&
                    p[2] < grid.anchor[2] + grid.dims[2])
                    path.push_back(packVoxelKey(uint32_t(p[0] - grid.anchor[0]), uint32_t(p[1] - grid.anchor[1]),
                                                uint32_t(p[2] - grid.anchor[2])));
            named.emplace_back("leak_path", buildOctree(grid, path));
        }
        // Each set as the topology grid of every other output (BoolGrid unless --topology mask),
        // tagged as `svo voxelize` tags its grids.
        openvdb::GridPtrVec grids;
        for (const auto& [name, voxels] : named) {
            GridOptions g = a.out.grids;
            g.name = name;
            g.attributes = false;
            grids.push_back(vdb::octreeToGrids(voxels, g).front());
        }
        vdb::writeVdbGrids(a.errors, grids, resultMetadata(mesh, grid, request, true));
        fmt::print("  {:<12} {} ({} grids missed, extra{})\n", "errors", a.errors,
                   a.out.grids.topology == GridOptions::Topology::Bool ? "bool" : "mask", holes.leak ? ", leak_path" : "");
    }

    if (!a.json.empty())
        writeJson(a.json, validate::reportJson(report), scene, mesh, grid, stats, gpuMs);
    outputs.commit(); // the reports are written whether it passed or not
    if (!report.passed) throw Failure("validation failed: " + report.reason);
    fmt::print("  {:<12} passed: nothing missed{}\n", "verdict", holes.applies ? ", no leak" : "");
}

} // namespace

void addValidateCommand(CLI::App& app)
{
    auto args = std::make_shared<ValidateArgs>();
    CLI::App* cmd = app.add_subcommand(
        "validate", "Check a voxelization against exact CGAL tests (triangle-box, or triangle-segment for "
                    "--mode thin): nothing missed, no holes; with --sdf, a level set against CGAL's distances and "
                    "sides and OpenVDB's meshToLevelSet (exit 0 pass, 3 fail, 1 error)");
    cmd->add_option("mesh", args->mesh,
                    fmt::format("Mesh file ({}); none = built-in Cornell box", supportedMeshExtensions()))
        ->check(nonEmptyMeshPath, "MESH");
    addGridOptions(*cmd, args->grid);
    addBackendOptions(*cmd, args->backend);
    addOptions(*cmd, args->backend.settings, {"mode"});
    addOutputPath(*cmd, "--json", args->json, "Write the report as JSON");
    addOutputPath(*cmd, "--errors", args->errors,
                  "Write the missed and extra voxels (and any leak path) as grids in a .vdb, of the --topology type",
                  {".vdb"});
    addOptions(*cmd, args->out.grids, {"topology"}, "for --errors");
    addOptions(*cmd, args->report);
    addOptions(*cmd, args->habits, {"no_clobber"}); // the report is the result: no -q or -v
    cmd->add_flag("--sdf", args->sdf,
                  "Check the level set (voxelize --sdf) instead: distances, signs and band against CGAL, beside "
                  "OpenVDB's meshToLevelSet");
    addBandOptions(*cmd, args->levelSet, "for --sdf");
    addOptions(*cmd, args->levelSet.options, {"sign", "winding_accuracy"}, "for --sdf");
    cmd->callback([args, cmd] { runValidate(*args, *cmd); });
}

} // namespace svo::app
