// svo convert IN.vdb|IN.nvdb|IN.svo -o OUT.svo|OUT.vdb|OUT.nvdb
//
// A .vdb or .nvdb input to .vdb or .nvdb output keeps its grids whole: every grid (or
// the one --grid names) with its type, class, transform, values and metadata
// (NanoVDB keeps type, class, name, transform and values; it has no string
// metadata; a .nvdb input is read and checked by vdb::readNanoVdbGrids). A .svo file holds one grid's active voxels; a grid that holds
// more (a level set's distances, normals, any value but true or 1) is refused
// unless --topology-only asks for the active voxels alone, which also makes
// the old octree-built grids (--topology, --fog) from a .vdb input.
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "stale_sidecar.h"
#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/vdb_io/nanovdb_input.h"
#include "svo/vdb_io/nanovdb_output.h"
#include "svo/load_octree.h"
#include "svo/result_metadata.h"
#include "svo/vdb_io/octree_files.h"
#include "svo/vdb_io/reader_grids.h"
#include "svo/vdb_io/vdb_file.h"

namespace svo::app {
namespace {

struct ConvertArgs {
    std::string input, output, gridName;
    BackendArgs backend;
    OutputArgs out;
    OutputHabits habits; ///< -q, -v, --no-clobber
    bool topologyOnly = false;
};

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// .vdb or .nvdb to .vdb or .nvdb, every grid as it is.
void copyGrids(const ConvertArgs& a, bool nanoInput, Clock::time_point start, OutputBatch& outputs)
{
    openvdb::GridPtrVec grids;
    {
        Progress p("reading " + a.input);
        grids = nanoInput ? vdb::readNanoVdbGrids(a.input, a.gridName) : vdb::readVdbGrids(a.input, a.gridName);
    }
    WriteReport written;
    written.format = outputFormat(a.output);
    {
        Progress p("writing " + a.output);
        if (written.format == OutputFormat::NanoVdb) written.bytes = vdb::writeNanoVdb(a.output, grids, a.out.grids.codec);
        else written.bytes = vdb::writeVdbGrids(a.output, grids, {}).bytes;
    }
    outputs.commit(); // then the report: what it says was written is in place
    const std::string removed = removeStaleSidecar(a.output, {a.input}, a.habits);
    if (!reportShown()) {
        uint64_t voxels = 0;
        for (const auto& g : grids) voxels += g->activeVoxelCount();
        if (summaryShown())
            fmt::print("svo convert: wrote {} ({} grid{} as they are, {} active voxels, {:.2f} MB) in {}{}\n", a.output,
                       grids.size(), grids.size() == 1 ? "" : "s", thousands(voxels), double(written.bytes) / 1e6,
                       seconds(msSince(start)), staleSidecarNote(removed, a.output));
        return;
    }
    fmt::print("svo convert\n");
    fmt::print("  {:<12} {} ({} grid{})\n", "input", a.input, grids.size(), grids.size() == 1 ? "" : "s");
    fmt::print("  {:<12} {} ({:.2f} MB{}, the grids as they are)\n", "output", a.output, double(written.bytes) / 1e6,
               written.format == OutputFormat::NanoVdb ? ", NanoVDB" : "");
    for (const auto& g : grids) {
        const auto cls = g->getGridClass();
        fmt::print("  {:<12} '{}' {}{}, {} active voxels\n", "grid", g->getName(), g->valueType(),
                   cls == openvdb::GRID_UNKNOWN ? "" : ", " + openvdb::GridBase::gridClassToString(cls),
                   thousands(g->activeVoxelCount()));
    }
    if (!removed.empty()) fmt::print("  {:<12} {}\n", "removed", staleSidecarText(removed, a.output));
}

void runConvert(const ConvertArgs& a, const CLI::App& cmd)
{
    const auto start = Clock::now();
    const std::string ext = std::filesystem::path(a.input).extension().string();
    if (ext != ".vdb" && ext != ".nvdb" && ext != ".svo")
        throw IoError(fmt::format("{}: svo convert reads .vdb, .nvdb and .svo files; voxelize meshes with svo voxelize",
                                  a.input));
    const bool gridsInput = ext == ".vdb" || ext == ".nvdb";
    checkOutputPath(a.output);
    checkCodec(a.out, a.output);
    checkOutputs({a.input}, {a.output});
    checkClobber(a.habits, {a.output});
    OutputBatch outputs({a.output}); // in place at the very end (atomic_file.h)
    const GridOptions grids = a.out.grids;
    const bool toSvo = outputFormat(a.output) == OutputFormat::Svo;
    if (toSvo && (cmd.count("--fog") || cmd.count("--topology")))
        throw InvalidInput(fmt::format("{}: --fog and --topology apply to .vdb and .nvdb output, not .svo", a.output));
    if (ext == ".svo" && a.topologyOnly)
        throw InvalidInput(fmt::format("{}: --topology-only applies to a .vdb or .nvdb input; a .svo file holds active voxels only",
                                       a.input));
    if (gridsInput && !toSvo && !a.topologyOnly) {
        if (cmd.count("--fog") || cmd.count("--topology"))
            throw InvalidInput(fmt::format("{}: a {} input keeps its grids as they are; --fog and --topology make new "
                                           "grids from its active voxels, which needs --topology-only",
                                           a.input, ext));
        return copyGrids(a, ext == ".nvdb", start, outputs);
    }
    LibraryCall call(a.backend, "building the octree");
    const LoadedOctree lo = loadOctree(call.voxelizer, a.input, a.gridName, {}, call.options);
    if (!lo.valuesDropped.empty() && !a.topologyOnly)
        throw InvalidInput(fmt::format("{}: {} would be lost: {} holds only which voxels are active; write .vdb or .nvdb to "
                                       "keep them, or give --topology-only to keep the active voxels alone",
                                       a.input, lo.valuesDropped, toSvo ? "a .svo file" : "an octree"));
    const std::map<std::string, std::string> meta = sourceMetadata(a.input);
    // A .vdb output's triangle indices go beside it (reader_grids.h): an output too, known once the input is read.
    if (outputFormat(a.output) == OutputFormat::Vdb && grids.attributes && !lo.octree.attributes.triangles.empty()) {
        const std::string sidecar = vdb::triangleSidecarPath(a.output);
        checkOutputs({a.input}, {a.output, sidecar});
        checkClobber(a.habits, {sidecar});
        outputs.add(sidecar);
    }
    WriteReport written;
    {
        Progress p("writing " + a.output);
        written = writeOctree(a.output, lo.octree, grids, meta);
    }
    outputs.commit(); // then the report: what it says was written is in place
    const std::string removed = written.sidecar.empty() ? removeStaleSidecar(a.output, {a.input}, a.habits) : std::string();
    if (!reportShown()) {
        if (summaryShown())
            fmt::print("svo convert: wrote {} ({} voxels, {:.2f} MB) in {}{}{}\n", a.output,
                       thousands(lo.octree.voxelCount()), double(written.bytes) / 1e6, seconds(msSince(start)),
                       written.sidecar.empty() ? std::string() : fmt::format("; triangle_id in {}", written.sidecar),
                       staleSidecarNote(removed, a.output));
        return;
    }
    fmt::print("svo convert\n");
    fmt::print("  {:<12} {}\n", "input", describeInput(a.input, lo, call.stats));
    fmt::print("  {:<12} {}\n", "output", describeOutput(a.output, written, grids));
    if (!written.sidecar.empty())
        fmt::print("  {:<12} {} ({:.2f} MB; grid triangle_id, which python3-openvdb does not read)\n", "beside it",
                   written.sidecar, double(written.sidecarBytes) / 1e6);
    if (!removed.empty()) fmt::print("  {:<12} {}\n", "removed", staleSidecarText(removed, a.output));
    fmt::print("  {:<12} {} voxels in {} bricks\n", "octree", thousands(lo.octree.voxelCount()),
               thousands(lo.octree.bricks.size()));
    fmt::print("\n  {:<20} {:>10} {:>10}\n", "stage", "GPU ms", "wall ms");
    printStages(lo.stages);
    printStages(written.stages);
}

} // namespace

void addConvertCommand(CLI::App& app)
{
    auto args = std::make_shared<ConvertArgs>();
    CLI::App* cmd = app.add_subcommand("convert", "Convert between .vdb or .nvdb grids and .svo octrees");
    cmd->add_option("input", args->input, "Input .vdb, .nvdb or .svo")->required();
    addOutputPath(*cmd, "-o,--output", args->output, "Output .svo, .vdb or .nvdb")->required();
    addGridNameOption(*cmd, args->gridName);
    addBackendOptions(*cmd, args->backend);
    addOutputOptions(*cmd, args->out);
    addOutputHabits(*cmd, args->habits);
    cmd->add_flag("--topology-only", args->topologyOnly,
                  "From a .vdb or .nvdb input, keep only one grid's active voxels (its values and class dropped), as an "
                  "octree written as .svo or as new grids (--topology, --fog); without it a .vdb or .nvdb input keeps "
                  "every grid whole, and a .svo output refuses a grid with values");
    cmd->callback([args, cmd] { runConvert(*args, *cmd); });
}

} // namespace svo::app
