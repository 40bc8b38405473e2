// The GPU backends against the CPU reference on generated and real meshes:
// raster, and compute, which must keep exactly the raster backend's voxels.
#include <algorithm>
#include <array>
#include <cstdlib>
#include <gtest/gtest.h>
#include <memory>
#include <set>

#include "reference_check.h"
#include "scenes.h"
#include "svo/core/default_scene.h"
#include "svo/core/mesh_io.h"
#include "svo/gl/raster_voxelizer.h"

using namespace svo;

namespace {

class GpuVoxelize : public ::testing::Test {
protected:
    static void SetUpTestSuite() { context_ = std::make_unique<gl::Context>(); }
    static void TearDownTestSuite() { context_.reset(); }

    /// Voxelizes on the GPU and checks R <= G <= A; returns the counts.
    test::BandCounts check(const TriangleMesh& mesh, const GridRequest& req, const gl::RasterOptions& opt = {})
    {
        const GridSpec grid = makeGrid(mesh, req);
        RunStats report;
        const Voxelization g = gl::voxelizeRaster(*context_, mesh, grid, opt, &report);
        const auto c = test::compareToReference(mesh, g, opt.mode);
        if (opt.pipeline == gl::Pipeline::Raster && opt.conservative != gl::ConservativeMode::CentroidPush) {
            // The compute backend walks the same columns with the same test.
            gl::RasterOptions compute = opt;
            compute.pipeline = gl::Pipeline::Compute;
            RunStats computeReport;
            const Voxelization k = gl::voxelizeRaster(*context_, mesh, grid, compute, &computeReport);
            EXPECT_EQ(k.keys, g.keys) << mesh.source << ": the compute backend differs from the raster backend";
            // Entry for entry too, where the raster path gives each column one
            // fragment: NVIDIA's hardware conservative raster repeats some
            // (690 extra entries for 20,423 voxels of random triangles on an H100).
            if (std::string(gl::conservativeModeName(*context_, opt)) == "shader")
                EXPECT_EQ(computeReport.listEntries, report.listEntries) << mesh.source;
            else
                EXPECT_LE(computeReport.listEntries, report.listEntries) << mesh.source;
        }
        EXPECT_EQ(c.missed, 0u) << mesh.source;
        EXPECT_EQ(c.extra, 0u) << mesh.source;
        EXPECT_GT(c.got, 0u) << mesh.source;
        std::printf("  %-40s %-4s res/h %-8g voxels %9zu  band %6zu  eps %.2g  retries %d\n", mesh.source.c_str(),
                    opt.mode == VoxelMode::Thin ? "thin" : "", req.resolution ? double(req.resolution) : req.voxelSize,
                    c.got, c.band, grid.epsilon(), report.overflowRetries);
        return c;
    }

    /// Thin mode (shader dilation, so llvmpipe and NVIDIA run the same path),
    /// checked as check() does, and against the conservative voxels of the
    /// same grid, which must hold it. Returns (thin, conservative) voxel counts.
    std::pair<size_t, size_t> checkThin(const TriangleMesh& mesh, const GridRequest& req)
    {
        gl::RasterOptions thin;
        thin.mode = VoxelMode::Thin;
        thin.conservative = gl::ConservativeMode::Shader;
        check(mesh, req, thin);
        const GridSpec grid = makeGrid(mesh, req);
        const auto t = gl::voxelizeRaster(*context_, mesh, grid, thin).keys;
        const auto c = gl::voxelizeRaster(*context_, mesh, grid).keys;
        EXPECT_TRUE(std::includes(c.begin(), c.end(), t.begin(), t.end()))
            << mesh.source << ": a thin voxel is not a conservative one";
        return {t.size(), c.size()};
    }

    /// The voxels of a run as global index coordinates.
    static std::set<std::array<int64_t, 3>> globalVoxels(const Voxelization& v)
    {
        std::set<std::array<int64_t, 3>> out;
        for (uint64_t k : v.keys) out.insert(v.grid.toGlobal(unpackVoxelKey(k)));
        return out;
    }
    static std::unique_ptr<gl::Context> context_;
};
std::unique_ptr<gl::Context> GpuVoxelize::context_;

GridRequest res(int n) { return GridRequest{n, 0.0}; }
GridRequest size(double h) { return GridRequest{0, h}; }

} // namespace

TEST_F(GpuVoxelize, RandomTrianglesInManyOrientations)
{
    for (uint32_t seed : {1u, 2u, 3u}) check(test::randomTriangles(512, seed), size(1.0));
    // The same triangles at a finer grid, so each spans many voxels.
    check(test::randomTriangles(64, 7), size(0.125));
}

TEST_F(GpuVoxelize, CubeWithFacesOnVoxelBoundaries)
{
    // Faces at index +-4.5: exactly on the planes between voxels 4 and 5.
    const auto c = check(test::box({-4.5, -4.5, -4.5}, {4.5, 4.5, 4.5}), size(1.0));
    // Closed cubes touch on both sides of each face: 11^3 - 7^3 shell voxels.
    EXPECT_EQ(c.allowed, 11u * 11 * 11 - 7u * 7 * 7);
    EXPECT_EQ(c.got, c.allowed);
    // Faces through voxel centres.
    const auto d = check(test::box({-4, -4, -4}, {4, 4, 4}), size(1.0));
    EXPECT_EQ(d.got, 9u * 9 * 9 - 7u * 7 * 7);
}

TEST_F(GpuVoxelize, Sphere)
{
    const auto s = test::sphere({0.1, 0.2, 0.3}, 1.0, 64, 32);
    check(s, res(32));
    check(s, res(128));
}

TEST_F(GpuVoxelize, CornellBox)
{
    check(cornellBox(), res(64));
    check(cornellBox(), res(256));
}

namespace {
TriangleMesh oneTriangle(Vec3d a, Vec3d b, Vec3d c, const char* name)
{
    TriangleMesh m;
    m.positions = {a, b, c};
    m.triangles = {{0, 1, 2}};
    m.source = name;
    return m;
}
} // namespace

// One triangle whose column box needs more than 65,535 chunks of 64 columns
// (2047^2 / 64 = 65,473 at 2046; llvmpipe stops any loop after 65,535
// iterations): the compute backend once queued a triangle's chunks in one
// shader loop and lost the rest past the driver's budget.
TEST_F(GpuVoxelize, ATriangleOfMoreChunksThanTheLoopLimitKeepsEveryVoxel)
{
    const auto c = check(oneTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "right triangle"), res(2047));
    EXPECT_GT(c.got, 2047u * 2048 / 2);
}

// Needles and slivers across the grid: their normal is rounding, so their
// columns run along the axis their longest edge crosses least, a few voxels
// each, and the raster path draws them as a box along the edge, not their
// bounding box. Before, each of the diagonal needle's 1025^2 columns walked
// the whole grid (17.8 s on llvmpipe at 1024, and the compute backend lost
// 4,827 of 7,169 voxels past the loop budget).
TEST_F(GpuVoxelize, NeedlesAndSliversKeepEveryVoxel)
{
    check(oneTriangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, "diagonal needle"), res(1024));
    check(oneTriangle({0, 0, 0}, {2, 1, 0.5}, {1, 0.5, 0.25}, "needle, middle corner"), res(4096));
    check(oneTriangle({0, 0, 0}, {2, 1, 0.5}, {1, 0.5, 0.25 + 1e-6}, "sliver"), res(4096));
    check(oneTriangle({0, 0, 0}, {0, 0, 1}, {0, 0, 2}, "needle along z"), res(2048));
    check(oneTriangle({0.3, 0.3, 0.3}, {0.3, 0.3, 0.3}, {0.3, 0.3, 0.3}, "point"), size(1.0));
    gl::RasterOptions thin;
    thin.mode = VoxelMode::Thin;
    thin.conservative = gl::ConservativeMode::Shader;
    check(oneTriangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, "diagonal needle"), res(512), thin);
}

TEST_F(GpuVoxelize, ShaderAndHardwareDilationAgree)
{
    if (!context_->info().conservativeRasterNV) GTEST_SKIP() << "no GL_NV_conservative_raster on this device";
    gl::RasterOptions shader, hardware;
    shader.conservative = gl::ConservativeMode::Shader;
    hardware.conservative = gl::ConservativeMode::Hardware;
    const auto mesh = cornellBox();
    const GridSpec grid = makeGrid(mesh, res(96));
    const auto a = gl::voxelizeRaster(*context_, mesh, grid, shader);
    const auto b = gl::voxelizeRaster(*context_, mesh, grid, hardware);
    EXPECT_EQ(a.keys, b.keys);
}

TEST_F(GpuVoxelize, OverflowTriggersExactlyOneRetry)
{
    gl::RasterOptions tiny;
    tiny.initialCapacity = 16;
    const auto mesh = test::sphere({0, 0, 0}, 1.0, 32, 16);
    const GridSpec grid = makeGrid(mesh, res(64));
    RunStats smallReport, normalReport;
    const auto small = gl::voxelizeRaster(*context_, mesh, grid, tiny, &smallReport);
    const auto normal = gl::voxelizeRaster(*context_, mesh, grid, {}, &normalReport);
    EXPECT_EQ(smallReport.overflowRetries, 1);
    EXPECT_EQ(normalReport.overflowRetries, 0);
    EXPECT_EQ(small.keys, normal.keys);
}

#ifdef SVO_CGAL_MESHES
TEST_F(GpuVoxelize, RealMeshesFromCgalData)
{
    // SVO_CGAL_MESHES in the environment overrides the build's path (for a bundle run elsewhere).
    const char* env = std::getenv("SVO_CGAL_MESHES");
    const std::string dir = env && *env ? env : SVO_CGAL_MESHES;
    for (const char* name : {"elephant.off", "fandisk.off", "knot1.off", "cow.off"})
        for (int r : {32, 100, 256}) check(loadMesh(dir + "/" + name), res(r));
}
#endif

TEST_F(GpuVoxelize, ThinModeOnEveryScene)
{
    // The scenes above, in thin mode: raster (shader dilation) and compute
    // against the CPU reference's thin sets, and inside the conservative voxels.
    for (uint32_t seed : {1u, 2u, 3u}) {
        const auto [thin, conservative] = checkThin(test::randomTriangles(512, seed), size(1.0));
        EXPECT_LT(thin, conservative); // slanted triangles: thin keeps fewer
    }
    checkThin(test::randomTriangles(64, 7), size(0.125));
    checkThin(test::box({-4.5, -4.5, -4.5}, {4.5, 4.5, 4.5}), size(1.0));
    checkThin(test::box({-4, -4, -4}, {4, 4, 4}), size(1.0));
    const auto s = test::sphere({0.1, 0.2, 0.3}, 1.0, 64, 32);
    checkThin(s, res(32));
    checkThin(s, res(128));
    checkThin(cornellBox(), res(64));
    checkThin(cornellBox(), res(256));
#ifdef SVO_CGAL_MESHES
    const char* env = std::getenv("SVO_CGAL_MESHES");
    const std::string dir = env && *env ? env : SVO_CGAL_MESHES;
    for (const char* name : {"elephant.off", "fandisk.off", "knot1.off", "cow.off"})
        for (int r : {32, 100, 256}) checkThin(loadMesh(dir + "/" + name), res(r));
#endif
}

TEST_F(GpuVoxelize, ThinSlantedPlaneKeepsOneVoxelPerColumn)
{
    // The quad z = x/2 + 0.3 over x, y in [0.1, 11.9] x [0.1, 7.9], voxel
    // size 1, so index = world. Worked by hand:
    // - a voxel's z segment at (i, j) meets the quad when i in 1..11, j in
    //   1..7 and |i/2 + 0.3 - k| <= 1/2: k = i/2 for even i (0.3 away),
    //   (i+1)/2 for odd i (0.2 away), one voxel per column;
    // - its x segment (height k) meets the plane at x = 2k - 0.6, inside
    //   [i - 1/2, i + 1/2] only for i = 2k - 1, the voxel found above;
    // - its y segment (x = i, z = k) would need i/2 + 0.3 = k, never so.
    // The conservative cube meets the plane when |i/2 + 0.3 - k| <= 3/4:
    // k = i/2 and i/2 + 1 for even i (0.3 and 0.7 away), only (i+1)/2 for odd
    // i (0.2; the others 0.8 and 1.2), for columns whose cube lies over the
    // quad (i in 1..11, j in 1..7). Nothing here is within 0.05 of touching.
    TriangleMesh quad;
    quad.source = "slanted quad";
    quad.positions = {{0.1, 0.1, 0.35}, {11.9, 0.1, 6.25}, {11.9, 7.9, 6.25}, {0.1, 7.9, 0.35}};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    const GridSpec grid = makeGrid(quad, size(1.0));
    std::set<std::array<int64_t, 3>> thin, conservativeInside;
    for (int64_t i = 1; i <= 11; ++i)
        for (int64_t j = 1; j <= 7; ++j) {
            thin.insert({i, j, (i + 1) / 2});
            conservativeInside.insert({i, j, (i + 1) / 2});
            if (i % 2 == 0) conservativeInside.insert({i, j, i / 2 + 1});
        }
    for (const auto pipeline : {gl::Pipeline::Raster, gl::Pipeline::Compute}) {
        gl::RasterOptions o;
        o.pipeline = pipeline;
        o.conservative = pipeline == gl::Pipeline::Raster ? gl::ConservativeMode::Shader : gl::ConservativeMode::Auto;
        o.mode = VoxelMode::Thin;
        EXPECT_EQ(globalVoxels(gl::voxelizeRaster(*context_, quad, grid, o)), thin);
        // Conservative, in the columns whose cubes lie over the quad.
        o.mode = VoxelMode::Conservative;
        std::set<std::array<int64_t, 3>> inside;
        for (const auto& v : globalVoxels(gl::voxelizeRaster(*context_, quad, grid, o)))
            if (v[0] >= 1 && v[0] <= 11 && v[1] >= 1 && v[1] <= 7) inside.insert(v);
        EXPECT_EQ(inside, conservativeInside);
    }
    EXPECT_EQ(globalVoxels(voxelizeCpu(quad, grid, 0.0, VoxelMode::Thin)), thin);
}

TEST_F(GpuVoxelize, ThinFlatPlaneKeepsOnlyColumnsOverIt)
{
    // The square z = 0.3, x and y in [0.1, 3.9]: both modes keep one layer,
    // k = 0. The conservative cubes of columns 0..4 reach it (5 x 5); a thin
    // voxel needs its z segment, at (i, j), over the square: columns 1..3
    // (3 x 3). Its x and y segments lie at z = 0, below the square.
    TriangleMesh square;
    square.source = "flat square";
    square.positions = {{0.1, 0.1, 0.3}, {3.9, 0.1, 0.3}, {3.9, 3.9, 0.3}, {0.1, 3.9, 0.3}};
    square.triangles = {{0, 1, 2}, {0, 2, 3}};
    const GridSpec grid = makeGrid(square, size(1.0));
    std::set<std::array<int64_t, 3>> thin, conservative;
    for (int64_t i = 0; i <= 4; ++i)
        for (int64_t j = 0; j <= 4; ++j) {
            conservative.insert({i, j, 0});
            if (i >= 1 && i <= 3 && j >= 1 && j <= 3) thin.insert({i, j, 0});
        }
    for (const auto pipeline : {gl::Pipeline::Raster, gl::Pipeline::Compute}) {
        gl::RasterOptions o;
        o.pipeline = pipeline;
        o.mode = VoxelMode::Thin;
        EXPECT_EQ(globalVoxels(gl::voxelizeRaster(*context_, square, grid, o)), thin);
        o.mode = VoxelMode::Conservative;
        EXPECT_EQ(globalVoxels(gl::voxelizeRaster(*context_, square, grid, o)), conservative);
    }
}

TEST(GlContext, HeadlessCoreContextReportsItself)
{
    gl::Context context;
    const auto& info = context.info();
    EXPECT_FALSE(info.renderer.empty());
    EXPECT_FALSE(info.vendor.empty());
    EXPECT_EQ(info.version.rfind("4.", 0), 0u) << info.version; // the constructor refuses anything below 4.5
    EXPECT_GE(info.maxViewport, 16384);                          // GL 4.5's minimum framebuffer size
    EXPECT_FALSE(info.eglDevice.empty());
    std::printf("  %s | %s | %s | %s\n", info.eglDevice.c_str(), info.vendor.c_str(), info.renderer.c_str(),
                info.version.c_str());
}
