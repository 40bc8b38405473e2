// The GPU backends against the CPU reference on generated and real meshes:
// raster, and compute, which must keep exactly the raster backend's voxels.
#include <cstdlib>
#include <gtest/gtest.h>
#include <memory>

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
        const Voxelization g = gl::voxelizeRaster(*context_, mesh, grid, opt);
        const auto c = test::compareToReference(mesh, g);
        if (opt.pipeline == gl::Pipeline::Raster && opt.conservative != gl::ConservativeMode::CentroidPush) {
            // The compute backend walks the same columns with the same test.
            gl::RasterOptions compute = opt;
            compute.pipeline = gl::Pipeline::Compute;
            const Voxelization k = gl::voxelizeRaster(*context_, mesh, grid, compute);
            EXPECT_EQ(k.keys, g.keys) << mesh.source << ": the compute backend differs from the raster backend";
            // Entry for entry too, where the raster path gives each column one
            // fragment: NVIDIA's hardware conservative raster repeats some
            // (690 extra entries for 20,423 voxels of random triangles on an H100).
            if (std::string(gl::conservativeModeName(*context_, opt)) == "shader")
                EXPECT_EQ(k.listEntries, g.listEntries) << mesh.source;
            else
                EXPECT_LE(k.listEntries, g.listEntries) << mesh.source;
        }
        EXPECT_EQ(c.missed, 0u) << mesh.source;
        EXPECT_EQ(c.extra, 0u) << mesh.source;
        EXPECT_GT(c.got, 0u) << mesh.source;
        std::printf("  %-40s res/h %-8g voxels %9zu  band %6zu  eps %.2g  retries %d\n", mesh.source.c_str(),
                    req.resolution ? double(req.resolution) : req.voxelSize, c.got, c.band, grid.epsilon(),
                    g.overflowRetries);
        return c;
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
    const auto small = gl::voxelizeRaster(*context_, mesh, grid, tiny);
    const auto normal = gl::voxelizeRaster(*context_, mesh, grid);
    EXPECT_EQ(small.overflowRetries, 1);
    EXPECT_EQ(normal.overflowRetries, 0);
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
