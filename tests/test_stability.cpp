// Stiff and extreme inputs through the GPU path, held against CGAL's exact
// reference. Set SVO_STABILITY_TABLE=path to also write the table that
// docs/stability.md shows.
#include <chrono>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <memory>

#include "stability_scenes.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/error.h"
#include "svo/gl/raster_voxelizer.h"
#include "svo/validate/classify.h"
#include "svo/validate/hole_check.h"

using namespace svo;

namespace {

struct Row {
    std::string group, name, grid, holes;
    size_t triangles = 0, voxels = 0, missed = 0, boundary = 0, extra = 0, missedExact = 0;
    size_t cpuMissed = 0, cpuExtra = 0;
    long eps0MissedExact = -1, bigEpsExtra = -1;
    int retries = 0;
    double eps = 0, ms = 0;
};

size_t countMissing(const std::vector<uint64_t>& want, const std::vector<uint64_t>& have)
{
    std::vector<uint64_t> d;
    std::set_difference(want.begin(), want.end(), have.begin(), have.end(), std::back_inserter(d));
    return d.size();
}

} // namespace

TEST(Stability, EveryAdversarialSceneIsExact)
{
    gl::Context context;
    std::vector<Row> rows;
    for (const auto& scene : test::stabilityScenes()) {
        SCOPED_TRACE(scene.name);
        const GridSpec grid = makeGrid(scene.mesh, scene.grid);
        Row r;
        r.group = scene.group;
        r.name = scene.name;
        r.triangles = scene.mesh.triangles.size();
        r.grid = scene.grid.resolution ? fmt::format("r {}", scene.grid.resolution)
                                       : fmt::format("h {:g}", scene.grid.voxelSize);
        r.eps = grid.epsilon();
        const auto t0 = std::chrono::steady_clock::now();
        RunStats report;
        const Octree gpu = gl::voxelizeToOctree(context, scene.mesh, grid, {}, &report);
        r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        ASSERT_TRUE(checkOctree(gpu).empty());
        const auto g = octreeKeys(gpu);
        r.voxels = g.size();
        {
            gl::RasterOptions compute;
            compute.pipeline = gl::Pipeline::Compute;
            EXPECT_EQ(octreeKeys(gl::voxelizeToOctree(context, scene.mesh, grid, compute)), g)
                << "the compute backend differs from the raster backend";
        }
        r.retries = report.overflowRetries;

        const auto ref = validate::exactReference(scene.mesh, grid, grid.epsilon());
        const auto c = validate::classify(scene.mesh, grid, g, ref, 3);
        r.missed = c.missed.size();
        r.boundary = c.boundary.size();
        r.extra = c.extra.size();
        const auto& exact = ref.exact; // the conservative set itself
        EXPECT_EQ(exact, validate::exactReference(scene.mesh, grid, 0.0).allowed); // E is A at epsilon 0
        r.missedExact = countMissing(exact, g);
        EXPECT_EQ(r.missed, 0u);
        EXPECT_EQ(r.extra, 0u);
        EXPECT_EQ(r.missedExact, 0u) << "the GPU lost a voxel the exact conservative set has";

        // The double-precision CPU reference sits between R and A too.
        const auto cpu = voxelizeCpu(scene.mesh, grid).keys;
        r.cpuMissed = countMissing(ref.required, cpu);
        r.cpuExtra = countMissing(cpu, ref.allowed);
        EXPECT_EQ(r.cpuMissed, 0u);
        EXPECT_EQ(r.cpuExtra, 0u);

        // What the guard band buys: none at all, and far too much (0.05 voxels).
        if (scene.group == "on the lattice" || scene.group == "placement" || scene.group == "axis ties") {
            gl::RasterOptions none, wide;
            none.guardBand = 0.0;
            wide.guardBand = 0.05;
            r.eps0MissedExact = long(countMissing(exact, octreeKeys(gl::voxelizeToOctree(context, scene.mesh, grid, none))));
            r.bigEpsExtra = long(countMissing(octreeKeys(gl::voxelizeToOctree(context, scene.mesh, grid, wide)), ref.allowed));
        }
        const auto h = validate::checkHoles(scene.mesh, grid, g);
        r.holes = h.applies ? (h.leak ? "LEAK" : "closed, no leak") : (h.reason.find("open") != std::string::npos ? "open" : "not a manifold");
        EXPECT_FALSE(h.leak);
        rows.push_back(r);
        std::printf("  %-16s %-42s %8zu voxels  missed %zu/%zu  band %zu  extra %zu  eps0 %ld  wide %ld  %s\n",
                    r.group.c_str(), r.name.c_str(), r.voxels, r.missed, r.missedExact, r.boundary, r.extra,
                    r.eps0MissedExact, r.bigEpsExtra, r.holes.c_str());
    }

    if (const char* path = std::getenv("SVO_STABILITY_TABLE")) {
        std::ofstream out(path);
        out << "| group | case | triangles | grid | ε (voxels) | voxels | missed (R) | missed (exact) | boundary | extra | "
               "CPU missed / extra | retries | holes | ε = 0: missed (exact) | ε = 0.05: extra |\n"
            << "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---|---:|---|---:|---:|\n";
        auto cell = [](std::string t) { // a '|' would end the markdown cell
            for (size_t i = 0; i < t.size(); ++i)
                if (t[i] == '|') t.insert(i++, 1, '\\');
            return t;
        };
        for (const auto& r : rows)
            out << fmt::format("| {} | {} | {} | {} | {:.2g} | {} | {} | {} | {} | {} | {} / {} | {} | {} | {} | {} |\n",
                               r.group, cell(r.name), r.triangles, r.grid, r.eps, r.voxels, r.missed, r.missedExact,
                               r.boundary, r.extra, r.cpuMissed, r.cpuExtra, r.retries, r.holes,
                               r.eps0MissedExact < 0 ? std::string("–") : std::to_string(r.eps0MissedExact),
                               r.bigEpsExtra < 0 ? std::string("–") : std::to_string(r.bigEpsExtra));
    }
}

TEST(Stability, EveryAdversarialSceneIsExactInThinMode)
{
    // The same scenes in thin mode: raster (shader dilation) and compute
    // agree, nothing of R or of the exact thin set E (CGAL segment tests) is
    // missed, nothing lies outside A, the CPU reference sits between R and A,
    // every thin voxel is a conservative one, and closed shells hold against
    // a 6-connected fill.
    gl::Context context;
    for (const auto& scene : test::stabilityScenes()) {
        SCOPED_TRACE(scene.name);
        const GridSpec grid = makeGrid(scene.mesh, scene.grid);
        gl::RasterOptions thin;
        thin.mode = VoxelMode::Thin;
        thin.conservative = gl::ConservativeMode::Shader;
        const auto g = octreeKeys(gl::voxelizeToOctree(context, scene.mesh, grid, thin));
        gl::RasterOptions compute = thin;
        compute.pipeline = gl::Pipeline::Compute;
        compute.conservative = gl::ConservativeMode::Auto;
        EXPECT_EQ(octreeKeys(gl::voxelizeToOctree(context, scene.mesh, grid, compute)), g)
            << "the compute backend differs from the raster backend";
        const auto ref = validate::exactReference(scene.mesh, grid, grid.epsilon(), VoxelMode::Thin);
        const auto c = validate::classify(scene.mesh, grid, g, ref, 3);
        EXPECT_EQ(c.missed.size(), 0u);
        EXPECT_EQ(c.missedExact.size(), 0u) << "the GPU lost a voxel the exact thin set has";
        EXPECT_EQ(c.extra.size(), 0u);
        const auto cpu = voxelizeCpu(scene.mesh, grid, 0.0, VoxelMode::Thin).keys;
        EXPECT_EQ(countMissing(ref.required, cpu), 0u);
        EXPECT_EQ(countMissing(cpu, ref.allowed), 0u);
        EXPECT_EQ(countMissing(g, octreeKeys(gl::voxelizeToOctree(context, scene.mesh, grid))), 0u)
            << "a thin voxel is not a conservative one";
        const auto h = validate::checkHoles(scene.mesh, grid, g, 6);
        EXPECT_FALSE(h.leak);
        std::printf("  %-16s %-42s %8zu thin voxels  missed %zu/%zu  band %zu  extra %zu  %s\n", scene.group.c_str(),
                    scene.name.c_str(), g.size(), c.missed.size(), c.missedExact.size(), c.boundary.size(),
                    c.extra.size(), h.applies ? (h.leak ? "LEAK" : "closed, no leak") : "not checked");
    }
}

TEST(Stability, BeyondTheLimitsIsAClearError)
{
    // One voxel past the largest grid the 21-bit keys address.
    const auto tri = test::soup("t", {{Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 1, 0}}});
    try {
        makeGrid(tri, {int64_t(kMaxGridDim), 0});
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("beyond the largest supported grid"), std::string::npos) << e.what();
    }
    // A grid that fits, with a triangle whose voxel list could not: refused
    // before anything is allocated, never truncated.
    gl::Context context;
    const auto huge = test::soup("huge", {{Vec3d{0, 0, 0}, Vec3d{1, 0.5, 0.2}, Vec3d{0.3, 1, 0.8}}});
    const GridSpec grid = makeGrid(huge, {int64_t(kMaxGridDim) - 16, 0});
    try {
        gl::voxelizeToOctree(context, huge, grid);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("use a coarser grid"), std::string::npos) << e.what();
    }
    // The compute backend counts one triangle's columns in 32 bits: a triangle
    // over more columns is refused before any GPU work, with what to do instead.
    gl::RasterOptions compute;
    compute.pipeline = gl::Pipeline::Compute;
    const auto flat = test::soup("flat", {{Vec3d{0, 0, 0}, Vec3d{1, 0, 0}, Vec3d{0, 1, 0}}});
    try {
        gl::voxelizeToOctree(context, flat, makeGrid(flat, {70000, 0}), compute);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("voxel columns, more than the compute backend counts"), std::string::npos)
            << e.what();
    }
}
