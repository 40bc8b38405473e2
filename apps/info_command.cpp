// svo info FILE: what an octree built from a mesh, .vdb or .svo looks like.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"

namespace svo::app {
namespace {

struct InfoArgs {
    std::string input, gridName;
    int64_t resolution = 0;
    double voxelSize = 0;
    BackendArgs backend;
};

void runInfo(const InfoArgs& a, const CLI::App& cmd)
{
    LibraryCall call(a.backend, "building the octree");
    const LoadedOctree lo =
        loadOctree(call.voxelizer, a.input, a.gridName, gridRequest(cmd, a.resolution, a.voxelSize), call.options);
    if (lo.mesh) printWarnings(lo.mesh->warnings);
    printWarnings(call.stats.warnings);
    fmt::print("svo info\n");
    fmt::print("  {:<12} {}\n", "input", describeInput(a.input, lo, call.stats));
    printOctreeSummary(lo.octree);
}

} // namespace

void addInfoCommand(CLI::App& app)
{
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand("info", "Print the octree of a .svo, .vdb or mesh file: levels, nodes, bricks, bytes");
    cmd->add_option("input", args->input, "A .svo, .vdb or mesh file")->required();
    cmd->add_option("--grid", args->gridName, "Grid of a .vdb input (default: the first)");
    addGridOptions(*cmd, args->resolution, args->voxelSize);
    addBackendOptions(*cmd, args->backend);
    cmd->callback([args, cmd] { runInfo(*args, *cmd); });
}

} // namespace svo::app
