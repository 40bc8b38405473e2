// NanoVDB grids laid out from svo's bricks (svo/vdb_io/nanovdb_layout.h,
// nanovdb_grids.h) against NanoVDB's own host code: its converter from the
// OpenVDB grid the same data gives (nanovdb::openToNanoVDB via toNanoVdb),
// its statistics (nanovdb::gridStats), validator (nanovdb::isValid, full
// checksum), file reader (nanovdb::io::readGrids) and its command-line
// validator (nanovdb_validate, Debian's libnanovdb-tools).
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <gtest/gtest.h>
#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/GridStats.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>

#include "scenes.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/gl/device.h"
#include "svo/gl/field_pipeline.h"
#include "svo/gl/voxelize_pipeline.h"
#include "svo/vdb_io/field_grids.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/nanovdb_file.h"
#include "svo/vdb_io/nanovdb_grids.h"
#include "svo/vdb_io/nanovdb_input.h"
#include "svo/vdb_io/nanovdb_layout.h"
#include "svo/vdb_io/nanovdb_output.h"
#include "svo/vdb_io/reader_grids.h"
#include "temp_dir.h"

namespace svo {
namespace {

using vdb::NanoHandle;

/// NanoVDB's own statistics (StatsMode::MinMax, the builder's) and checksum,
/// recomputed on a copy, give the builder's bytes exactly.
template <typename BuildT>
void expectNanoVdbsOwnStatistics(const NanoHandle& h)
{
    std::vector<uint8_t> copy(h.data(), h.data() + h.size());
    auto* grid = reinterpret_cast<nanovdb::NanoGrid<BuildT>*>(copy.data());
    nanovdb::gridStats(*grid, nanovdb::StatsMode::MinMax);
    nanovdb::updateChecksum(*grid, nanovdb::ChecksumMode::Full);
    EXPECT_EQ(0, std::memcmp(copy.data(), h.data(), copy.size())) << grid->gridName() << ": statistics or bounding boxes differ";
}

/// Voxel for voxel and value for value over both grids' boxes grown by a
/// leaf, inactive values included; and the grid-level facts.
template <typename BuildT>
void expectSameGrid(const nanovdb::NanoGrid<BuildT>& a, const nanovdb::NanoGrid<BuildT>& b)
{
    const std::string name = a.gridName();
    ASSERT_EQ(name, std::string(b.gridName()));
    EXPECT_EQ(a.gridClass(), b.gridClass()) << name;
    EXPECT_EQ(a.activeVoxelCount(), b.activeVoxelCount()) << name;
    EXPECT_EQ(a.indexBBox(), b.indexBBox()) << name;
    EXPECT_EQ(a.voxelSize(), b.voxelSize()) << name;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(a.map().mVecD[i], b.map().mVecD[i]) << name;
    EXPECT_EQ(a.tree().background(), b.tree().background()) << name;
    if constexpr (std::is_same_v<BuildT, float> || std::is_same_v<BuildT, int32_t>) {
        EXPECT_EQ(a.tree().root().minimum(), b.tree().root().minimum()) << name;
        EXPECT_EQ(a.tree().root().maximum(), b.tree().root().maximum()) << name;
    }
    nanovdb::CoordBBox box = a.indexBBox();
    if (box.empty()) return;
    box.expand(b.indexBBox().min());
    box.expand(b.indexBBox().max());
    box.expand(box.min() - nanovdb::Coord(8));
    box.expand(box.max() + nanovdb::Coord(8));
    auto ra = a.getAccessor();
    auto rb = b.getAccessor();
    uint64_t differ = 0;
    for (auto it = box.begin(); it; ++it) {
        const nanovdb::Coord c = *it;
        if (ra.isActive(c) != rb.isActive(c) || !(ra.getValue(c) == rb.getValue(c))) {
            if (++differ <= 3)
                ADD_FAILURE() << name << " differs at (" << c[0] << ", " << c[1] << ", " << c[2] << "): active "
                              << ra.isActive(c) << " vs " << rb.isActive(c);
        }
    }
    EXPECT_EQ(differ, 0u) << name;
}

/// Dispatches on the grid type; checks NanoVDB's validator first.
void expectSame(const NanoHandle& mine, const NanoHandle& host)
{
    const auto* m = mine.gridMetaData();
    ASSERT_EQ(m->gridType(), host.gridMetaData()->gridType()) << m->shortGridName();
    auto check = [&](auto tag) {
        using BuildT = decltype(tag);
        const auto* a = mine.grid<BuildT>();
        const auto* b = host.grid<BuildT>();
        ASSERT_TRUE(a && b);
        EXPECT_TRUE(nanovdb::isValid(*a, true, true)) << a->gridName();
        EXPECT_TRUE(nanovdb::validateChecksum(*a, nanovdb::ChecksumMode::Full)) << a->gridName();
        expectNanoVdbsOwnStatistics<BuildT>(mine);
        expectSameGrid(*a, *b);
    };
    switch (m->gridType()) {
    case nanovdb::GridType::Mask: return check(nanovdb::ValueMask{});
    case nanovdb::GridType::Boolean: return check(bool{});
    case nanovdb::GridType::Float: return check(float{});
    case nanovdb::GridType::Int32: return check(int32_t{});
    case nanovdb::GridType::Vec3f: return check(nanovdb::Vec3f{});
    default: FAIL() << "unexpected grid type " << nanovdb::toStr(m->gridType());
    }
}

void expectSameGrids(const std::vector<NanoHandle>& mine, const openvdb::GridPtrVec& host)
{
    ASSERT_EQ(mine.size(), host.size());
    for (size_t i = 0; i < mine.size(); ++i) expectSame(mine[i], vdb::toNanoVdb(host[i]));
}

/// Written with each codec, read back by NanoVDB's reader (same bytes) and by
/// svo's checked reader (same active voxels), and passed by NanoVDB's
/// command-line validator.
void expectFilesRoundTrip(const std::vector<NanoHandle>& grids, const std::string& stem)
{
    test::TempDir dir("nanovdb_layout");
    for (const auto codec : {vdb::NanoCodec::None, vdb::NanoCodec::Zip, vdb::NanoCodec::Blosc}) {
        if (!vdb::nanoCodecAvailable(codec)) continue;
        const std::string path = dir.path(stem + std::to_string(int(codec)) + ".nvdb");
        vdb::writeNanoVdb(path, grids, codec);
        const auto back = nanovdb::io::readGrids<nanovdb::HostBuffer>(path);
        ASSERT_EQ(back.size(), grids.size());
        for (size_t i = 0; i < grids.size(); ++i) {
            ASSERT_EQ(back[i].size(), grids[i].size());
            EXPECT_EQ(0, std::memcmp(back[i].data(), grids[i].data(), grids[i].size())) << path << " grid " << i;
        }
        const openvdb::GridPtrVec mine = vdb::readNanoVdbGrids(path);
        ASSERT_EQ(mine.size(), grids.size());
        for (size_t i = 0; i < grids.size(); ++i)
            EXPECT_EQ(mine[i]->activeVoxelCount(), grids[i].gridMetaData()->activeVoxelCount()) << path << " grid " << i;
        const std::string cmd = "nanovdb_validate " + path + " > /dev/null 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
}

struct Scene {
    std::string name;
    TriangleMesh mesh;
    int resolution;
};

std::vector<Scene> scenes()
{
    // The UV sphere is open at its poles (winding signs only); the others are closed.
    std::vector<Scene> s = {{"sphere", test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24), 64},
                            {"icosphere", icosphere({0.1, 0.2, -0.3}, 1.0, 3), 56},
                            {"box", test::box({-1, -0.5, -0.25}, {1, 0.5, 0.25}), 48},
                            {"cornell", cornellBox(), 64}};
#ifdef SVO_CGAL_MESHES
    s.push_back({"elephant", loadMesh(std::string(SVO_CGAL_MESHES) + "/elephant.off"), 80});
#endif
    return s;
}

/// Parity signs need a closed mesh.
bool closed(const std::string& scene) { return scene != "cornell" && scene != "sphere"; }

/// The GL passes (raster, on every GL 4.5 device, llvmpipe included) or the
/// CPU backend: the data the library lays out, and the OpenVDB grids its
/// OpenVDB path makes of the same data (level_set.cpp, octree_files.cpp).
class NanoVdbLayout : public ::testing::TestWithParam<Backend> {
protected:
    VoxelizeSettings settings() const
    {
        VoxelizeSettings s;
        s.backend = GetParam();
        return s;
    }
    Octree octree(const TriangleMesh& mesh, const GridSpec& grid)
    {
        VoxelizeSettings s = settings();
        s.attributes = kNormals | kTriangles;
        VoxelizeStats stats;
        return gl::voxelizeMesh(device, mesh, grid, s, Checkpoint{}, stats);
    }
    DistanceBricks field(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls)
    {
        VoxelizeStats stats;
        return gl::levelSetBricks(device, mesh, grid, ls, settings(), Checkpoint{}, stats);
    }
    SolidBricks solid(const TriangleMesh& mesh, const GridSpec& grid, const SignOptions& sign)
    {
        VoxelizeStats stats;
        return gl::solidBricks(device, mesh, grid, settings(), sign, Checkpoint{}, stats);
    }
    gl::Device device;
};

TEST_P(NanoVdbLayout, SurfaceGridsEqualNanoVdbsConverter)
{
    for (const auto& s : scenes()) {
        SCOPED_TRACE(s.name);
        const GridSpec grid = makeGrid(s.mesh, {s.resolution, 0.0});
        const Octree oct = octree(s.mesh, grid);
        for (const auto topology : {GridOptions::Topology::Mask, GridOptions::Topology::Bool}) {
            GridOptions g;
            g.topology = topology;
            g.fog = true;
            const auto mine = vdb::octreeToNanoGrids(oct, g);
            ASSERT_EQ(mine.size(), 4u); // topology, density, normal, triangle_id
            expectSameGrids(mine, vdb::octreeToGrids(oct, g));
            if (topology == GridOptions::Topology::Mask) expectFilesRoundTrip(mine, s.name);
        }
    }
}

TEST_P(NanoVdbLayout, DistanceFieldsEqualNanoVdbsConverter)
{
    for (const auto& s : scenes()) {
        SCOPED_TRACE(s.name);
        const GridSpec grid = makeGrid(s.mesh, {s.resolution, 0.0});
        LevelSetOptions parity, winding, udf;
        parity.sign = SignOptions(SignMethod::Parity);
        parity.closestTriangle = true;
        winding.sign = SignOptions(SignMethod::Winding);
        winding.interiorBand = 2.0;
        udf.unsignedDistance = true;
        udf.exteriorBand = 2.5;
        std::vector<LevelSetOptions> kinds = {winding, udf};
        if (closed(s.name)) kinds.push_back(parity);
        for (const auto& ls : kinds) {
            SCOPED_TRACE(ls.unsignedDistance ? "udf" : ls.sign.method == SignMethod::Parity ? "parity" : "winding");
            const DistanceBricks f = field(s.mesh, grid, ls);
            const auto mine = vdb::levelSetNanoGrids(f, ls.exteriorBand, ls.interiorBand, grid);
            ASSERT_EQ(mine.size(), ls.closestTriangle ? 2u : 1u);
            expectSameGrids(mine, vdb::levelSetGrids(f, ls.exteriorBand, ls.interiorBand, grid.voxelSize,
                                                     vdb::makeTransform(grid)));
            expectFilesRoundTrip(mine, s.name + "_field");
        }
    }
}

TEST_P(NanoVdbLayout, SolidsEqualNanoVdbsConverter)
{
    for (const auto& s : scenes()) {
        if (s.name == "cornell") continue;
        SCOPED_TRACE(s.name);
        const GridSpec grid = makeGrid(s.mesh, {s.resolution, 0.0});
        for (const auto method : {SignMethod::Parity, SignMethod::Winding}) {
            if (method == SignMethod::Parity && !closed(s.name)) continue;
            const SolidBricks b = solid(s.mesh, grid, SignOptions(method));
            for (const auto topology : {GridOptions::Topology::Mask, GridOptions::Topology::Bool}) {
                std::vector<NanoHandle> mine;
                mine.push_back(vdb::solidNanoGrid(b, grid, topology));
                expectSame(mine.front(),
                           vdb::toNanoVdb(vdb::withTopology(vdb::solidGrid(b, vdb::makeTransform(grid)), topology)));
                expectFilesRoundTrip(mine, s.name + (topology == GridOptions::Topology::Bool ? "_solid_bool" : "_solid"));
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, NanoVdbLayout, ::testing::Values(Backend::Cpu, Backend::Raster),
                         [](const auto& p) { return p.param == Backend::Cpu ? std::string("Cpu") : std::string("Gl"); });

TEST(NanoVdbLayoutInput, TilesAtBothLevelsAndNegativeOrigins)
{
    // Hand-made: leaves on both sides of the origin, an active 128³ tile, an
    // inactive 8³ tile; NanoVDB's accessors read each back.
    vdb::SparseVoxels<float> s;
    s.background = 2.0f;
    s.origins = {{-8, 0, 0}, {0, -4096, 16}};
    s.masks.resize(2);
    s.masks[0].words[0] = 1; // voxel (-8, 0, 0)
    s.masks[1].words[7] = uint64_t(1) << 63; // voxel (7, -4089, 23)
    s.values.assign(1024, 2.0f);
    s.values[0] = -0.5f;
    s.values[1023] = 0.25f;
    s.tiles.push_back({{128, 128, 128}, 2, 1.5f, true});
    s.tiles.push_back({{-16, 0, 0}, 1, -2.0f, false});
    vdb::NanoGridInfo info;
    info.name = "hand";
    const NanoHandle h = vdb::buildNanoGrid<float>(s, info);
    const auto* g = h.grid<float>();
    ASSERT_TRUE(g);
    EXPECT_TRUE(nanovdb::isValid(*g, true, true));
    expectNanoVdbsOwnStatistics<float>(h);
    auto acc = g->getAccessor();
    EXPECT_EQ(acc.getValue(nanovdb::Coord(-8, 0, 0)), -0.5f);
    EXPECT_TRUE(acc.isActive(nanovdb::Coord(-8, 0, 0)));
    EXPECT_EQ(acc.getValue(nanovdb::Coord(7, -4089, 23)), 0.25f);
    EXPECT_EQ(acc.getValue(nanovdb::Coord(200, 255, 130)), 1.5f);
    EXPECT_TRUE(acc.isActive(nanovdb::Coord(200, 255, 130)));
    EXPECT_EQ(acc.getValue(nanovdb::Coord(-9, 7, 7)), -2.0f);
    EXPECT_FALSE(acc.isActive(nanovdb::Coord(-9, 7, 7)));
    EXPECT_EQ(acc.getValue(nanovdb::Coord(1000, 1000, 1000)), 2.0f);
    EXPECT_EQ(g->activeVoxelCount(), 2u + 128u * 128u * 128u);
    EXPECT_EQ(g->tree().root().minimum(), -0.5f);
    EXPECT_EQ(g->tree().root().maximum(), 1.5f);
}

// A node with no active value has an empty box in NanoVDB (its GridStats,
// and svo's layout as a region's level set makes such nodes), so its
// origin() is no place; NanoVDB's own converter reads it anyway. svo's
// reader places the node from its parent: the values come back where they lie.
TEST(NanoVdbLayoutInput, NodesWithNoActiveValueAreReadWhereTheyLie)
{
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(2.0f);
    grid->setName("inactive nodes");
    grid->tree().setValueOn(openvdb::Coord(1, 2, 3), 0.5f);
    const openvdb::Coord inUpper(5, -4000, -4000), inLower(300, 5, 5); // alone in their upper and lower node
    grid->tree().setValueOff(inUpper, -2.0f);
    grid->tree().setValueOff(inLower, -1.0f);
    std::vector<NanoHandle> nano;
    nano.push_back(vdb::toNanoVdb(grid)); // NanoVDB's own converter
    ASSERT_EQ(nano[0].grid<float>()->getAccessor().getValue(nanovdb::Coord(5, -4000, -4000)), -2.0f);
    test::TempDir dir("nanovdb_layout");
    const std::string path = dir.path("inactive.nvdb");
    vdb::writeNanoVdb(path, nano, vdb::NanoCodec::None);
    const openvdb::GridPtrVec back = vdb::readNanoVdbGrids(path);
    ASSERT_EQ(back.size(), 1u);
    const auto& f = static_cast<const openvdb::FloatGrid&>(*back[0]);
    EXPECT_EQ(f.activeVoxelCount(), 1u);
    for (const openvdb::Coord& c : {inUpper, inLower, openvdb::Coord(1, 2, 3), openvdb::Coord(0, 0, 0)}) {
        EXPECT_EQ(f.tree().getValue(c), grid->tree().getValue(c)) << c;
        EXPECT_EQ(f.tree().isValueOn(c), grid->tree().isValueOn(c)) << c;
    }
    EXPECT_EQ(f.tree().leafCount(), grid->tree().leafCount());
    openvdb::CoordBBox leaves;
    f.tree().evalLeafBoundingBox(leaves);
    openvdb::CoordBBox want;
    grid->tree().evalLeafBoundingBox(want);
    EXPECT_EQ(leaves, want) << "every node where it lies";
}

TEST(NanoVdbLayoutInput, BadInputIsRefused)
{
    vdb::SparseVoxels<float> s;
    s.origins = {{1, 0, 0}};
    s.masks.resize(1);
    EXPECT_THROW(vdb::buildNanoGrid<float>(s, {}), InvalidInput);
    s.origins = {{0, 0, 0}, {0, 0, 0}};
    s.masks.resize(2);
    EXPECT_THROW(vdb::buildNanoGrid<float>(s, {}), InvalidInput);
    s.origins = {{0, 0, 0}};
    s.masks.resize(1);
    s.tiles.push_back({{0, 0, 0}, 1, 0.0f, true});
    EXPECT_THROW(vdb::buildNanoGrid<float>(s, {}), InvalidInput);
}

// A compressed file whose blocks are cut, changed or claim too much is refused
// in one line, never read past its end (the reader is what svo info and svo
// convert use).
TEST(NanoVdbLayoutInput, DamagedCompressedFilesAreRefused)
{
    vdb::SparseVoxels<float> s;
    s.origins = {{0, 0, 0}, {64, -8, 8}};
    s.masks.resize(2);
    for (auto& m : s.masks)
        for (auto& w : m.words) w = 0x00ff00ff00ff00ffull;
    s.values.assign(1024, 0.5f);
    vdb::NanoGridInfo info;
    info.name = "damaged";
    const std::vector<NanoHandle> grids = [&] {
        std::vector<NanoHandle> g;
        g.push_back(vdb::buildNanoGrid<float>(s, info));
        return g;
    }();
    test::TempDir dir("nanovdb_damaged");
    for (const auto codec : {vdb::NanoCodec::Zip, vdb::NanoCodec::Blosc}) {
        if (!vdb::nanoCodecAvailable(codec)) continue;
        const std::string path = dir.path("d" + std::to_string(int(codec)) + ".nvdb");
        vdb::writeNanoVdb(path, grids, codec);
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        ASSERT_EQ(vdb::readNanoVdbGridsFromBytes(bytes, "whole")[0]->activeVoxelCount(), 2u * 256u);
        const auto refused = [&](const std::string& b, const std::string& what) {
            try {
                vdb::readNanoVdbGridsFromBytes(b, "x.nvdb");
                ADD_FAILURE() << what << ": read";
            } catch (const IoError& e) {
                EXPECT_EQ(std::string(e.what()).rfind("x.nvdb: ", 0), 0u) << what << ": " << e.what();
            }
        };
        refused(bytes.substr(0, bytes.size() - 3), "cut");
        std::string changed = bytes;
        changed[changed.size() - 20] ^= 0x5a; // inside the compressed data
        refused(changed, "changed");
    }
}

} // namespace
} // namespace svo
