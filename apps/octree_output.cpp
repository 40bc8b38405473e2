#include "octree_output.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>

#include "mesh_voxelizer.h"
#include "progress.h"
#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/core/octree_file.h"
#include "svo/vdb_io/vdb_file.h"

namespace svo::app {

void addGridOptions(CLI::App& cmd, int64_t& resolution, double& voxelSize)
{
    auto* res = cmd.add_option("-r,--resolution", resolution, "Voxels along the longest bounding-box side (default 256)");
    auto* size = cmd.add_option("--voxel-size", voxelSize, "Voxel size in world units");
    res->excludes(size);
}

GridRequest gridRequest(const CLI::App& cmd, int64_t resolution, double voxelSize)
{
    const bool gotRes = cmd.count("--resolution") > 0, gotSize = cmd.count("--voxel-size") > 0;
    if (gotRes && resolution < 1) throw Error(fmt::format("--resolution must be at least 1, got {}", resolution));
    if (gotSize && !(voxelSize > 0)) throw Error(fmt::format("--voxel-size must be positive, got {}", voxelSize));
    GridRequest r;
    r.resolution = gotRes ? resolution : (gotSize ? 0 : 256);
    r.voxelSize = gotSize ? voxelSize : 0;
    return r;
}

void addOutputOptions(CLI::App& cmd, OutputSettings& s)
{
    cmd.add_option("--topology", s.topology, "Grid type of the .vdb topology: mask (MaskGrid) or bool (BoolGrid)")
        ->check(CLI::IsMember({"mask", "bool"}))
        ->capture_default_str();
    cmd.add_flag("--fog", s.fog, "Also write a fog-volume FloatGrid 'density' (.vdb output)");
}

std::string outputKind(const std::string& path)
{
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".vdb") return "vdb";
    if (ext == ".svo") return "svo";
    throw Error(fmt::format("{}: the output must end in .vdb or .svo", path));
}

void checkOutputPath(const std::string& path)
{
    outputKind(path);
    checkWritable(path);
}

OutputReport writeOctreeOutput(const std::string& path, const Octree& octree, const OutputSettings& s,
                               const std::map<std::string, std::string>& metadata)
{
    using Clock = std::chrono::steady_clock;
    OutputReport report;
    Progress p("writing " + path);
    if (outputKind(path) == "svo") {
        const auto t0 = Clock::now();
        writeOctreeFile(path, octree);
        report.stages.push_back({"svo write", -1, std::chrono::duration<double, std::milli>(Clock::now() - t0).count()});
        std::error_code ec;
        report.description = fmt::format("{} ({:.2f} MB octree)", path, double(std::filesystem::file_size(path, ec)) / 1e6);
        return report;
    }
    vdb::WriteOptions wo;
    wo.topology = s.topology == "bool" ? vdb::Topology::Bool : vdb::Topology::Mask;
    wo.fog = s.fog;
    wo.metadata = metadata;
    const vdb::WriteStats ws = vdb::writeVdb(path, octree, wo);
    report.stages.push_back({"vdb build (cpu)", -1, ws.buildMs});
    report.stages.push_back({"vdb write", -1, ws.writeMs});
    report.description = fmt::format("{} ({:.2f} MB, {} {} leaves{})", path, double(ws.bytes) / 1e6,
                                     thousands(ws.leaves), s.topology, s.fog ? ", with fog grid" : "");
    return report;
}

void printOctreeSummary(const Octree& o)
{
    const OctreeStats st = octreeStats(o);
    const auto t = o.grid.translation();
    fmt::print("  {:<12} {} x {} x {} voxels from index ({}, {}, {}), voxel size {:.6g}, translation ({:.6g}, {:.6g}, "
               "{:.6g})\n",
               "grid", o.grid.dims[0], o.grid.dims[1], o.grid.dims[2], o.grid.anchor[0], o.grid.anchor[1],
               o.grid.anchor[2], o.grid.voxelSize, t[0], t[1], t[2]);
    fmt::print("  {:<12} {} (root 0 .. bricks {}); root covers {}^3 voxels\n", "levels", o.brickLevel + 1, o.brickLevel,
               8u << o.brickLevel);
    fmt::print("  {:<12} {:>6} {:>14} {:>14}\n", "", "level", "nodes", "occupied");
    for (size_t l = 0; l < st.nodesPerLevel.size(); ++l)
        fmt::print("  {:<12} {:>6} {:>14} {:>14}\n", "", l, thousands(st.nodesPerLevel[l]),
                   thousands(st.occupiedPerLevel[l]));
    fmt::print("  {:<12} {}\n", "bricks", thousands(st.bricks));
    fmt::print("  {:<12} {}\n", "voxels", thousands(st.voxels));
    fmt::print("  {:<12} {} (nodes {} + bricks {})\n", "bytes", thousands(st.bytes),
               thousands(o.nodes.size() * sizeof(OctreeNode)), thousands(o.bricks.size() * sizeof(Brick)));
    fmt::print("  {:<12} {:.3f}\n", "bytes/voxel", st.bytesPerVoxel());
    fmt::print("  {:<12} {:.3f} of brick voxels occupied\n", "fill ratio", st.fillRatio());
}

} // namespace svo::app
