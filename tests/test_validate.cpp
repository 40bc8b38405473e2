// svo validate's parts: the exact CGAL reference, the classification, and the
// hole check, on planted errors and on the GPU's own output.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <memory>
#include <random>

#include "scenes.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/mesh_io.h"
#include "svo/core/voxel_key.h"
#include "svo/gl/raster_voxelizer.h"
#include "svo/validate/classify.h"
#include "svo/validate/hole_check.h"
#include "svo/validate/report.h"

using namespace svo;

namespace {

bool includes(const std::vector<uint64_t>& big, const std::vector<uint64_t>& small)
{
    return std::includes(big.begin(), big.end(), small.begin(), small.end());
}

class Validate : public ::testing::Test {
protected:
    static void SetUpTestSuite() { context_ = std::make_unique<gl::Context>(); }
    static void TearDownTestSuite() { context_.reset(); }
    static std::vector<uint64_t> gpuVoxels(const TriangleMesh& mesh, const GridSpec& grid,
                                           VoxelMode mode = VoxelMode::Conservative)
    {
        gl::RasterOptions o;
        o.mode = mode;
        return octreeKeys(gl::voxelizeToOctree(*context_, mesh, grid, o));
    }
    static std::unique_ptr<gl::Context> context_;
};
std::unique_ptr<gl::Context> Validate::context_;

} // namespace

TEST(ExactReference, BracketsTheCpuReference)
{
    // Two independent computations: CGAL's exact tests and the shared overlap
    // test in double. R (shrunk) <= CPU <= A (grown).
    for (const auto& mesh : {test::randomTriangles(300, 11), test::sphere({0.3, 0.1, 0.2}, 1.0, 40, 20)}) {
        const GridSpec grid = makeGrid(mesh, {0, mesh.source == "random triangles" ? 1.0 : 0.05});
        const auto ref = validate::exactReference(mesh, grid, grid.epsilon());
        const auto cpu = voxelizeCpu(mesh, grid).keys;
        EXPECT_TRUE(includes(cpu, ref.required)) << mesh.source;
        EXPECT_TRUE(includes(ref.allowed, cpu)) << mesh.source;
        EXPECT_TRUE(includes(ref.allowed, ref.required));
        EXPECT_GT(ref.required.size(), 1000u);
    }
}

TEST(ExactReference, DegenerateTrianglesCoverWhatTheyTouch)
{
    TriangleMesh m;
    m.source = "degenerate";
    // A needle from (0.2,0.2,0.2) to (5.2,0.2,0.2) listed with its middle point
    // last, and a point triangle at (3,3,3) on voxel corners... of 8 voxels? No:
    // index (3,3,3) is a voxel centre, so it covers exactly that voxel.
    m.positions = {{0.2, 0.2, 0.2}, {5.2, 0.2, 0.2}, {2.7, 0.2, 0.2}, {3.5, 3.5, 3.5}};
    m.triangles = {{0, 2, 1}, {3, 3, 3}};
    GridSpec grid = makeGrid(m, {0, 1.0});
    const auto ref = validate::exactReference(m, grid, 0.0);
    EXPECT_EQ(ref.degenerate, 2u);
    // The needle covers voxels x = 0..5 of row (0,0); the point (3.5,3.5,3.5)
    // sits on a corner shared by 8 voxels.
    EXPECT_EQ(ref.allowed.size(), 6u + 8u);
    EXPECT_EQ(ref.required, ref.allowed);
}

TEST(ExactReference, ThinBracketsTheCpuReferenceAndLiesInsideTheConservativeSets)
{
    // CGAL's exact segment tests against the shared thin test in double:
    // R <= CPU <= A, and each thin set inside the conservative set of its name.
    for (const auto& mesh : {test::randomTriangles(300, 11), test::sphere({0.3, 0.1, 0.2}, 1.0, 40, 20)}) {
        const GridSpec grid = makeGrid(mesh, {0, mesh.source == "random triangles" ? 1.0 : 0.05});
        const auto thin = validate::exactReference(mesh, grid, grid.epsilon(), VoxelMode::Thin);
        const auto cube = validate::exactReference(mesh, grid, grid.epsilon(), VoxelMode::Conservative);
        const auto cpu = voxelizeCpu(mesh, grid, 0.0, VoxelMode::Thin).keys;
        EXPECT_TRUE(includes(cpu, thin.required)) << mesh.source;
        EXPECT_TRUE(includes(thin.allowed, cpu)) << mesh.source;
        EXPECT_TRUE(includes(thin.exact, thin.required));
        EXPECT_TRUE(includes(thin.allowed, thin.exact));
        EXPECT_TRUE(includes(cube.required, thin.required));
        EXPECT_TRUE(includes(cube.exact, thin.exact));
        EXPECT_TRUE(includes(cube.allowed, thin.allowed));
        EXPECT_LT(thin.exact.size(), cube.exact.size()) << mesh.source;
        EXPECT_GT(thin.required.size(), 1000u);
    }
}

TEST(ExactReference, ThinEqualsTheCpuReferenceOnSnappedCoordinates)
{
    // Corners on a 1/4 grid, voxel size 1: double arithmetic is exact, so the
    // CPU reference's thin test must give CGAL's exact thin set E, segment
    // ends and edges along segments included; needles and points too.
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> u(0, 40), d(-6, 6);
    TriangleMesh m;
    m.source = "snapped triangles";
    for (uint32_t t = 0; t < 400; ++t) {
        const Vec3d a{u(rng) * 0.25, u(rng) * 0.25, u(rng) * 0.25};
        Vec3d b = a + Vec3d{d(rng) * 0.25, d(rng) * 0.25, d(rng) * 0.25};
        Vec3d c = a + Vec3d{d(rng) * 0.25, d(rng) * 0.25, d(rng) * 0.25};
        if (t % 3 == 0) b.z = c.z = a.z; // axis-aligned planes
        if (t % 7 == 1) c = a + 0.5 * (b - a); // needles
        if (t % 11 == 2) b = c = a;            // points
        m.positions.insert(m.positions.end(), {a, b, c});
        m.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    const GridSpec grid = makeGrid(m, {0, 1.0});
    const auto ref = validate::exactReference(m, grid, 0.0, VoxelMode::Thin);
    EXPECT_GT(ref.degenerate, 40u);
    const auto cpu = voxelizeCpu(m, grid, 0.0, VoxelMode::Thin).keys;
    EXPECT_EQ(cpu, ref.exact);
    EXPECT_EQ(ref.exact, ref.allowed); // epsilon 0: one set
    // The shortened segments (epsilon 0.01) miss the triangles that only touch an end.
    const auto shrunk = validate::exactReference(m, grid, 0.01, VoxelMode::Thin);
    EXPECT_LT(shrunk.required.size(), shrunk.exact.size());
    EXPECT_EQ(shrunk.exact, ref.exact);
}

TEST_F(Validate, ThinPassesOnRealMeshesAndFailsWithoutAVoxel)
{
#ifdef SVO_CGAL_MESHES
    const std::string dir = std::getenv("SVO_CGAL_MESHES") ? std::getenv("SVO_CGAL_MESHES") : SVO_CGAL_MESHES;
    for (const char* name : {"elephant.off", "knot1.off"})
        for (int res : {64, 160}) {
            const TriangleMesh mesh = loadMesh(dir + "/" + name);
            const GridSpec grid = makeGrid(mesh, {res, 0});
            const auto g = gpuVoxels(mesh, grid, VoxelMode::Thin);
            validate::ReportOptions options;
            options.mode = VoxelMode::Thin;
            const auto report = validate::validateVoxelization(mesh, buildOctree(grid, g), g, options);
            EXPECT_TRUE(report.passed) << name << " " << res << ": " << report.reason;
            EXPECT_TRUE(report.holes.applies) << report.holes.reason;
            EXPECT_EQ(report.holes.connectivity, 6);
            EXPECT_TRUE(report.classification.extra.empty());

            // One voxel of the exact thin set removed: the verdict fails and names it.
            const auto ref = validate::exactReference(mesh, grid, grid.epsilon(), VoxelMode::Thin);
            const uint64_t victim = ref.exact[ref.exact.size() / 2];
            auto removed = g;
            removed.erase(std::find(removed.begin(), removed.end(), victim));
            options.holes = false;
            const auto bad = validate::validateVoxelization(mesh, buildOctree(grid, removed), removed, options);
            EXPECT_FALSE(bad.passed);
            EXPECT_EQ(bad.classification.missedExact, std::vector<uint64_t>{victim});
            EXPECT_NE(bad.reason.find("exact thin set"), std::string::npos) << bad.reason;

            // Held to the conservative sets, a thin voxelization misses voxels.
            options.mode = VoxelMode::Conservative;
            const auto asCube = validate::validateVoxelization(mesh, buildOctree(grid, g), g, options);
            EXPECT_FALSE(asCube.passed);
            EXPECT_GT(asCube.classification.missed.size(), g.size() / 4) << name;
            std::printf("  %-14s %4d thin voxels %8zu boundary %5zu (conservative would miss %zu)\n", name, res,
                        g.size(), report.classification.boundary.size(), asCube.classification.missed.size());
        }
#else
    GTEST_SKIP() << "libcgal-demo's meshes were not found at configure time";
#endif
}

TEST_F(Validate, ThinShellIsClosedOnlyFor6ConnectedFills)
{
    // A thin voxelization of a closed sphere walls the inside off from
    // 6-connected paths, the connectivity svo validate uses for it, but not
    // from 26-connected ones: diagonal steps pass between its voxels.
    const auto mesh = test::icosphere({0.05, 0.1, 0.15}, 1.0, 4);
    const GridSpec grid = makeGrid(mesh, {40, 0});
    const auto thin = gpuVoxels(mesh, grid, VoxelMode::Thin);
    const auto six = validate::checkHoles(mesh, grid, thin, 6);
    ASSERT_TRUE(six.applies) << six.reason;
    EXPECT_FALSE(six.leak);
    EXPECT_TRUE(validate::checkHoles(mesh, grid, thin, 26).leak);
    // And one voxel cut where the shell crosses an axis opens it to 6-connected fills too.
    auto cut = thin;
    const Vec3d top = grid.toLocal({0.05, 0.1, 1.15});
    const int64_t i = std::lround(top.x), j = std::lround(top.y);
    const size_t before = cut.size();
    cut.erase(std::remove_if(cut.begin(), cut.end(),
                             [&](uint64_t k) {
                                 const auto p = unpackVoxelKey(k);
                                 return int64_t(p[0]) == i && int64_t(p[1]) == j && double(p[2]) > top.z - 3;
                             }),
              cut.end());
    ASSERT_LT(cut.size(), before);
    EXPECT_TRUE(validate::checkHoles(mesh, grid, cut, 6).leak);
}

TEST_F(Validate, PlantedErrorsAreCaught)
{
    const auto mesh = test::icosphere({0, 0, 0}, 1.0, 4);
    const GridSpec grid = makeGrid(mesh, {40, 0});
    const auto ref = validate::exactReference(mesh, grid, grid.epsilon());
    std::vector<uint64_t> g = gpuVoxels(mesh, grid);
    auto c = validate::classify(mesh, grid, g, ref);
    ASSERT_TRUE(c.missed.empty());
    ASSERT_TRUE(c.extra.empty());

    // Remove one required voxel: missed = 1, and it is the worst case.
    auto removed = g;
    const uint64_t victim = ref.required[ref.required.size() / 2];
    removed.erase(std::find(removed.begin(), removed.end(), victim));
    c = validate::classify(mesh, grid, removed, ref);
    EXPECT_EQ(c.missed, std::vector<uint64_t>{victim});
    ASSERT_EQ(c.worstMissed.size(), 1u);
    EXPECT_EQ(c.worstMissed[0].index, grid.toGlobal(unpackVoxelKey(victim)));
    EXPECT_LT(c.worstMissed[0].distance, 0.87); // within half a diagonal of the surface
    EXPECT_GE(c.worstMissed[0].triangle, 0);

    // Add the voxel at the sphere's centre: extra = 1, about a radius away.
    const Vec3d centre = grid.toLocal({0, 0, 0});
    const uint64_t far = packVoxelKey(uint32_t(std::lround(centre.x)), uint32_t(std::lround(centre.y)),
                                      uint32_t(std::lround(centre.z)));
    auto added = g;
    added.insert(std::lower_bound(added.begin(), added.end(), far), far);
    c = validate::classify(mesh, grid, added, ref);
    EXPECT_EQ(c.extra, std::vector<uint64_t>{far});
    ASSERT_EQ(c.worstExtra.size(), 1u);
    EXPECT_NEAR(c.worstExtra[0].distance, 20.0, 1.0); // radius 1 at 40 voxels per diameter

    // The intact shell is closed; cut the voxels on one ray from the centre and it leaks.
    const auto ok = validate::checkHoles(mesh, grid, g);
    ASSERT_TRUE(ok.applies) << ok.reason;
    EXPECT_FALSE(ok.leak);
    auto cut = g;
    const auto cc = unpackVoxelKey(far);
    cut.erase(std::remove_if(cut.begin(), cut.end(),
                             [&](uint64_t k) {
                                 const auto p = unpackVoxelKey(k);
                                 return p[1] == cc[1] && p[2] == cc[2] && p[0] > cc[0];
                             }),
              cut.end());
    ASSERT_LT(cut.size(), g.size());
    const auto leak = validate::checkHoles(mesh, grid, cut);
    EXPECT_TRUE(leak.leak);
    ASSERT_GE(leak.leakPath.size(), 2u);
    // The path starts outside the grid's voxels and ends at a voxel inside the sphere.
    const auto& last = leak.leakPath.back();
    const Vec3d lastWorld{double(last[0]) * grid.voxelSize, double(last[1]) * grid.voxelSize,
                          double(last[2]) * grid.voxelSize};
    EXPECT_LT(std::sqrt(lastWorld.x * lastWorld.x + lastWorld.y * lastWorld.y + lastWorld.z * lastWorld.z), 1.0);
    for (size_t i = 1; i < leak.leakPath.size(); ++i)
        for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(leak.leakPath[i][a] - leak.leakPath[i - 1][a]), 1);
}

TEST_F(Validate, AVoxelThatOnlyTouchesIsStillRequired)
{
    // Faces on voxel planes (x = ±4.5 between voxels 4 and 5): the voxels on
    // both sides touch a face only on their boundary, so they are in the exact
    // conservative set E but not in R (cubes shrunk by epsilon).
    const auto box = test::box({-4.5, -4.5, -4.5}, {4.5, 4.5, 4.5});
    const GridSpec grid = makeGrid(box, {0, 1.0});
    const auto ref = validate::exactReference(box, grid, grid.epsilon());
    EXPECT_TRUE(ref.required.empty()); // no voxel's shrunk cube meets a face on the planes
    // Voxels -5..5 on each axis with a coordinate of ±4 or ±5.
    EXPECT_EQ(ref.exact.size(), 11u * 11 * 11 - 7u * 7 * 7);
    EXPECT_TRUE(includes(ref.allowed, ref.exact));
    auto g = gpuVoxels(box, grid);
    ASSERT_EQ(g, ref.exact); // the GPU keeps every touching voxel

    // Drop one: R has nothing to miss, but E does, and the verdict fails.
    const uint64_t victim = ref.exact[ref.exact.size() / 3];
    g.erase(std::find(g.begin(), g.end(), victim));
    const auto c = validate::classify(box, grid, g, ref);
    EXPECT_TRUE(c.missed.empty());
    EXPECT_EQ(c.missedExact, std::vector<uint64_t>{victim});
    ASSERT_EQ(c.worstMissed.size(), 1u);
    EXPECT_EQ(c.worstMissed[0].index, grid.toGlobal(unpackVoxelKey(victim)));
    validate::ReportOptions options;
    options.holes = false;
    const auto report = validate::validateVoxelization(box, buildOctree(grid, g), g, options);
    EXPECT_FALSE(report.passed);
    EXPECT_NE(report.reason.find("1 voxels of the exact conservative set missed"), std::string::npos) << report.reason;
}

TEST_F(Validate, OneVoxelHoleInAThinWallLeaks)
{
    // Faces through voxel centres: a shell exactly one voxel thick.
    const auto box = test::box({-4, -4, -4}, {4, 4, 4});
    const GridSpec grid = makeGrid(box, {0, 1.0});
    auto g = gpuVoxels(box, grid);
    ASSERT_EQ(g.size(), 9u * 9 * 9 - 7u * 7 * 7);
    EXPECT_FALSE(validate::checkHoles(box, grid, g).leak);
    const Vec3d face = grid.toLocal({4, 0, 0});
    const uint64_t k = packVoxelKey(uint32_t(face.x), uint32_t(face.y), uint32_t(face.z));
    g.erase(std::find(g.begin(), g.end(), k));
    const auto h = validate::checkHoles(box, grid, g);
    EXPECT_TRUE(h.leak);
    // 6-connected fill leaks too: the hole is a face opening.
    EXPECT_TRUE(validate::checkHoles(box, grid, g, 6).leak);
}

TEST_F(Validate, OpenMeshesAreNotHoleChecked)
{
    TriangleMesh open = test::box({0, 0, 0}, {3, 3, 3});
    open.triangles.pop_back();
    const GridSpec grid = makeGrid(open, {0, 0.5});
    const auto h = validate::checkHoles(open, grid, gpuVoxels(open, grid));
    EXPECT_FALSE(h.applies);
    EXPECT_NE(h.reason.find("open"), std::string::npos) << h.reason;
}

TEST_F(Validate, GpuPassesOnRealMeshes)
{
#ifdef SVO_CGAL_MESHES
    const std::string dir = std::getenv("SVO_CGAL_MESHES") ? std::getenv("SVO_CGAL_MESHES") : SVO_CGAL_MESHES;
    for (const char* name : {"elephant.off", "knot1.off", "fandisk.off", "cow.off"})
        for (int res : {64, 160}) {
            const TriangleMesh mesh = loadMesh(dir + "/" + name);
            const GridSpec grid = makeGrid(mesh, {res, 0});
            const auto g = gpuVoxels(mesh, grid);
            const auto c = validate::classify(mesh, grid, g, validate::exactReference(mesh, grid, grid.epsilon()));
            EXPECT_TRUE(c.missed.empty()) << name << " " << res;
            EXPECT_TRUE(c.extra.empty()) << name << " " << res;
            const auto h = validate::checkHoles(mesh, grid, g);
            EXPECT_FALSE(h.leak) << name << " " << res;
            std::printf("  %-14s %4d voxels %8zu boundary %5zu holes %s\n", name, res, g.size(), c.boundary.size(),
                        h.applies ? "checked" : h.reason.c_str());
        }
#else
    GTEST_SKIP() << "libcgal-demo's meshes were not found at configure time";
#endif
}
