// svo convert IN.vdb|IN.svo -o OUT.svo|OUT.vdb
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "svo/core/atomic_file.h"
#include "svo/core/error.h"

namespace svo::app {
namespace {

struct ConvertArgs {
    std::string input, output, gridName;
    BackendArgs backend;
    OutputArgs out;
};

void runConvert(const ConvertArgs& a, const CLI::App& cmd)
{
    const std::string ext = std::filesystem::path(a.input).extension().string();
    if (ext != ".vdb" && ext != ".svo")
        throw Error(fmt::format("{}: svo convert reads .vdb and .svo files; voxelize meshes with svo voxelize", a.input));
    checkOutputPath(a.output);
    checkOutputs({a.input}, {a.output});
    OutputBatch outputs({a.output}); // in place at the very end (atomic_file.h)
    const GridOptions grids = a.out.gridOptions();
    if (outputFormat(a.output) == OutputFormat::Svo && (cmd.count("--fog") || cmd.count("--topology")))
        throw Error(fmt::format("{}: --fog and --topology apply to .vdb and .nvdb output, not .svo", a.output));
    LibraryCall call(a.backend, "building the octree");
    const LoadedOctree lo = loadOctree(call.voxelizer, a.input, a.gridName, {}, call.options);
    const std::map<std::string, std::string> meta = {{"svo:source", a.input}, {"svo:version", SVO_VERSION}};
    WriteReport written;
    {
        Progress p("writing " + a.output);
        written = writeOctree(a.output, lo.octree, grids, meta);
    }
    fmt::print("svo convert\n");
    fmt::print("  {:<12} {}\n", "input", describeInput(a.input, lo, call.stats));
    fmt::print("  {:<12} {}\n", "output", describeOutput(a.output, written, grids));
    fmt::print("  {:<12} {} voxels in {} bricks\n", "octree", thousands(lo.octree.voxelCount()),
               thousands(lo.octree.bricks.size()));
    fmt::print("\n  {:<20} {:>10} {:>10}\n", "stage", "GPU ms", "wall ms");
    printStages(lo.stages);
    printStages(written.stages);
    outputs.commit();
}

} // namespace

void addConvertCommand(CLI::App& app)
{
    auto args = std::make_shared<ConvertArgs>();
    CLI::App* cmd = app.add_subcommand("convert", "Convert between .vdb grids and .svo octrees");
    cmd->add_option("input", args->input, "Input .vdb or .svo")->required();
    addOutputPath(*cmd, "-o,--output", args->output, "Output .svo, .vdb or .nvdb")->required();
    cmd->add_option("--grid", args->gridName, "Grid of the input .vdb (default: the first)");
    addBackendOptions(*cmd, args->backend);
    addOutputOptions(*cmd, args->out);
    cmd->callback([args, cmd] { runConvert(*args, *cmd); });
}

} // namespace svo::app
