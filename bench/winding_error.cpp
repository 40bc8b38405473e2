// Error against GPU time for winding-number signs: solids of one mesh at one
// resolution for several accuracies (beta), each against the solid with every
// triangle evaluated exactly (beta = infinity), medians of a few runs.
//   svo-bench-winding MESH --res 256 512 --beta 1 1.5 2 3 4 [--reference-beta inf] --runs 3 --md out.md
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <openvdb/tools/Count.h>

#include "svo/core/atomic_file.h"
#include "svo/core/mesh_io.h"
#include "svo/svo.h"

namespace {

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

/// GPU milliseconds of the winding passes (per brick and per voxel).
double windingGpuMs(const svo::VoxelizeStats& s)
{
    double ms = 0;
    for (const auto& st : s.stages)
        if (st.name.rfind("winding per", 0) == 0) ms += st.gpuMs;
    return ms;
}

double totalWallMs(const svo::VoxelizeStats& s)
{
    double ms = 0;
    for (const auto& st : s.stages) ms += st.wallMs;
    return ms;
}

/// Active voxels in exactly one of the two solids.
uint64_t differing(const openvdb::MaskGrid& a, const openvdb::MaskGrid& b)
{
    auto x = a.deepCopy();
    x->tree().topologyDifference(b.tree());
    auto y = b.deepCopy();
    y->tree().topologyDifference(a.tree());
    return x->activeVoxelCount() + y->activeVoxelCount();
}

} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"svo winding-number benchmark: error against GPU time over beta"};
    std::string meshPath, mdPath;
    std::vector<int> resolutions{256, 512};
    std::vector<double> betas{1, 1.5, 2, 3, 4};
    int runs = 3;
    double reference = std::numeric_limits<double>::infinity();
    app.add_option("mesh", meshPath, "Mesh file")->required();
    app.add_option("--res", resolutions, "Resolutions");
    app.add_option("--beta", betas, "Accuracies to time against beta = infinity");
    app.add_option("--runs", runs, "Runs per point (median)")->check(CLI::PositiveNumber);
    app.add_option("--reference-beta", reference, "The accuracy the others are compared with (default inf: every "
                                                  "triangle exact)");
    app.add_option("--md", mdPath, "Markdown table to write");
    CLI11_PARSE(app, argc, argv);
    try {
        openvdb::initialize();
        const svo::TriangleMesh mesh = svo::loadMesh(meshPath);
        svo::Voxelizer v;
        std::string md = fmt::format("Mesh {} ({} triangles), on {}. Solids with winding-number signs; error = "
                                     "voxels whose side differs from beta = {} ({}).\n\n"
                                     "| grid | beta | winding GPU ms | call wall ms | differing voxels | of solid |\n"
                                     "|---|---|---|---|---|---|\n",
                                     mesh.source, mesh.triangles.size(), v.deviceDescription(), reference,
                                     std::isinf(reference) ? "every triangle exact" : "the reference");
        for (int r : resolutions) {
            const svo::GridSpec grid = svo::makeGrid(mesh, svo::GridRequest{r, 0});
            std::vector<double> all = betas;
            all.push_back(reference);
            std::vector<openvdb::MaskGrid::Ptr> solids;
            std::vector<double> gpu, wall;
            for (double beta : all) {
                std::vector<double> g, w;
                openvdb::MaskGrid::Ptr solid;
                for (int i = 0; i < runs + 1; ++i) { // the first run warms up
                    svo::VoxelizeStats stats;
                    svo::VoxelizeOptions o;
                    o.stats = &stats;
                    solid = v.solid(mesh, grid, o, svo::SignOptions(svo::SignMethod::Winding, beta));
                    if (i) g.push_back(windingGpuMs(stats)), w.push_back(totalWallMs(stats));
                }
                solids.push_back(solid);
                gpu.push_back(median(g));
                wall.push_back(median(w));
            }
            const auto& exact = *solids.back();
            for (size_t i = 0; i < all.size(); ++i) {
                const uint64_t diff = differing(*solids[i], exact);
                const std::string line =
                    fmt::format("| {}³ | {} | {:.2f} | {:.1f} | {} | {:.2e} |\n", r,
                                std::isinf(all[i]) ? std::string("inf") : fmt::format("{}", all[i]), gpu[i], wall[i],
                                diff, double(diff) / double(exact.activeVoxelCount()));
                fmt::print("{}", line);
                md += line;
            }
        }
        if (!mdPath.empty()) svo::writeFileAtomically(mdPath, md);
    } catch (const std::exception& e) {
        fmt::print(stderr, "svo-bench-winding: {}\n", e.what());
        return 1;
    }
    return 0;
}
