// svo convert IN.vdb|IN.svo -o OUT.svo|OUT.vdb
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "octree_input.h"
#include "octree_output.h"
#include "svo/core/error.h"

namespace svo::app {
namespace {

struct ConvertArgs {
    std::string input, output;
    InputOptions in;
    OutputSettings out;
};

void runConvert(const ConvertArgs& a)
{
    const std::string ext = std::filesystem::path(a.input).extension().string();
    if (ext != ".vdb" && ext != ".svo")
        throw Error(fmt::format("{}: svo convert reads .vdb and .svo files; voxelize meshes with svo voxelize", a.input));
    checkOutputPath(a.output);
    LoadedOctree lo = loadOctree(a.input, a.in);
    std::map<std::string, std::string> meta = {{"svo:source", a.input}, {"svo:version", SVO_VERSION}};
    const OutputReport written = writeOctreeOutput(a.output, lo.octree, a.out, meta);
    fmt::print("svo convert\n");
    fmt::print("  {:<12} {}\n", "input", lo.description);
    fmt::print("  {:<12} {}\n", "output", written.description);
    fmt::print("  {:<12} {} voxels in {} bricks\n", "octree", thousands(lo.octree.voxelCount()),
               thousands(lo.octree.bricks.size()));
    fmt::print("\n  {:<20} {:>10} {:>10}\n", "stage", "GPU ms", "wall ms");
    for (const auto& s : lo.stages) fmt::print("  {:<20} {:>10} {:>10.2f}\n", s.name, s.gpuMs < 0 ? std::string("-") : fmt::format("{:.3f}", s.gpuMs), s.wallMs);
    for (const auto& s : written.stages) fmt::print("  {:<20} {:>10} {:>10.2f}\n", s.name, "-", s.wallMs);
}

} // namespace

void addConvertCommand(CLI::App& app)
{
    auto args = std::make_shared<ConvertArgs>();
    CLI::App* cmd = app.add_subcommand("convert", "Convert between .vdb grids and .svo octrees");
    cmd->add_option("input", args->input, "Input .vdb or .svo")->required();
    cmd->add_option("-o,--output", args->output, "Output .svo or .vdb")->required();
    cmd->add_option("--grid", args->in.gridName, "Grid of the input .vdb (default: the first)");
    addBackendOptions(*cmd, args->in.backend);
    addOutputOptions(*cmd, args->out);
    cmd->callback([args] { runConvert(*args); });
}

} // namespace svo::app
