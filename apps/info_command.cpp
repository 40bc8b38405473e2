// svo info FILE: what an octree built from a mesh, .vdb or .svo looks like.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "octree_input.h"
#include "octree_output.h"

namespace svo::app {
namespace {

struct InfoArgs {
    std::string input;
    int64_t resolution = 0;
    double voxelSize = 0;
    InputOptions in;
};

void runInfo(InfoArgs a, const CLI::App& cmd)
{
    a.in.gridRequest = gridRequest(cmd, a.resolution, a.voxelSize);
    const LoadedOctree lo = loadOctree(a.input, a.in);
    fmt::print("svo info\n");
    fmt::print("  {:<12} {}\n", "input", lo.description);
    printOctreeSummary(lo.octree);
}

} // namespace

void addInfoCommand(CLI::App& app)
{
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand("info", "Print the octree of a .svo, .vdb or mesh file: levels, nodes, bricks, bytes");
    cmd->add_option("input", args->input, "A .svo, .vdb or mesh file")->required();
    cmd->add_option("--grid", args->in.gridName, "Grid of a .vdb input (default: the first)");
    addGridOptions(*cmd, args->resolution, args->voxelSize);
    addBackendOptions(*cmd, args->in.backend);
    cmd->callback([args, cmd] { runInfo(*args, *cmd); });
}

} // namespace svo::app
