#include "octree_input.h"

#include <chrono>
#include <filesystem>
#include <fmt/format.h>

#include "progress.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/core/octree_file.h"
#include "svo/gl/octree_builder.h"
#include "svo/vdb_io/vdb_file.h"

namespace svo::app {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

} // namespace

LoadedOctree loadOctree(const std::string& path, const InputOptions& opt)
{
    LoadedOctree out;
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".svo") {
        Progress p("reading " + path);
        const auto t0 = Clock::now();
        out.octree = readOctreeFile(path);
        out.kind = "svo";
        out.description = fmt::format("{} (.svo version {})", path, kOctreeFileVersion);
        out.stages.push_back({"svo read", -1, msSince(t0)});
        return out;
    }
    if (ext == ".vdb") {
        vdb::VdbBricks vb;
        {
            Progress p("reading " + path);
            const auto t0 = Clock::now();
            vb = vdb::readVdbBricks(path, opt.gridName);
            out.stages.push_back({"vdb read", -1, msSince(t0)});
        }
        out.kind = "vdb";
        out.description = fmt::format("{}, grid '{}' ({}, {} bricks{})", path, vb.gridName, vb.gridType,
                                      thousands(vb.bricks.size()),
                                      vb.tilesExpanded ? fmt::format(", {} active tiles expanded", vb.tilesExpanded) : "");
        if (opt.backend.backend == "cpu") {
            Progress p("building the octree on the CPU");
            const auto t0 = Clock::now();
            out.octree = buildOctreeFromBricks(vb.grid, std::move(vb.bricks));
            out.stages.push_back({"octree build (cpu)", -1, msSince(t0)});
        } else {
            gl::ContextOptions co;
            co.device = opt.backend.device;
            co.debug = opt.backend.glDebug;
            gl::Context context(co);
            Progress p("building the octree on the GPU");
            auto r = gl::buildOctreeGpu(context, vb.grid, vb.bricks);
            out.octree = std::move(r.octree);
            for (auto& s : r.stages) out.stages.push_back(s);
        }
        return out;
    }
    TriangleMesh mesh;
    {
        Progress p("loading " + path);
        mesh = loadMesh(path);
    }
    for (const auto& w : mesh.warnings) fmt::print(stderr, "svo: warning: {}\n", w);
    const GridSpec grid = makeGrid(mesh, opt.gridRequest);
    MeshVoxelization mv = voxelizeMesh(mesh, grid, opt.backend);
    out.octree = std::move(mv.result.octree);
    out.kind = "mesh";
    out.description = fmt::format("{} ({} triangles), voxelized by {}", path, thousands(mesh.triangles.size()),
                                  mv.backendLine);
    out.stages = mv.result.stages;
    out.mesh = std::move(mesh);
    return out;
}

} // namespace svo::app
