// svo voxelize [MESH] -o out.vdb|out.nvdb|out.svo [--resolution N | --voxel-size h]
//              [--sdf | --udf | --fill solid | --fill band] [--band W | --exterior-band A --interior-band B]
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <future>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sys/resource.h>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "progress.h"
#include "stale_sidecar.h"
#include "svo/core/atomic_file.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/vdb_io/nanovdb_file.h"
#include "svo/vdb_io/reader_grids.h"
#include "svo/vdb_io/vdb_file.h"
#include "svo/result_metadata.h"
#include "svo/voxelizer.h"

namespace svo::app {
namespace {

struct VoxelizeArgs {
    std::string mesh;
    std::string output;
    std::string json;
    GridRequest grid; ///< -r/--resolution or --voxel-size
    int repeat = 1;
    BackendArgs backend;
    OutputArgs out;
    OutputHabits habits; ///< -q, -v, --no-clobber
    // Level sets, unsigned distances and solids.
    bool sdf = false;
    std::string fill = "surface";
    FieldArgs levelSet; ///< bands, sign, --udf and --closest-triangle
    bool udf() const { return levelSet.options.unsignedDistance; }
    bool band() const { return fill == "band"; }
    bool field() const { return sdf || udf() || fill == "solid" || band(); }
    /// Whether a .vdb output gets a triangle sidecar (reader_grids.h).
    bool triangleGrids() const
    {
        return field() ? levelSet.options.closestTriangle : (backend.settings.attributes & kTriangles) != 0;
    }
};

double peakRssMb()
{
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_maxrss) / 1024.0; // kilobytes on Linux
}

/// The summary's first lines, the same for grids and octrees.
void printHeading(const std::string& scene, size_t triangles, const GridSpec& grid, const GridRequest& request)
{
    fmt::print("svo voxelize\n");
    fmt::print("  {:<11} {}\n", "scene", scene);
    fmt::print("  {:<11} {}\n", "triangles", thousands(triangles));
    fmt::print("  {:<11} {} x {} x {} local voxels, voxel size {:.6g}, {}\n", "grid", grid.dims[0], grid.dims[1],
               grid.dims[2], grid.voxelSize,
               request.voxelSize > 0 ? std::string("from --voxel-size") : fmt::format("resolution {}", request.resolution));
}

/// The stage table; `medianOf` says which stages --repeat gives as medians.
void printStageTable(const std::vector<StageTime>& stages, double wallMs, int repeat, const char* medianOf,
                     const StartupStats* startup)
{
    fmt::print("\n  {:<20} {:>10} {:>10}{}\n", "stage", "GPU ms", "wall ms",
               repeat > 1 ? fmt::format("   ({}median of {} runs after a warm-up)", medianOf, repeat) : "");
    if (startup) printStartup(*startup);
    printStages(stages);
    fmt::print("  {:<20} {:>10} {:>10.2f}\n", "total", "", wallMs);
}

/// The JSON summary's "stages": GPU milliseconds null where not measured.
nlohmann::json stagesJson(const std::vector<StageTime>& stages)
{
    nlohmann::json out = nlohmann::json::array();
    for (const auto& s : stages)
        out.push_back({{"name", s.name},
                       {"gpu_ms", s.gpuMs < 0 ? nlohmann::json(nullptr) : nlohmann::json(s.gpuMs)},
                       {"wall_ms", s.wallMs}});
    return out;
}

/// Refuses combinations that have no meaning before any work is done.
void checkFieldArgs(const VoxelizeArgs& a, const CLI::App& cmd)
{
    const int modes = int(a.sdf) + int(a.udf()) + int(a.fill == "solid") + int(a.band());
    if (modes > 1)
        throw InvalidInput("--sdf, --udf, --fill solid and --fill band each make a different grid; give one of them");
    const bool bands = bandsGiven(cmd);
    if (bands && !a.sdf && !a.udf() && !a.band())
        throw InvalidInput("--band, --exterior-band and --interior-band apply to --sdf, --udf and --fill band");
    if (a.band() && (cmd.count("--exterior-band") || cmd.count("--interior-band")))
        throw InvalidInput("--fill band takes --band, its half width; it has no inside or outside");
    if (cmd.count("--band") && (cmd.count("--exterior-band") || cmd.count("--interior-band")))
        throw InvalidInput("--band sets both bands; give it or --exterior-band/--interior-band, not both");
    if (a.udf() && cmd.count("--interior-band")) throw InvalidInput("--interior-band applies to --sdf; --udf has no inside");
    if (a.levelSet.options.closestTriangle && !a.sdf && !a.udf()) throw InvalidInput("--closest-triangle applies to --sdf and --udf");
    if (cmd.count("--sign") && !a.sdf && a.fill != "solid") throw InvalidInput("--sign applies to --sdf and --fill solid");
    if (cmd.count("--winding-accuracy") && !a.sdf && a.fill != "solid")
        throw InvalidInput("--winding-accuracy applies to --sdf and --fill solid");
    if (cmd.count("--winding-accuracy") && a.levelSet.options.sign.method == SignMethod::Parity)
        throw InvalidInput("--winding-accuracy applies to winding-number signs, not to --sign parity");
    if (cmd.count("--part-of-closed-mesh") && !a.sdf && a.fill != "solid")
        throw InvalidInput("--part-of-closed-mesh applies to --sdf and --fill solid");
    if (!a.field()) return;
    checkFieldMode(a.backend.voxelizeOptions()); // --mode thin: the library's rule, as svo validate --sdf checks it
    if (a.backend.settings.attributes)
        throw InvalidInput("--attributes applies to surface voxels, not to --sdf, --udf or --fill solid or band");
    if (cmd.count("--fog")) throw InvalidInput("--fog applies to surface voxels, not to --sdf, --udf or --fill solid or band");
    if (cmd.count("--topology") && a.fill == "surface")
        throw InvalidInput("--topology applies to surface voxels and --fill solid or band, not to --sdf or --udf");
    if (!a.output.empty() && outputFormat(a.output) == OutputFormat::Svo)
        throw InvalidInput(
            fmt::format("{}: --sdf, --udf and --fill solid or band write grids; name a .vdb or .nvdb file", a.output));
    // A level set's band comes from the triangles, not from rasterized voxels.
    if ((a.sdf || a.udf() || a.band()) && (cmd.count("--conservative") || a.backend.settings.backend == Backend::Raster))
        throw InvalidInput(
            "--sdf, --udf and --fill band run compute passes only: --backend raster and --conservative do not apply");
}

nlohmann::json startupJson(const StartupStats& s)
{
    return {{"egl_ms", s.eglMs},
            {"program_ms", s.programMs},
            {"programs_compiled", s.programsCompiled},
            {"programs_loaded", s.programsLoaded},
            {"programs_refused", s.programsRefused},
            {"program_cache", s.programCache}};
}

/// Frees @a mesh once its grids are made, so that writing them does not
/// also hold it (a large mesh's peak memory); returns its triangle count.
size_t release(TriangleMesh& mesh)
{
    const size_t triangles = mesh.triangles.size();
    mesh = TriangleMesh();
    return triangles;
}

/// What every --json report holds: the input and its grid, where the run
/// went, and what it cost. Each kind of run adds its own fields.
nlohmann::json runJson(const std::string& scene, size_t triangles, const GridSpec& grid,
                       const VoxelizeStats& stats, int repeat, double wallMs)
{
    return {{"scene", scene},
            {"triangles", triangles},
            {"dims", grid.dims},
            {"voxel_size", grid.voxelSize},
            {"backend", stats.backend},
            {"renderer", stats.renderer},
            {"gpu_bytes", stats.gpuBytes},
            {"repeat", repeat},
            {"peak_rss_mb", peakRssMb()},
            {"startup", startupJson(stats.startup)},
            {"stages", stagesJson(stats.stages)},
            {"total_wall_ms", wallMs}};
}

/// Runs @a once --repeat times (after one warm-up when there are several
/// runs and @a warmUp() says so) and returns the last run's result. @a stats
/// gets each stage's median over the runs, the load stage first, and the
/// start-up the first call paid; the warnings are printed.
template <typename Once, typename WarmUp>
auto timedRuns(LibraryCall& call, int repeat, WarmUp warmUp, const StageTime& load, VoxelizeStats& stats, Once once)
{
    std::vector<VoxelizeStats> runs(static_cast<size_t>(repeat));
    decltype(once()) result;
    std::optional<StartupStats> startup; // the first call's: later calls on this Voxelizer start warm
    if (repeat > 1 && warmUp()) {
        once();
        startup = call.stats.startup;
    }
    for (auto& run : runs) {
        result = once();
        run = call.stats;
        if (!startup) startup = run.startup;
    }
    stats = medianStats(runs);
    stats.stages.insert(stats.stages.begin(), load);
    stats.startup = *startup;
    printWarnings(stats.warnings);
    return result;
}

/// The first grid's counts and every grid's name, from OpenVDB or NanoVDB grids.
struct GridCounts {
    uint64_t voxels = 0, leaves = 0, tiles = 0;
    std::string name, names;
    explicit GridCounts(const openvdb::GridPtrVec& grids)
        : voxels(grids.front()->activeVoxelCount()), leaves(grids.front()->baseTree().leafCount()),
          tiles(grids.front()->baseTree().activeTileCount()), name(grids.front()->getName())
    {
        for (const auto& g : grids) names += (names.empty() ? "" : ", ") + g->getName();
    }
    explicit GridCounts(const std::vector<vdb::NanoHandle>& grids)
    {
        const auto* m = grids.front().gridMetaData();
        voxels = m->activeVoxelCount();
        leaves = m->nodeCount(0);
        for (uint32_t level = 1; level <= 3; ++level) tiles += m->activeTileCount(level);
        name = m->shortGridName();
        for (const auto& g : grids) names += (names.empty() ? "" : ", ") + std::string(g.gridMetaData()->shortGridName());
    }
};

/// svo voxelize --sdf | --udf | --fill solid | --fill band: grids from the library, written as .vdb or .nvdb.
void runField(const VoxelizeArgs& a, const LevelSetOptions& ls, LibraryCall& call, TriangleMesh& mesh, const StageTime& load,
              const std::string& scene,
              const GridSpec& grid, const GridRequest& request, const std::string& output, bool timingOnly,
              std::chrono::steady_clock::time_point start, OutputBatch& outputs)
{
    const bool solid = a.fill == "solid", band = a.band();

    VoxelizeStats stats;
    // .nvdb: NanoVDB grids laid out from the field's bricks, no OpenVDB tree.
    const bool nano = !timingOnly && outputFormat(output) == OutputFormat::NanoVdb;
    std::vector<vdb::NanoHandle> nanoGrids;
    const openvdb::GridPtrVec all = timedRuns(call, a.repeat, [] { return true; }, load, stats, [&] {
        nanoGrids.clear();
        if (nano && solid)
            nanoGrids.push_back(call.voxelizer.solidNanoVdb(mesh, grid, call.options, ls.sign, a.out.grids.topology));
        else if (nano && band)
            nanoGrids.push_back(
                call.voxelizer.bandNanoVdb(mesh, grid, ls.exteriorBand, call.options, a.out.grids.topology));
        else if (nano)
            nanoGrids = call.voxelizer.levelSetNanoVdb(mesh, grid, ls, call.options);
        if (nano) return openvdb::GridPtrVec{};
        if (solid)
            return openvdb::GridPtrVec{
                vdb::withTopology(call.voxelizer.solid(mesh, grid, call.options, ls.sign), a.out.grids.topology)};
        if (band)
            return openvdb::GridPtrVec{vdb::withTopology(
                call.voxelizer.band(mesh, grid, ls.exteriorBand, call.options), a.out.grids.topology)};
        return call.voxelizer.levelSet(mesh, grid, ls, call.options);
    });
    // Closest triangles (Int32Grid) beside the output: python3-openvdb opens the output whole.
    const auto [grids, triangles] = vdb::splitTriangleGrids(all);
    // Python's level_set() and solid() tag theirs the same (no guard band: a field's voxels are not a surface's).
    const std::map<std::string, std::string> meta = resultMetadata(mesh, grid, request, false);
    const size_t triangleCount = release(mesh);
    vdb::WriteStats written;
    std::string sidecar;
    if (nano) {
        Progress p("writing " + output);
        const auto t0 = std::chrono::steady_clock::now();
        written.bytes = vdb::writeNanoVdb(output, nanoGrids, a.out.grids.codec);
        written.writeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        stats.stages.push_back({"write", -1, written.writeMs});
    } else if (!timingOnly) {
        Progress p("writing " + output);
        written = vdb::writeVdbGrids(output, grids, meta);
        if (!triangles.empty()) {
            sidecar = vdb::triangleSidecarPath(output);
            vdb::markTriangleSidecar(triangles, output);
            written.sidecarBytes = vdb::writeVdbGrids(sidecar, triangles, meta).bytes;
        }
        stats.stages.push_back({"write", -1, written.writeMs});
    }
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const GridCounts counts = nano ? GridCounts(nanoGrids) : GridCounts(grids);
    const bool boolGrid = a.out.grids.topology == GridOptions::Topology::Bool;
    if (!a.json.empty()) {
        nlohmann::json report = runJson(scene, triangleCount, grid, stats, a.repeat, wall);
        report.update(nlohmann::json{{"kind", solid ? "solid" : band ? "band" : a.udf() ? "udf" : "sdf"},
                                     {"exterior_band", ls.exteriorBand},
                                     {"interior_band", ls.interiorBand},
                                     {"sign", stats.sign},
                                     {"open_columns", stats.openColumns},
                                     {"active_voxels", counts.voxels},
                                     {"leaves", counts.leaves},
                                     {"active_tiles", counts.tiles},
                                     {"band_bricks", stats.bandBricks},
                                     {"winding_bricks", stats.windingBricks},
                                     {"winding_walks", stats.windingWalks}});
        writeFileAtomically(a.json, report.dump(2) + "\n");
    }
    outputs.commit(); // then the summary: what it says was written is in place
    const std::string removed = timingOnly || !sidecar.empty() ? std::string() : removeStaleSidecar(output, {a.mesh}, a.habits);
    if (!reportShown()) {
        if (summaryShown())
            fmt::print("svo voxelize: {} ({} '{}', {} active voxels{}) in {}{}{}\n",
                       timingOnly ? std::string("nothing written (--repeat without -o)")
                                  : fmt::format("wrote {}", output),
                       solid ? fmt::format("solid, {}", boolGrid ? "bool" : "mask")
                       : band ? fmt::format("band, {}", boolGrid ? "bool" : "mask")
                       : a.udf() ? std::string("unsigned distance")
                                 : std::string("level set"),
                       counts.name, thousands(counts.voxels),
                       timingOnly ? std::string() : fmt::format(", {:.2f} MB", double(written.bytes) / 1e6),
                       seconds(wall),
                       sidecar.empty() ? std::string() : fmt::format("; {} in {}", GridCounts(triangles).names, sidecar),
                       staleSidecarNote(removed, output));
    } else {
        printHeading(scene, triangleCount, grid, request);
        if (solid)
            fmt::print("  {:<11} solid: inside and surface voxels ({})\n", "grid kind",
                       boolGrid ? "BoolGrid" : "MaskGrid");
        else if (band)
            fmt::print("  {:<11} band: voxels nearer than {} voxels to a triangle ({})\n", "grid kind", ls.exteriorBand,
                       boolGrid ? "BoolGrid" : "MaskGrid");
        else if (a.udf())
            fmt::print("  {:<11} unsigned distance, band {} voxels\n", "grid kind", ls.exteriorBand);
        else
            fmt::print("  {:<11} level set, exterior band {} voxels, interior band {} voxels\n", "grid kind",
                       ls.exteriorBand, ls.interiorBand);
        if (!stats.sign.empty()) fmt::print("  {:<11} {}\n", "sign", stats.sign);
        fmt::print("  {:<11} {} active ({} leaves, {} active tiles)\n", "voxels", thousands(counts.voxels),
                   thousands(counts.leaves), thousands(counts.tiles));
        fmt::print("  {:<11} {} band bricks{}{}, {:.1f} MB of GPU buffers\n", "work", thousands(stats.bandBricks),
                   stats.windingBricks ? fmt::format(" and {} bricks beyond it voxel by voxel", thousands(stats.windingBricks))
                                       : std::string(),
                   stats.windingWalks ? fmt::format(", winding numbers walked at {} centres", thousands(stats.windingWalks))
                                      : std::string(),
                   double(stats.gpuBytes) / 1e6);
        fmt::print("  {:<11} {}\n", "backend", backendLine(stats));
        fmt::print("  {:<11} {}\n", "output",
                   timingOnly ? std::string("none (--repeat without -o times the runs only)")
                              : fmt::format("{} ({:.2f} MB; grids {})", output, double(written.bytes) / 1e6, counts.names));
        if (!sidecar.empty())
            fmt::print("  {:<11} {} ({:.2f} MB; grids {}, which python3-openvdb does not read)\n", "beside it", sidecar,
                       double(written.sidecarBytes) / 1e6, GridCounts(triangles).names);
        if (!removed.empty()) fmt::print("  {:<11} {}\n", "removed", staleSidecarText(removed, output));
        printStageTable(stats.stages, wall, a.repeat, "", &stats.startup);
    }
}

void runVoxelize(const VoxelizeArgs& a, const CLI::App& cmd)
{
    checkFieldArgs(a, cmd);
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const GridRequest request = gridRequest(a.grid);

    // No output may be the input or another output: refused before any work.
    checkOutputs({a.mesh}, {a.output, a.json});
    checkClobber(a.habits, {a.output, a.json});
    // Every output is finished in a temporary and all are put in place together
    // at the end: a failure or an interrupt before then replaces none of them.
    OutputBatch outputs({a.output, a.json});
    LibraryCall call(a.backend, a.fill == "solid" ? "filling the solid"
                                : a.band()        ? "finding the band"
                                : a.field()       ? "computing the distance field"
                                                  : "voxelizing");
    // EGL set-up beside loading the mesh; joined (a device error rethrown) before the first call.
    std::future<void> device;
    if (call.voxelizer.backendFor(call.options) != Backend::Cpu)
        device = std::async(std::launch::async, [&voxelizer = call.voxelizer] { voxelizer.startDevice(); });
    // Then load: a bad mesh must fail before any output is considered.
    TriangleMesh mesh;
    const auto loadStart = Clock::now();
    {
        Progress p("loading " + (a.mesh.empty() ? std::string("built-in scene") : a.mesh));
        mesh = a.mesh.empty() ? cornellBox() : loadMesh(a.mesh);
    }
    const StageTime load{"mesh load (cpu)", -1, std::chrono::duration<double, std::milli>(Clock::now() - loadStart).count()};
    printWarnings(mesh.warnings);
    const std::string scene = a.mesh.empty() ? mesh.source : std::filesystem::path(a.mesh).stem().string();
    // --repeat without -o is a timing run and writes nothing; otherwise the
    // default name is used, and replaced like any output (vdb_tool's habit).
    const bool timingOnly = a.repeat > 1 && a.output.empty();
    const std::string output = timingOnly ? std::string() : a.output.empty() ? scene + ".vdb" : a.output;
    if (!timingOnly) checkOutputPath(output);
    checkCodec(a.out, output);
    // A .vdb output's triangle indices go beside it (reader_grids.h): an output too.
    const std::string sidecar = !timingOnly && a.triangleGrids() && outputFormat(output) == OutputFormat::Vdb
                                    ? vdb::triangleSidecarPath(output)
                                    : std::string();
    checkOutputs({a.mesh}, {output, a.json, sidecar}); // the default name is known only now
    checkClobber(a.habits, {output, sidecar});
    outputs.add(output);
    outputs.add(sidecar);
    if (!a.json.empty()) checkWritable(a.json);
    const GridSpec grid = makeGrid(mesh, request);
    // An OpenVDB output must be able to hold the voxel size: refused before the GPU works.
    if (!timingOnly && outputFormat(output) != OutputFormat::Svo) vdb::checkVdbGrid(grid, output);
    if (device.valid()) {
        try {
            device.get();
        } catch (const DeviceError&) {
            // Backend::Auto with no GL runs on the CPU (gl::Device::withoutGl): the call decides,
            // and fails with this error where the work needs the GPU.
            if (call.options.backend != Backend::Auto || call.options.dilation != Dilation::Auto) throw;
        }
    }
    if (a.field()) {
        return runField(a, a.levelSet.levelSetOptions(cmd), call, mesh, load, scene, grid, request, output, timingOnly,
                        start, outputs);
    }
    const GridOptions grids = a.out.grids;
    if (!timingOnly && outputFormat(output) == OutputFormat::Svo && (cmd.count("--fog") || cmd.count("--topology")))
        throw InvalidInput(fmt::format("{}: --fog and --topology apply to .vdb and .nvdb output, not .svo", output));

    // Voxelize: with --repeat, one warm-up on the GPU, then per-stage medians.
    VoxelizeStats stats;
    const Octree octree = timedRuns(
        call, a.repeat, [&] { return call.voxelizer.backendFor(call.options) != Backend::Cpu; }, load, stats,
        [&] { return call.voxelizer.voxelize(mesh, grid, call.options); });

    // Python's voxelize() tags its grids the same.
    const std::map<std::string, std::string> meta = resultMetadata(mesh, grid, request, true);
    const size_t triangleCount = release(mesh);
    WriteReport written;
    if (!timingOnly && outputFormat(output) == OutputFormat::NanoVdb) {
        // Laid out by the Voxelizer: on the GPU where the voxels were made there.
        Progress p("writing " + output);
        VoxelizeOptions nano = call.options;
        nano.stats = &stats;
        const size_t warned = stats.warnings.size();
        const std::vector<vdb::NanoHandle> handles = call.voxelizer.octreeNanoVdb(octree, grids, nano);
        printWarnings(std::vector<std::string>(stats.warnings.begin() + std::ptrdiff_t(warned), stats.warnings.end()));
        const auto t0 = Clock::now();
        written.format = OutputFormat::NanoVdb;
        written.bytes = vdb::writeNanoVdb(output, handles, grids.codec);
        written.leaves = octree.bricks.size();
        written.stages.push_back({"nvdb write", -1, std::chrono::duration<double, std::milli>(Clock::now() - t0).count()});
    } else if (!timingOnly) {
        Progress p("writing " + output);
        written = writeOctree(output, octree, grids, meta);
    }
    for (const auto& s : written.stages) stats.stages.push_back(s);
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

    const auto st = octreeStats(octree);
    if (!a.json.empty()) {
        nlohmann::json report = runJson(scene, triangleCount, grid, stats, a.repeat, wall);
        report.update(nlohmann::json{{"resolution", request.resolution},
                                     {"mode", stats.mode},
                                     {"conservative", nameOf(a.backend.settings.dilation)},
                                     {"dilation", stats.dilation},
                                     {"epsilon", grid.epsilon()},
                                     {"voxels", st.voxels},
                                     {"bricks", st.bricks},
                                     {"nodes", octree.nodes.size()},
                                     {"nodes_per_level", st.nodesPerLevel},
                                     {"octree_bytes", st.bytes},
                                     {"list_entries", stats.listEntries},
                                     {"overflow_retries", stats.overflowRetries},
                                     {"tiles", stats.tiles}});
        writeFileAtomically(a.json, report.dump(2) + "\n");
    }
    outputs.commit(); // then the summary: what it says was written is in place
    const std::string removed =
        timingOnly || !written.sidecar.empty() ? std::string() : removeStaleSidecar(output, {a.mesh}, a.habits);
    if (!reportShown()) {
        if (summaryShown())
            fmt::print("svo voxelize: {} ({}{} voxels{}) in {}{}{}\n",
                       timingOnly ? std::string("nothing written (--repeat without -o)")
                                  : fmt::format("wrote {}", output),
                       timingOnly                         ? std::string()
                       : written.format == OutputFormat::Svo ? std::string("octree, ")
                                                          : fmt::format("{} grid '{}'{}, ",
                                                                        grids.topology == GridOptions::Topology::Bool
                                                                            ? "bool"
                                                                            : "mask",
                                                                        grids.name, grids.fog ? " and 'density'" : ""),
                       thousands(st.voxels),
                       timingOnly ? std::string() : fmt::format(", {:.2f} MB", double(written.bytes) / 1e6),
                       seconds(wall),
                       written.sidecar.empty() ? std::string() : fmt::format("; triangle_id in {}", written.sidecar),
                       staleSidecarNote(removed, output));
    } else {
        printHeading(scene, triangleCount, grid, request);
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
        fmt::print("  {:<11} {} entries, {} overflow retries, {:.1f} MB of GPU buffers{}\n", "voxel list",
                   thousands(stats.listEntries), stats.overflowRetries, double(stats.gpuBytes) / 1e6,
                   stats.tiles > 1 ? fmt::format(", in {} tiles", stats.tiles) : std::string());
        fmt::print("  {:<11} {}\n", "output",
                   timingOnly ? std::string("none (--repeat without -o times the runs only)")
                              : describeOutput(output, written, grids));
        if (!written.sidecar.empty())
            fmt::print("  {:<11} {} ({:.2f} MB; grid triangle_id, which python3-openvdb does not read)\n", "beside it",
                       written.sidecar, double(written.sidecarBytes) / 1e6);
        if (!removed.empty()) fmt::print("  {:<11} {}\n", "removed", staleSidecarText(removed, output));
        printStageTable(stats.stages, wall, a.repeat, "voxelize stages: ", &stats.startup);
    }
}

} // namespace

void addVoxelizeCommand(CLI::App& app)
{
    auto args = std::make_shared<VoxelizeArgs>();
    CLI::App* cmd = app.add_subcommand(
        "voxelize", "Voxelize a mesh (default: the built-in Cornell box) into a .vdb or .nvdb grid or a .svo octree");
    cmd->add_option("mesh", args->mesh,
                    fmt::format("Mesh file ({}); none = built-in Cornell box", supportedMeshExtensions()))
        ->check(nonEmptyMeshPath, "MESH");
    addOutputPath(*cmd, "-o,--output", args->output, "Output .vdb, .nvdb (NanoVDB) or .svo (default: <scene>.vdb)");
    addOutputPath(*cmd, "--json", args->json, "Also write the summary (counts, bytes, stage times) as JSON");
    addGridOptions(*cmd, args->grid);
    addBackendOptions(*cmd, args->backend);
    addOptions(*cmd, args->backend.settings, {"attributes", "mode", "gpu_memory", "region"});
    addOutputOptions(*cmd, args->out);
    addOutputHabits(*cmd, args->habits);
    cmd->add_flag("--sdf", args->sdf,
                  "Write a narrow-band signed distance field (OpenVDB level set, grid 'surface') instead of voxels");
    addOptions(*cmd, args->levelSet.options, {"unsigned"}, "within the band (grid 'distance') instead of voxels");
    cmd->add_option("--fill", args->fill,
                    "surface: the voxels the triangles touch; solid: also every voxel whose centre is inside "
                    "(grid 'solid', whole regions as tiles); band: every voxel whose centre is nearer than --band "
                    "voxels to a triangle (grid 'band': the active voxels of --udf, without distances)")
        ->check(CLI::IsMember({"surface", "solid", "band"}));
    addBandOptions(*cmd, args->levelSet, "for --sdf, --udf and --fill band");
    addOptions(*cmd, args->levelSet.options, {"sign", "winding_accuracy", "part_of_closed_mesh"},
               "for --sdf and --fill solid");
    addOptions(*cmd, args->levelSet.options, {"closest_triangle"}, "with --sdf or --udf");
    cmd->add_option("--repeat", args->repeat,
                    "Voxelize N times (after one warm-up on the GPU) and report per-stage medians; without -o, "
                    "nothing is written")
        ->check(CLI::Range(1, 1000));
    cmd->callback([args, cmd] { runVoxelize(*args, *cmd); });
}

} // namespace svo::app
