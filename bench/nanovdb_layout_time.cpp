// The host path's NanoVDB build, before and after issue 45, on the same data:
// an OpenVDB grid (grid_builder.h, field_grids.h) then nanovdb::openToNanoVDB
// (toNanoVdb), against the layout written from the bricks (nanovdb_grids.h).
// File writes are left out: both give grids of the same size.
//   svo-bench-nanovdb-layout MESH|icosphere [--res 256 512] [--runs 5] [--backend cpu|gpu]
// Prints one Markdown row per mesh, resolution and kind: medians in ms.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "svo/core/default_scene.h"
#include "svo/core/mesh_io.h"
#include "svo/gl/device.h"
#include "svo/gl/field_pipeline.h"
#include "svo/gl/voxelize_pipeline.h"
#include "svo/vdb_io/field_grids.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/nanovdb_grids.h"
#include "svo/vdb_io/nanovdb_output.h"

namespace {

using Clock = std::chrono::steady_clock;

template <typename F>
double medianMs(int runs, F&& f)
{
    std::vector<double> ms;
    f(); // warm-up
    for (int r = 0; r < runs; ++r) {
        const auto t0 = Clock::now();
        f();
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

} // namespace

int main(int argc, char** argv)
{
    using namespace svo;
    std::string mesh = "icosphere";
    std::vector<int64_t> res;
    int runs = 5;
    Backend backend = Backend::Cpu;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--res") {
            while (i + 1 < argc && argv[i + 1][0] != '-') res.push_back(std::atoll(argv[++i]));
        } else if (a == "--runs" && i + 1 < argc) {
            runs = std::atoi(argv[++i]);
        } else if (a == "--backend" && i + 1 < argc) {
            backend = std::string(argv[++i]) == "gpu" ? Backend::Compute : Backend::Cpu;
        } else {
            mesh = a;
        }
    }
    if (res.empty()) res = {128, 256};
    openvdb::initialize();
    const TriangleMesh m = mesh == "icosphere" ? icosphere({0, 0, 0}, 1.0, 6) : loadMesh(mesh);
    gl::Device device;
    fmt::print("| mesh | N | kind | voxels | OpenVDB + openToNanoVDB ms | layout ms | gain | layout without checksum ms |\n"
               "|---|---|---|---|---|---|---|---|\n");
    for (const int64_t n : res) {
        const GridSpec grid = makeGrid(m, {n, 0.0});
        VoxelizeSettings s;
        s.backend = backend;
        VoxelizeStats stats;
        auto row = [&](const char* kind, uint64_t voxels, double before, double after, double bare) {
            fmt::print("| {} | {} | {} | {} | {:.1f} | {:.1f} | {:.2f}× | {:.1f} |\n", mesh, n, kind, voxels, before, after,
                       before / after, bare);
        };
        const Octree oct = gl::voxelizeMesh(device, m, grid, s, Checkpoint{}, stats);
        GridOptions g;
        g.fog = true;
        const double surfBefore = medianMs(runs, [&] {
            for (const auto& vg : vdb::octreeToGrids(oct, g)) vdb::toNanoVdb(vg);
        });
        const double surfAfter = medianMs(runs, [&] { vdb::octreeToNanoGrids(oct, g); });
        const double surfBare = medianMs(runs, [&] { vdb::octreeToNanoGrids(oct, g, false); });
        row("surface + fog", vdb::octreeToNanoGrids(oct, g).front().gridMetaData()->activeVoxelCount(), surfBefore, surfAfter,
            surfBare);
        for (const bool udf : {true, false}) {
            LevelSetOptions ls;
            ls.unsignedDistance = udf;
            const DistanceBricks f = gl::levelSetBricks(device, m, grid, ls, s, Checkpoint{}, stats);
            const auto xform = vdb::makeTransform(grid);
            const double before = medianMs(runs, [&] {
                for (const auto& vg : vdb::levelSetGrids(f, ls.exteriorBand, ls.interiorBand, grid.voxelSize, xform))
                    vdb::toNanoVdb(vg);
            });
            const double after = medianMs(runs, [&] { vdb::levelSetNanoGrids(f, ls.exteriorBand, ls.interiorBand, grid); });
            const double bare = medianMs(runs, [&] { vdb::levelSetNanoGrids(f, ls.exteriorBand, ls.interiorBand, grid, false); });
            row(udf ? "udf band 3" : "sdf band 3",
                vdb::levelSetNanoGrids(f, ls.exteriorBand, ls.interiorBand, grid).front().gridMetaData()->activeVoxelCount(),
                before, after, bare);
        }
    }
    return 0;
}
