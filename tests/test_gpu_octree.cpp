// The GPU octree build against the CPU reference, and octree <-> OpenVDB round
// trips read back with OpenVDB's own reader.
#include <filesystem>
#include <fstream>
#include <functional>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <memory>
#include <random>
#include <openvdb/openvdb.h>
#include <openvdb/tools/PointIndexGrid.h>
#include <set>
#include <unistd.h>

#include "octree_scenes.h"
#include "scenes.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/gpu_layout.h"
#include "voxelize_layout.h" // SVO_BUILD_BITMAP_MAX_LEVEL (gl/voxelize/shaders)
#include "svo/core/mesh_io.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_attributes.h"
#include "svo/core/voxel_mode.h"
#include "svo/gl/raster_voxelizer.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/vdb_file.h"
#include "temp_dir.h"

using namespace svo;
namespace fs = std::filesystem;

namespace {

using VoxelSet = std::set<std::array<int64_t, 3>>;

VoxelSet globalVoxels(const Octree& o)
{
    VoxelSet s;
    for (uint64_t k : octreeKeys(o)) s.insert(o.grid.toGlobal(unpackVoxelKey(k)));
    return s;
}

VoxelSet vdbVoxels(const std::string& path, const std::string& name)
{
    openvdb::io::File f(path);
    f.open();
    auto base = f.readGrid(name);
    f.close();
    VoxelSet s;
    base->apply<vdb::GridTypes>([&](const auto& g) {
        for (auto it = g.cbeginValueOn(); it; ++it) {
            EXPECT_TRUE(it.isVoxelValue());
            s.insert({it.getCoord().x(), it.getCoord().y(), it.getCoord().z()});
        }
    });
    return s;
}

const test::TempDir tmp("test_gpu_octree");
std::string tempPath(const std::string& name) { return tmp.path(name); }

class GpuOctree : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        openvdb::initialize();
        context_ = std::make_unique<gl::Context>();
    }
    static void TearDownTestSuite() { context_.reset(); }

    /// The GPU octree of a mesh equals the CPU reference built from the same
    /// GPU voxel set (read back as keys), and is sound as the GPU laid it out.
    void expectMatchesReference(const TriangleMesh& mesh, const GridRequest& req, const gl::RasterOptions& opt = {})
    {
        const GridSpec grid = makeGrid(mesh, req);
        RunStats keysReport, gpuReport;
        const Voxelization keys = gl::voxelizeRaster(*context_, mesh, grid, {}, &keysReport);
        const Octree gpu = gl::voxelizeToOctree(*context_, mesh, grid, opt, &gpuReport);
        const auto problems = checkOctree(gpu);
        EXPECT_TRUE(problems.empty()) << mesh.source << ": " << problems.front();
        const Octree reference = buildOctree(grid, keys.keys);
        EXPECT_TRUE(sameOctree(canonicalOrder(gpu), reference)) << mesh.source;
        // Built from occupancy bitmaps, the GPU lays out the canonical order itself.
        if (brickLevelFor(grid) <= SVO_BUILD_BITMAP_MAX_LEVEL) {
            EXPECT_TRUE(sameOctree(gpu, reference)) << mesh.source;
        }
        EXPECT_EQ(gpu.voxelCount(), keys.keys.size()) << mesh.source;
        EXPECT_EQ(gpuReport.listEntries, keysReport.listEntries) << mesh.source;
        std::printf("  %-28s voxels %9zu bricks %7zu nodes %8zu levels %u retries %d\n", mesh.source.c_str(),
                    keys.keys.size(), gpu.bricks.size(), gpu.nodes.size(), gpu.brickLevel + 1,
                    gpuReport.overflowRetries);
    }

    static std::unique_ptr<gl::Context> context_;
};
std::unique_ptr<gl::Context> GpuOctree::context_;

} // namespace

TEST_F(GpuOctree, MatchesReferenceOnGeneratedMeshes)
{
    expectMatchesReference(test::randomTriangles(512, 1), {0, 1.0});
    expectMatchesReference(test::sphere({0.1, 0.2, 0.3}, 1.0, 64, 32), {100, 0});
    expectMatchesReference(test::box({-4.5, -4.5, -4.5}, {4.5, 4.5, 4.5}), {0, 1.0}); // one level
    expectMatchesReference(cornellBox(), {256, 0});
}

TEST_F(GpuOctree, MatchesReferenceOnRealMeshes)
{
#ifdef SVO_CGAL_MESHES
    const std::string dir = std::getenv("SVO_CGAL_MESHES") ? std::getenv("SVO_CGAL_MESHES") : SVO_CGAL_MESHES;
    for (const char* name : {"elephant.off", "knot1.off", "fandisk.off"})
        expectMatchesReference(loadMesh(dir + "/" + name), {200, 0});
#else
    GTEST_SKIP() << "libcgal-demo's meshes were not found at configure time";
#endif
}

TEST_F(GpuOctree, OverflowingEveryBufferRetriesToTheSameResult)
{
    const auto mesh = test::sphere({0, 0, 0}, 1.0, 48, 24);
    const GridSpec grid = makeGrid(mesh, {64, 0});
    gl::RasterOptions tinyList, tinyOctree;
    tinyList.initialCapacity = 16;     // the voxel list overflows: rasterize again
    tinyOctree.initialBrickCapacity = 1; // bricks and nodes overflow: build again
    for (const auto& opt : {tinyList, tinyOctree}) {
        RunStats report;
        gl::voxelizeToOctree(*context_, mesh, grid, opt, &report);
        EXPECT_GE(report.overflowRetries, 1);
        expectMatchesReference(mesh, {64, 0}, opt);
    }
    // The bitmap build counts nodes and bricks exactly past its capacity: one rebuild is enough.
    RunStats report;
    gl::voxelizeToOctree(*context_, mesh, grid, tinyOctree, &report);
    EXPECT_EQ(report.overflowRetries, 1);
}

TEST_F(GpuOctree, TilesWithinAGpuBudgetGiveTheUntiledOctree)
{
    // A budget half of what the whole grid takes: the grid is cut into
    // tiles, each within the budget, and the merged octree, its attribute
    // channels and its voxel list equal the untiled ones bit for bit.
    std::vector<std::pair<TriangleMesh, GridRequest>> scenes = {{cornellBox(), {256, 0}},
                                                                {test::sphere({0.1, 0.2, 0.3}, 1.0, 64, 32), {150, 0}}};
#ifdef SVO_CGAL_MESHES
    const std::string dir = std::getenv("SVO_CGAL_MESHES") ? std::getenv("SVO_CGAL_MESHES") : SVO_CGAL_MESHES;
    scenes.emplace_back(loadMesh(dir + "/elephant.off"), GridRequest{200, 0});
#endif
    for (const auto& [mesh, req] : scenes)
        for (auto pipeline : {gl::Pipeline::Raster, gl::Pipeline::Compute})
            for (auto mode : {VoxelMode::Conservative, VoxelMode::Thin}) {
                const std::string what = fmt::format("{} {} {}", mesh.source,
                                                     pipeline == gl::Pipeline::Raster ? "raster" : "compute",
                                                     voxelModeName(mode));
                const GridSpec grid = makeGrid(mesh, req);
                gl::RasterOptions opt;
                opt.pipeline = pipeline;
                opt.mode = mode;
                opt.attributes = kNormals | kTriangles | (mesh.colors.empty() ? 0 : kColors);
                std::vector<uint64_t> wholeList, tiledList;
                opt.voxelList = &wholeList;
                gl::Context fresh; // scratch buffers from other tests would count against the budget
                RunStats wholeReport, tiledReport;
                const Octree whole = gl::voxelizeToOctree(fresh, mesh, grid, opt, &wholeReport);
                ASSERT_EQ(wholeReport.tiles, 1u) << what;
                fresh.releaseScratch();
                opt.voxelList = &tiledList;
                opt.gpuMemory = wholeReport.gpuBytes / 2;
                const Octree tiled = gl::voxelizeToOctree(fresh, mesh, grid, opt, &tiledReport);
                EXPECT_GT(tiledReport.tiles, 2u) << what;
                EXPECT_LE(tiledReport.gpuBytes, opt.gpuMemory) << what;
                EXPECT_TRUE(checkOctree(tiled).empty()) << what;
                EXPECT_TRUE(sameOctree(tiled, canonicalOrder(whole))) << what;
                EXPECT_FALSE(tiled.attributes.normals.empty()) << what;
                EXPECT_EQ(tiledList, wholeList) << what;
                EXPECT_EQ(tiledReport.listEntries, wholeReport.listEntries) << what;
                std::printf("  %-40s %u tiles, GPU %.1f -> %.1f MiB, %lu voxels\n", what.c_str(), tiledReport.tiles,
                            double(wholeReport.gpuBytes) / (1 << 20), double(tiledReport.gpuBytes) / (1 << 20),
                            (unsigned long)tiled.voxelCount());
            }
}

TEST_F(GpuOctree, ABudgetTheMeshAloneExceedsIsAClearError)
{
    const auto mesh = test::sphere({0, 0, 0}, 1.0, 64, 32);
    gl::RasterOptions opt;
    opt.gpuMemory = 1024; // less than the vertices
    try {
        gl::voxelizeToOctree(*context_, mesh, makeGrid(mesh, {64, 0}), opt);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot hold the mesh"), std::string::npos) << e.what();
    }
}

TEST_F(GpuOctree, FromBricksMatchesReference)
{
    // 2048 and 4096 wide: bitmaps of many blocks per scan thread, up to the
    // bitmap build's last level; the last grid is wider: built by descent.
    for (auto dims : {std::array<uint32_t, 3>{8, 8, 8}, {33, 70, 9}, {300, 300, 300}, {2048, 16, 1030},
                      {4096, 9, 8}, {8200, 40, 9}}) {
        const GridSpec g = test::gridOf(dims[0], dims[1], dims[2]);
        const auto keys = test::randomVoxels(g, 20000, dims[1]);
        std::vector<std::pair<uint64_t, Brick>> bricks; // one voxel each: many duplicate bricks
        for (uint64_t k : keys) {
            Brick b;
            b.words[(k & 511) >> 6] = uint64_t(1) << (k & 63);
            bricks.emplace_back(brickOfKey(k), b);
        }
        const Octree gpu = gl::buildOctreeGpu(*context_, g, bricks);
        EXPECT_TRUE(checkOctree(gpu).empty());
        const Octree reference = buildOctree(g, keys);
        EXPECT_TRUE(sameOctree(canonicalOrder(gpu), reference));
        if (brickLevelFor(g) <= SVO_BUILD_BITMAP_MAX_LEVEL) {
            EXPECT_TRUE(sameOctree(gpu, reference));
        }
    }
}

TEST_F(GpuOctree, MeshToVdbToOctreeToVdbIsIdentical)
{
    const auto mesh = test::sphere({0.1, 0.2, 0.3}, 1.0, 64, 32);
    const GridSpec grid = makeGrid(mesh, {96, 0});
    const Octree first = gl::voxelizeToOctree(*context_, mesh, grid);
    const VoxelSet voxels = globalVoxels(first);
    for (auto [topology, name] : {std::pair{vdb::Topology::Mask, "mask"}, std::pair{vdb::Topology::Bool, "bool"}}) {
        vdb::WriteOptions wo;
        wo.topology = topology;
        wo.fog = true;
        const std::string a = tempPath(std::string(name) + "_a.vdb"), b = tempPath(std::string(name) + "_b.vdb");
        vdb::writeVdb(a, first, wo);
        for (const char* gridName : {"surface", "density"}) {
            EXPECT_EQ(vdbVoxels(a, gridName), voxels) << name << " " << gridName;
            const auto bricks = vdb::readVdbBricks(a, gridName);
            const Octree second = gl::buildOctreeGpu(*context_, bricks.grid, bricks.bricks);
            EXPECT_TRUE(checkOctree(second).empty());
            EXPECT_EQ(globalVoxels(second), voxels) << name << " " << gridName;
            EXPECT_EQ(second.grid.voxelSize, first.grid.voxelSize);
            EXPECT_EQ(second.grid.shift, first.grid.shift);
            vdb::writeVdb(b, second, wo);
            EXPECT_EQ(vdbVoxels(b, "surface"), voxels);
            EXPECT_EQ(vdbVoxels(b, "density"), voxels);
            const auto again = vdb::readVdbBricks(b, gridName);
            const Octree third = gl::buildOctreeGpu(*context_, again.grid, again.bricks);
            EXPECT_TRUE(sameOctree(canonicalOrder(third), canonicalOrder(second)));
        }
        // The transform survives: world positions of a voxel agree.
        openvdb::io::File f(a);
        f.open();
        const auto g = f.readGrid("surface");
        f.close();
        EXPECT_DOUBLE_EQ(g->voxelSize()[0], grid.voxelSize);
        fs::remove(a);
        fs::remove(b);
    }
}

TEST(VdbToBricks, ActiveTilesAreExpanded)
{
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    // A 128^3 active tile (a child of a level-2 internal node), an 8^3 one, and two voxels.
    grid->tree().addTile(2, openvdb::Coord(128, 0, -128), 2.0f, true);
    grid->tree().addTile(1, openvdb::Coord(-64, -64, -64), 2.0f, true);
    grid->tree().setValueOn(openvdb::Coord(-3, 5, 7), 1.0f);
    grid->tree().setValueOn(openvdb::Coord(300, 1, 1), 1.0f);
    const auto gb = vdb::gridToBricks(*grid, "tiles.vdb");
    EXPECT_EQ(gb.tilesExpanded, 2u);
    const Octree o = buildOctreeFromBricks(gb.grid, gb.bricks);
    EXPECT_TRUE(checkOctree(o).empty());
    EXPECT_EQ(o.voxelCount(), grid->activeVoxelCount());
    EXPECT_EQ(o.voxelCount(), 128u * 128 * 128 + 512 + 2);
    EXPECT_EQ(gb.grid.voxelSize, 0.25);
}

TEST(VdbToBricks, UnsupportedInputsAreRefused)
{
    openvdb::initialize();
    auto expectError = [](const std::function<void()>& f, const std::string& fragment) {
        try {
            f();
            ADD_FAILURE() << "no error; expected: " << fragment;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        }
    };
    auto shifted = openvdb::MaskGrid::create();
    auto xf = openvdb::math::Transform::createLinearTransform(1.0);
    xf->postTranslate(openvdb::Vec3d(0.5, 0, 0));
    shifted->setTransform(xf);
    expectError([&] { vdb::gridToBricks(*shifted, "half.vdb"); }, "not a whole number");
    auto rotated = openvdb::MaskGrid::create();
    auto rx = openvdb::math::Transform::createLinearTransform(1.0);
    rx->postRotate(0.3, openvdb::math::Z_AXIS);
    rotated->setTransform(rx);
    expectError([&] { vdb::gridToBricks(*rotated, "rot.vdb"); }, "transform");
    auto points = openvdb::tools::PointIndexGrid::create();
    expectError([&] { vdb::gridToBricks(*points, "points.vdb"); }, "does not read");

    const std::string empty = tempPath("nogrids.vdb");
    {
        openvdb::io::File f(empty);
        f.write(openvdb::GridPtrVec{});
        f.close();
    }
    expectError([&] { vdb::readVdbBricks(empty); }, "no grids");
    fs::remove(empty);
    const std::string one = tempPath("one.vdb");
    {
        auto g = openvdb::MaskGrid::create();
        g->setName("a");
        openvdb::io::File f(one);
        f.write(openvdb::GridPtrVec{g});
        f.close();
    }
    expectError([&] { vdb::readVdbBricks(one, "b"); }, "no grid named 'b'");
    fs::remove(one);
    const std::string junk = tempPath("junk.vdb");
    std::ofstream(junk) << "not a vdb file";
    expectError([&] { vdb::readVdbBricks(junk); }, "not a readable VDB file");
    fs::remove(junk);
    expectError([&] { vdb::readVdbBricks(tempPath("missing.vdb")); }, "no such file");
}

TEST_F(GpuOctree, AttributesEqualTheCpuReferenceOutsideTheBand)
{
    // Random triangles with random vertex colours, and a sphere; in both
    // modes (thin: the pairs come from the centre-segment test).
    auto random = test::randomTriangles(400, 5);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    for (size_t i = 0; i < random.positions.size(); ++i) random.colors.push_back({u(rng), u(rng), u(rng)});
    const uint32_t all = kNormals | kTriangles | kColors;
    for (const VoxelMode mode : {VoxelMode::Conservative, VoxelMode::Thin}) {
        for (const auto& [mesh, req] : {std::pair{random, GridRequest{0, 0.5}},
                                        std::pair{test::icosphere({0.1, 0.2, 0.3}, 1.0, 4), GridRequest{64, 0}}}) {
            const GridSpec grid = makeGrid(mesh, req);
            gl::RasterOptions opt;
            opt.attributes = all;
            opt.mode = mode;
            const Octree gpu = gl::voxelizeToOctree(*context_, mesh, grid, opt);
            ASSERT_TRUE(checkOctree(gpu).empty());
            ASSERT_EQ(gpu.channels(), mesh.colors.empty() ? uint32_t(kNormals | kTriangles) : all);
            // The GPU's (voxel, triangle) pairs lie between the CPU's on cubes (thin: segments)
            // shrunk and grown by epsilon; where those agree, so must the values.
            Octree lo = gpu, hi = gpu;
            attachAttributesCpu(mesh, lo, all, -grid.epsilon(), mode);
            attachAttributesCpu(mesh, hi, all, +grid.epsilon(), mode);
            size_t compared = 0, differ = 0;
            for (size_t v = 0; v < gpu.voxelCount(); ++v) {
                const bool decided = lo.attributes.triangles[v] == hi.attributes.triangles[v] &&
                                     lo.attributes.normals[v].x == hi.attributes.normals[v].x &&
                                     lo.attributes.normals[v].y == hi.attributes.normals[v].y &&
                                     lo.attributes.normals[v].z == hi.attributes.normals[v].z;
                if (!decided) continue;
                ++compared;
                const auto& g = gpu.attributes;
                const auto& c = hi.attributes;
                differ += g.triangles[v] != c.triangles[v] || g.normals[v].x != c.normals[v].x ||
                          g.normals[v].y != c.normals[v].y || g.normals[v].z != c.normals[v].z ||
                          (!c.colors.empty() && (g.colors[v].x != c.colors[v].x || g.colors[v].z != c.colors[v].z));
            }
            EXPECT_EQ(differ, 0u) << mesh.source;
            EXPECT_GT(double(compared), 0.99 * double(gpu.voxelCount())) << mesh.source;
            std::printf("  %-18s %-12s %zu voxels, %zu compared exactly\n", mesh.source.c_str(), voxelModeName(mode),
                        size_t(gpu.voxelCount()), compared);
        }
    }
}

TEST_F(GpuOctree, AttributeGridsReachTheVdbFile)
{
    auto mesh = test::icosphere({0, 0, 0}, 1.0, 3);
    for (size_t i = 0; i < mesh.positions.size(); ++i) mesh.colors.push_back({1.0f, 0.5f, 0.0f});
    const GridSpec grid = makeGrid(mesh, {32, 0});
    gl::RasterOptions opt;
    opt.attributes = kNormals | kTriangles | kColors;
    const Octree o = gl::voxelizeToOctree(*context_, mesh, grid, opt);
    const std::string path = tempPath("attributes.vdb");
    vdb::writeVdb(path, o, {});
    openvdb::io::File f(path);
    f.open();
    auto normal = openvdb::gridPtrCast<openvdb::Vec3SGrid>(f.readGrid("normal"));
    auto tri = openvdb::gridPtrCast<openvdb::Int32Grid>(f.readGrid("triangle_id"));
    auto color = openvdb::gridPtrCast<openvdb::Vec3SGrid>(f.readGrid("color"));
    f.close();
    fs::remove(path);
    ASSERT_TRUE(normal && tri && color);
    EXPECT_EQ(normal->activeVoxelCount(), openvdb::Index64(o.voxelCount()));
    // On a sphere, normals point away from the centre; colours are the one vertex colour.
    const auto xf = normal->transform();
    for (auto it = normal->cbeginValueOn(); it; ++it) {
        openvdb::Vec3d p = xf.indexToWorld(it.getCoord());
        EXPECT_GT(p.normalize() ? p.dot(openvdb::Vec3d(*it)) : 1.0, 0.5) << it.getCoord();
        EXPECT_NEAR((*it).length(), 1.0, 1e-4);
    }
    for (auto it = color->cbeginValueOn(); it; ++it) EXPECT_NEAR((*it)[1], 0.5f, 1e-4);
    for (auto it = tri->cbeginValueOn(); it; ++it) {
        EXPECT_GE(*it, 0);
        EXPECT_LT(*it, int32_t(mesh.triangles.size()));
    }
}
