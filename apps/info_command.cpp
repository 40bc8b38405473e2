// svo info FILE: what an octree built from a mesh, .vdb, .nvdb or .svo looks
// like; for a .nvdb, also every grid the file holds.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "svo/vdb_io/nanovdb_input.h"
#include "svo/core/mesh_io.h"

namespace svo::app {
namespace {

struct InfoArgs {
    std::string input, gridName;
    GridRequest grid; ///< -r/--resolution or --voxel-size
    BackendArgs backend;
};

/// One line per grid of a .nvdb file: name, type, class, active voxels,
/// index bounding box, voxel size and translation.
void printNanoVdbGrids(const std::string& path)
{
    for (const auto& g : vdb::readNanoVdbGrids(path)) {
        const auto cls = g->getGridClass();
        const openvdb::CoordBBox box = g->evalActiveVoxelBoundingBox();
        const openvdb::Vec3d vs = g->voxelSize();
        const openvdb::Vec3d t = g->indexToWorld(openvdb::Vec3d(0.0));
        const std::string size = vs[0] == vs[1] && vs[1] == vs[2]
                                     ? fmt::format("{:.6g}", vs[0])
                                     : fmt::format("({:.6g}, {:.6g}, {:.6g})", vs[0], vs[1], vs[2]);
        const std::string bbox = box.empty() ? std::string("empty")
                                             : fmt::format("({}, {}, {}) .. ({}, {}, {})", box.min()[0], box.min()[1],
                                                           box.min()[2], box.max()[0], box.max()[1], box.max()[2]);
        fmt::print("  {:<12} '{}' {}{}, {} active voxels, index bbox {}, voxel size {}, translation ({:.6g}, {:.6g}, "
                   "{:.6g})\n",
                   "nvdb grid", printable(g->getName()), g->valueType(),
                   cls == openvdb::GRID_UNKNOWN ? "" : ", " + openvdb::GridBase::gridClassToString(cls),
                   thousands(g->activeVoxelCount()), bbox, size, t[0], t[1], t[2]);
    }
}

void runInfo(const InfoArgs& a)
{
    LibraryCall call(a.backend, "building the octree");
    const LoadedOctree lo = call.load(a.input, a.gridName, gridRequest(a.grid));
    fmt::print("svo info\n");
    fmt::print("  {:<12} {}\n", "input", describeInput(a.input, lo, call.stats));
    if (std::filesystem::path(a.input).extension() == ".nvdb") printNanoVdbGrids(a.input);
    printOctreeSummary(lo.octree);
}

} // namespace

void addInfoCommand(CLI::App& app)
{
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand("info", "Print the octree of a .svo, .vdb, .nvdb or mesh file: levels, nodes, bricks, bytes (and a .nvdb's grids)");
    cmd->add_option("input", args->input,
                    fmt::format("A .svo, .vdb, .nvdb or mesh file ({})", supportedMeshExtensions()))
        ->required();
    addGridNameOption(*cmd, args->gridName);
    addGridOptions(*cmd, args->grid);
    addBackendOptions(*cmd, args->backend);
    cmd->callback([args] { runInfo(*args); });
}

} // namespace svo::app
