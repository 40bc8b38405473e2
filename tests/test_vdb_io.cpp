// .vdb output read back with OpenVDB's own reader: the exact voxel set and transform.
#include <filesystem>
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <set>

#include "scenes.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/error.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_key.h"
#include "svo/vdb_io/vdb_file.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace svo;

namespace {

std::set<std::array<int64_t, 3>> globalVoxels(const Voxelization& v)
{
    std::set<std::array<int64_t, 3>> s;
    for (uint64_t k : v.keys) s.insert(v.grid.toGlobal(unpackVoxelKey(k)));
    return s;
}

openvdb::GridPtrVecPtr readAll(const std::string& path)
{
    openvdb::initialize();
    openvdb::io::File f(path);
    f.open();
    auto grids = f.getGrids();
    f.close();
    return grids;
}

void expectRoundTrip(const TriangleMesh& mesh, const GridRequest& req, bool fog)
{
    const GridSpec grid = makeGrid(mesh, req);
    const Voxelization v = voxelizeCpu(mesh, grid);
    const test::TempDir tmp("vdb_io");
    const std::string path = tmp.path("out.vdb");
    vdb::WriteOptions o;
    o.fog = fog;
    o.metadata["svo:source"] = mesh.source;
    vdb::writeVdb(path, buildOctree(v.grid, v.keys), o);
    auto grids = readAll(path);
    ASSERT_EQ(grids->size(), fog ? 2u : 1u);
    const auto expected = globalVoxels(v);
    for (auto& base : *grids) {
        std::set<std::array<int64_t, 3>> got;
        if (auto mask = openvdb::gridPtrCast<openvdb::MaskGrid>(base)) {
            EXPECT_EQ(mask->getName(), "surface");
            for (auto it = mask->cbeginValueOn(); it; ++it) {
                ASSERT_TRUE(it.isVoxelValue());
                const auto c = it.getCoord();
                got.insert({c.x(), c.y(), c.z()});
            }
        } else if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) {
            EXPECT_EQ(f->getGridClass(), openvdb::GRID_FOG_VOLUME);
            for (auto it = f->cbeginValueOn(); it; ++it) {
                EXPECT_EQ(*it, 1.0f);
                const auto c = it.getCoord();
                got.insert({c.x(), c.y(), c.z()});
            }
        } else {
            FAIL() << "unexpected grid type " << base->type();
        }
        EXPECT_EQ(got, expected);
        EXPECT_EQ(base->metaValue<std::string>("svo:source"), mesh.source);
        // The transform: voxel size and translation exactly as the grid says.
        const auto& xf = base->transform();
        EXPECT_DOUBLE_EQ(xf.voxelSize()[0], grid.voxelSize);
        const auto t = grid.translation();
        const auto origin = xf.indexToWorld(openvdb::Vec3d(0, 0, 0));
        EXPECT_DOUBLE_EQ(origin[0], t[0]);
        EXPECT_DOUBLE_EQ(origin[1], t[1]);
        EXPECT_DOUBLE_EQ(origin[2], t[2]);
        // World bounds of the voxels match the mesh's within one voxel.
        const auto bbox = base->evalActiveVoxelBoundingBox();
        const auto lo = xf.indexToWorld(bbox.min()), hi = xf.indexToWorld(bbox.max());
        const auto mb = mesh.bounds();
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(lo[a], mb.min[a], grid.voxelSize * 1.0001);
            EXPECT_NEAR(hi[a], mb.max[a], grid.voxelSize * 1.0001);
        }
    }
    fs::remove(path);
}

} // namespace

TEST(VdbIo, SphereRoundTripsExactly) { expectRoundTrip(test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24), {100, 0}, true); }

TEST(VdbIo, FarFromOriginKeepsTheLatticeAndTheVoxels)
{
    // 1e9 world units away, at a voxel size that divides 1e9: the grid is
    // shifted by whole voxels and the voxel set is the same as at the origin.
    const double h = 1.0 / 64;
    const auto near = test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24);
    auto far = near;
    for (auto& p : far.positions) p = p + Vec3d{1e9, -1e9, 1e9};
    expectRoundTrip(far, {0, h}, false);
    const auto a = voxelizeCpu(near, makeGrid(near, {0, h}));
    const auto b = voxelizeCpu(far, makeGrid(far, {0, h}));
    EXPECT_EQ(a.keys.size(), b.keys.size());
    std::set<std::array<int64_t, 3>> sa, sb;
    const int64_t shift = int64_t(1e9 / h);
    for (auto v : globalVoxels(a)) sa.insert(v);
    for (auto v : globalVoxels(b)) {
        const auto& g = b.grid;
        sb.insert({v[0] + g.shift[0] - shift, v[1] + g.shift[1] + shift, v[2] + g.shift[2] - shift});
    }
    EXPECT_EQ(sa, sb);
}

TEST(VdbIo, UnwritableFolderIsAnErrorAndLeavesNothing)
{
    const auto mesh = test::box({0, 0, 0}, {1, 1, 1});
    const auto v = voxelizeCpu(mesh, makeGrid(mesh, {8, 0}));
    EXPECT_THROW(vdb::writeVdb("/nonexistent-folder/out.vdb", buildOctree(v.grid, v.keys), {}), svo::Error);
}
