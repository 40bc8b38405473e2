// Regions (VoxelizeOptions::region, svo/core/region.h): a call given a box
// of whole leaves returns exactly the whole-grid call's result cut to that
// box: the same voxels and attribute values for surfaces, and the same
// active voxels, distances and signs (the whole grid clipped by OpenVDB's
// own Grid::clip) for level sets, unsigned fields and solids, on every
// backend. Boxes are random (seeded), overlap the grid's edges, and one lies
// outside it.
#include <algorithm>
#include <cstring>
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <nanovdb/NanoVDB.h>
#include <openvdb/openvdb.h>
#include <openvdb/util/NullInterrupter.h>

#include "gl_backend.h"
#include "scenes.h"
#include "svo/core/city_scene.h"
#include "svo/core/error.h"
#include "svo/core/field_clip.h"
#include "svo/core/field_join.h"
#include "svo/core/mesh_io.h"
#include "svo/core/octree.h"
#include "svo/core/region.h"
#include "svo/core/voxel_key.h"
#include "svo/svo.h"
#include "regions.h" // the front door's private cut into regions

namespace svo::test {
namespace {

/// Leaf-aligned boxes over the grid's index range and a leaf beyond it on each side.
std::vector<IndexBox> randomRegions(const GridSpec& g, int count, uint64_t seed)
{
    uint64_t state = seed;
    auto next = [&](int64_t n) { // splitmix64, as the city scene uses
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return int64_t((z ^ (z >> 31)) % uint64_t(n));
    };
    std::vector<IndexBox> boxes;
    for (int i = 0; i < count; ++i) {
        IndexBox b;
        for (int a = 0; a < 3; ++a) {
            const int64_t leaves = (int64_t(g.dims[a]) + 7) / 8 + 2;
            const int64_t first = next(leaves), size = 1 + next(leaves - first);
            b.lo[a] = g.anchor[a] - 8 + 8 * first;
            b.hi[a] = b.lo[a] + 8 * size;
        }
        boxes.push_back(b);
    }
    IndexBox outside; // wholly beyond the grid
    for (int a = 0; a < 3; ++a) outside.lo[a] = g.anchor[a] + ((int64_t(g.dims[a]) + 7) / 8 + 4) * 8;
    for (int a = 0; a < 3; ++a) outside.hi[a] = outside.lo[a] + 16;
    boxes.push_back(outside);
    return boxes;
}

bool inRegion(const GridSpec& g, const IndexBox& r, uint64_t key)
{
    const auto local = unpackVoxelKey(key);
    for (int a = 0; a < 3; ++a) {
        const int64_t i = g.anchor[a] + local[a];
        if (i < r.lo[a] || i >= r.hi[a]) return false;
    }
    return true;
}

/// Voxel key -> (normal, triangle) of an octree's attribute channels.
std::map<uint64_t, std::pair<Vec3f, int32_t>> attributesByKey(const Octree& o)
{
    std::map<uint64_t, std::pair<Vec3f, int32_t>> out;
    const auto offsets = brickVoxelOffsets(o);
    for (const BrickRef& r : occupiedBricks(o)) {
        uint64_t at = offsets[r.index];
        const uint64_t base = packVoxelKey(r.origin[0], r.origin[1], r.origin[2]);
        for (uint32_t bit = 0; bit < 512; ++bit)
            if (o.bricks[r.index].words[bit >> 6] >> (bit & 63) & 1) {
                out[base | bit] = {o.attributes.normals[at], o.attributes.triangles[at]};
                ++at;
            }
    }
    return out;
}

std::string describe(const IndexBox& r)
{
    return "region (" + std::to_string(r.lo[0]) + ", " + std::to_string(r.lo[1]) + ", " + std::to_string(r.lo[2]) +
           ") to (" + std::to_string(r.hi[0]) + ", " + std::to_string(r.hi[1]) + ", " + std::to_string(r.hi[2]) + ")";
}

/// Every voxel of the region's grid as the whole grid clipped to the box has it.
void expectSameAsClipped(const openvdb::GridBase& wholeGrid, const openvdb::GridBase& partGrid, const IndexBox& r)
{
    auto clipped = wholeGrid.deepCopyGrid();
    clipped->clip(openvdb::CoordBBox(openvdb::Coord(int32_t(r.lo[0]), int32_t(r.lo[1]), int32_t(r.lo[2])),
                                     openvdb::Coord(int32_t(r.hi[0] - 1), int32_t(r.hi[1] - 1), int32_t(r.hi[2] - 1))));
    EXPECT_EQ(partGrid.activeVoxelCount(), clipped->activeVoxelCount());
    auto compare = [&](const auto& a, const auto& b) {
        uint64_t differ = 0;
        const auto bAcc = b.getConstAccessor();
        const auto aAcc = a.getConstAccessor();
        for (int64_t x = r.lo[0]; x < r.hi[0]; ++x)
            for (int64_t y = r.lo[1]; y < r.hi[1]; ++y)
                for (int64_t z = r.lo[2]; z < r.hi[2]; ++z) {
                    const openvdb::Coord c{int32_t(x), int32_t(y), int32_t(z)};
                    const bool d = aAcc.getValue(c) != bAcc.getValue(c) || aAcc.isValueOn(c) != bAcc.isValueOn(c);
                    if (d && differ < 3)
                        ADD_FAILURE() << partGrid.getName() << " " << c << ": region " << aAcc.getValue(c) << " "
                                      << aAcc.isValueOn(c) << ", whole " << bAcc.getValue(c) << " " << bAcc.isValueOn(c);
                    differ += d;
                }
        EXPECT_EQ(differ, 0u) << "voxels of the box that differ";
        EXPECT_TRUE(a.tree().hasSameTopology(b.tree()));
    };
    if (const auto f = dynamic_cast<const openvdb::FloatGrid*>(&partGrid))
        compare(*f, static_cast<const openvdb::FloatGrid&>(*clipped));
    else if (const auto m = dynamic_cast<const openvdb::MaskGrid*>(&partGrid))
        compare(*m, static_cast<const openvdb::MaskGrid&>(*clipped));
    else if (const auto i = dynamic_cast<const openvdb::Int32Grid*>(&partGrid))
        compare(*i, static_cast<const openvdb::Int32Grid&>(*clipped));
    else
        ADD_FAILURE() << "unexpected grid type " << partGrid.type();
}

TriangleMesh holedSphere()
{
    TriangleMesh m = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    std::vector<std::array<uint32_t, 3>> kept;
    for (const auto& t : m.triangles)
        if (m.positions[t[0]].z < 1.0 || m.positions[t[1]].z < 1.0 || m.positions[t[2]].z < 1.0) kept.push_back(t);
    m.triangles = kept;
    m.source = "holed sphere";
    return m;
}

TriangleMesh smallCity()
{
    CityOptions o;
    o.triangles = 5000;
    o.seed = 7;
    return cityScene(o);
}

class Regions : public ::testing::TestWithParam<Backend> {};

TEST_P(Regions, SurfacesAndAttributesAreTheWholeGridsCutToTheBox)
{
    Voxelizer v;
    for (const TriangleMesh& mesh : {icosphere({0.1, -0.2, 0.3}, 1.0, 3), smallCity()}) {
        SCOPED_TRACE(mesh.source);
        const GridSpec grid = makeGrid(mesh, GridRequest{56, 0});
        VoxelizeOptions o;
        o.backend = GetParam();
        o.attributes = kNormals | kTriangles;
        const Octree whole = v.voxelize(mesh, grid, o);
        const auto wholeKeys = octreeKeys(whole);
        const auto wholeValues = attributesByKey(whole);
        ASSERT_GT(wholeKeys.size(), 1000u);
        for (const IndexBox& r : randomRegions(grid, 6, 11)) {
            SCOPED_TRACE(describe(r));
            o.region = r;
            const Octree part = v.voxelize(mesh, grid, o);
            std::vector<uint64_t> expected;
            for (uint64_t k : wholeKeys)
                if (inRegion(grid, r, k)) expected.push_back(k);
            EXPECT_EQ(octreeKeys(part), expected);
            EXPECT_TRUE(checkOctree(part).empty());
            uint64_t differ = 0;
            for (const auto& [key, value] : attributesByKey(part)) {
                const auto& w = wholeValues.at(key);
                differ += !(w.first.x == value.first.x && w.first.y == value.first.y && w.first.z == value.first.z) ||
                          w.second != value.second;
            }
            EXPECT_EQ(differ, 0u) << "voxels whose attributes differ";
            EXPECT_EQ(part.channels(), kNormals | kTriangles);
        }
        // A region no triangle reaches still has the channels, with no values.
        o.region = IndexBox{{1 << 20, 1 << 20, 1 << 20}, {(1 << 20) + 8, (1 << 20) + 8, (1 << 20) + 8}};
        const Octree none = v.voxelize(mesh, grid, o);
        EXPECT_EQ(none.voxelCount(), 0u);
        EXPECT_EQ(none.channels(), kNormals | kTriangles);
        EXPECT_TRUE(checkOctree(none).empty());
    }
}

/// The region's NanoVDB level set and solid (levelSetNanoVdb, solidNanoVdb
/// with the region: the region's bricks cut to it and laid out, no OpenVDB
/// tree) hold the OpenVDB grids' values and active states at every voxel of
/// @a r, and nothing beyond it. The level set's signs beyond the band come
/// from the parity runs (levelSetNanoGrids), not a flood fill of a band cut
/// at the region's sides.
void expectSameNanoGrids(Voxelizer& v, const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& o,
                         const openvdb::FloatGrid& sdf, const openvdb::MaskGrid& solid, const IndexBox& r)
{
    const auto nanoSdf = v.levelSetNanoVdb(mesh, grid, {}, o);
    const vdb::NanoHandle nanoSolid = v.solidNanoVdb(mesh, grid, o);
    const auto sdfAcc = nanoSdf.front().grid<float>()->getAccessor();
    const auto solidAcc = nanoSolid.grid<nanovdb::ValueMask>()->getAccessor();
    const auto wantSdf = sdf.getConstAccessor();
    const auto wantSolid = solid.getConstAccessor();
    uint64_t differ = 0;
    for (int64_t x = r.lo[0]; x < r.hi[0]; ++x)
        for (int64_t y = r.lo[1]; y < r.hi[1]; ++y)
            for (int64_t z = r.lo[2]; z < r.hi[2]; ++z) {
                const openvdb::Coord c{int32_t(x), int32_t(y), int32_t(z)};
                const nanovdb::Coord n(c.x(), c.y(), c.z());
                differ += sdfAcc.getValue(n) != wantSdf.getValue(c) || sdfAcc.isActive(n) != wantSdf.isValueOn(c);
                differ += solidAcc.isActive(n) != wantSolid.isValueOn(c);
            }
    EXPECT_EQ(differ, 0u) << "voxels of the region's NanoVDB grids that are not its OpenVDB grids'";
    EXPECT_EQ(nanoSdf.front().gridMetaData()->activeVoxelCount(), sdf.activeVoxelCount()) << "the level set's, in all";
    EXPECT_EQ(nanoSolid.gridMetaData()->activeVoxelCount(), solid.activeVoxelCount()) << "the solid's, in all";
}

TEST_P(Regions, LevelSetsUdfsAndSolidsAreTheWholeGridsCutToTheBox)
{
    Voxelizer v;
    // Closed (parity signs: a column's crossings below the box count), open
    // and mixed (winding numbers from the whole mesh's tree).
    for (const TriangleMesh& mesh : {icosphere({0.1, -0.2, 0.3}, 1.0, 3), holedSphere(), smallCity()}) {
        SCOPED_TRACE(mesh.source);
        const GridSpec grid = makeGrid(mesh, GridRequest{40, 0});
        VoxelizeOptions o;
        o.backend = GetParam() == Backend::Cpu ? Backend::Cpu : kGl;
        LevelSetOptions sdf, udf;
        udf.unsignedDistance = true;
        const auto wholeSdf = v.levelSet(mesh, grid, sdf, o);
        const auto wholeUdf = v.levelSet(mesh, grid, udf, o);
        const auto wholeSolid = v.solid(mesh, grid, o);
        for (const IndexBox& r : randomRegions(grid, 4, 23)) {
            SCOPED_TRACE(describe(r));
            o.region = r;
            const auto sdfPart = v.levelSet(mesh, grid, sdf, o);
            ASSERT_EQ(sdfPart.size(), wholeSdf.size());
            for (size_t i = 0; i < sdfPart.size(); ++i) expectSameAsClipped(*wholeSdf[i], *sdfPart[i], r);
            const auto udfPart = v.levelSet(mesh, grid, udf, o);
            for (size_t i = 0; i < udfPart.size(); ++i) expectSameAsClipped(*wholeUdf[i], *udfPart[i], r);
            const auto solidPart = v.solid(mesh, grid, o);
            expectSameAsClipped(*wholeSolid, *solidPart, r);
            expectSameNanoGrids(v, mesh, grid, o, static_cast<const openvdb::FloatGrid&>(*sdfPart.front()), *solidPart, r);
        }
        o.region.reset();
    }
}

// The band's bricks are those of the triangles' grown boxes near their
// planes; on CGAL's fandisk at 96³ some lie wholly inside with no voxel
// in the band, between no two band bricks of their column (so in no parity
// run). A region has no flood fill to sign them: its level set keeps their
// inside values, on the OpenVDB and NanoVDB paths, cut by the call or by a
// budget.
TEST_P(Regions, AParityRegionSignsBandBricksWithNoVoxelInTheBand)
{
    Voxelizer v;
    const TriangleMesh mesh = loadMesh(std::string(SVO_CGAL_MESHES) + "/fandisk.off");
    const GridSpec grid = makeGrid(mesh, GridRequest{96, 0});
    VoxelizeOptions o;
    o.backend = GetParam() == Backend::Cpu ? Backend::Cpu : kGl;
    const auto wholeSdf = v.levelSet(mesh, grid, {}, o);
    const auto wholeSolid = v.solid(mesh, grid, o);
    const IndexBox half{{0, -128, -128}, {128, 128, 128}}; // the grid is centred on the origin
    o.region = half;
    const auto sdfPart = v.levelSet(mesh, grid, {}, o);
    expectSameAsClipped(*wholeSdf.front(), *sdfPart.front(), half);
    const auto solidPart = v.solid(mesh, grid, o);
    expectSameNanoGrids(v, mesh, grid, o, static_cast<const openvdb::FloatGrid&>(*sdfPart.front()), *solidPart, half);
    if (GetParam() == Backend::Cpu) return; // a budget is the GPU's
    VoxelizeStats stats;
    o = onGl(&stats);
    o.gpuMemory = 1 << 20;
    const auto tiledSdf = v.levelSet(mesh, grid, {}, o);
    EXPECT_GE(stats.tiles, 2u) << "the budget cut the grid";
    const IndexBox all{{-128, -128, -128}, {128, 128, 128}};
    expectSameAsClipped(*wholeSdf.front(), *tiledSdf.front(), all);
}

/// The triangles of @a mesh whose local box, grown by @a margin voxels,
/// meets the columns of region @a r in x and y, whatever their height: what
/// a task of svo.distributed gets for a level set or solid signed by parity.
TriangleMesh columnsPart(const TriangleMesh& mesh, const GridSpec& grid, const IndexBox& r, double margin)
{
    TriangleMesh part = mesh;
    part.triangles.clear();
    for (const auto& t : mesh.triangles) {
        bool meets = true;
        for (int a = 0; a < 2; ++a) {
            double lo = 1e300, hi = -1e300;
            for (uint32_t v : t) {
                const double i = grid.toIndex(mesh.positions[v])[a];
                lo = std::min(lo, i), hi = std::max(hi, i);
            }
            meets = meets && hi + margin >= double(r.lo[a]) && lo - margin <= double(r.hi[a] - 1);
        }
        if (meets) part.triangles.push_back(t);
    }
    part.source = mesh.source + " (the region's columns)";
    return part;
}

TEST_P(Regions, ParitySignsNeedOnlyTheTrianglesOfTheRegionsColumns)
{
    // A closed mesh cut to a region's z columns is open at its sides: parity
    // asked for it is refused, and SignOptions::partOfClosedMesh takes it
    // unchecked. The part's region is then the whole mesh's, clipped.
    Voxelizer v;
    const TriangleMesh mesh = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    const GridSpec grid = makeGrid(mesh, GridRequest{40, 0});
    VoxelizeOptions o;
    o.backend = GetParam() == Backend::Cpu ? Backend::Cpu : kGl;
    LevelSetOptions sdf;
    const auto wholeSdf = v.levelSet(mesh, grid, sdf, o);
    const auto wholeSolid = v.solid(mesh, grid, o);
    SignOptions part;
    part.partOfClosedMesh = true;
    sdf.sign = part;
    uint64_t cut = 0;
    for (const IndexBox& r : randomRegions(grid, 4, 29)) {
        SCOPED_TRACE(describe(r));
        o.region = r;
        const TriangleMesh columns = columnsPart(mesh, grid, r, sdf.exteriorBand + 2);
        if (columns.triangles.empty() || columns.triangles.size() == mesh.triangles.size()) continue;
        ++cut;
        EXPECT_THROW(v.solid(columns, grid, o, SignOptions(SignMethod::Parity)), InvalidInput);
        const auto sdfPart = v.levelSet(columns, grid, sdf, o);
        ASSERT_EQ(sdfPart.size(), wholeSdf.size());
        for (size_t i = 0; i < sdfPart.size(); ++i) expectSameAsClipped(*wholeSdf[i], *sdfPart[i], r);
        expectSameAsClipped(*wholeSolid, *v.solid(columns, grid, o, part), r);
    }
    EXPECT_GE(cut, 2u) << "regions whose columns hold a part of the mesh";
    part.method = SignMethod::Winding;
    EXPECT_THROW(v.solid(mesh, grid, o, part), InvalidInput);
}


/// Whether two NanoVDB grids are the same bytes (their checksums included).
bool sameBytes(const vdb::NanoHandle& a, const vdb::NanoHandle& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size()) == 0;
}

// Past a GPU memory budget, level sets and solids are computed in regions
// and joined: the whole grid's result, value for value.
TEST(RegionsTiles, LevelSetsAndSolidsWithinAGpuBudgetAreTheWholeGrids)
{
    Voxelizer v;
    for (const TriangleMesh& mesh : {icosphere({0.1, -0.2, 0.3}, 1.0, 3), holedSphere()}) {
        SCOPED_TRACE(mesh.source);
        const GridSpec grid = makeGrid(mesh, GridRequest{48, 0});
        VoxelizeStats stats;
        VoxelizeOptions whole = onGl(&stats), tiled = onGl(&stats);
        tiled.gpuMemory = 1 << 20; // above the surface pass's smallest, below the fields' whole band
        const auto wholeSdf = v.levelSet(mesh, grid, {}, whole);
        ASSERT_EQ(stats.tiles, 1u);
        const auto tiledSdf = v.levelSet(mesh, grid, {}, tiled);
        EXPECT_GE(stats.tiles, 2u) << "the budget cut the grid";
        const IndexBox all{{grid.anchor[0] - 16, grid.anchor[1] - 16, grid.anchor[2] - 16},
                           {grid.anchor[0] + 72, grid.anchor[1] + 72, grid.anchor[2] + 72}};
        expectSameAsClipped(*wholeSdf.front(), *tiledSdf.front(), all);
        const auto wholeSolid = v.solid(mesh, grid, whole);
        const auto tiledSolid = v.solid(mesh, grid, tiled);
        EXPECT_GT(stats.tiles, 1u);
        expectSameAsClipped(*wholeSolid, *tiledSolid, all);
        // The NanoVDB calls join the regions' bricks: the whole grid's
        // grids, byte for byte (the whole grid's built on the GPU), for
        // unsigned and signed fields and for solids.
        LevelSetOptions udf;
        udf.unsignedDistance = true;
        udf.closestTriangle = true;
        LevelSetOptions sdf;
        sdf.closestTriangle = true;
        for (const LevelSetOptions& ls : {udf, sdf}) {
            SCOPED_TRACE(ls.unsignedDistance ? "udf" : "sdf");
            const auto wholeNano = v.levelSetNanoVdb(mesh, grid, ls, whole);
            ASSERT_EQ(stats.tiles, 1u);
            const auto tiledNano = v.levelSetNanoVdb(mesh, grid, ls, tiled);
            EXPECT_GE(stats.tiles, 2u);
            ASSERT_EQ(tiledNano.size(), 2u);
            ASSERT_EQ(wholeNano.size(), 2u);
            for (size_t i = 0; i < 2; ++i) EXPECT_TRUE(sameBytes(wholeNano[i], tiledNano[i])) << "grid " << i;
        }
        for (auto topology : {GridOptions::Topology::Mask, GridOptions::Topology::Bool}) {
            const auto wholeNano = v.solidNanoVdb(mesh, grid, whole, {}, topology);
            ASSERT_EQ(stats.tiles, 1u);
            const auto tiledNano = v.solidNanoVdb(mesh, grid, tiled, {}, topology);
            EXPECT_GE(stats.tiles, 2u);
            EXPECT_TRUE(sameBytes(wholeNano, tiledNano)) << "solid";
        }
        tiled.gpuMemory = 1024; // less than the mesh itself
        try {
            v.levelSet(mesh, grid, {}, tiled);
            ADD_FAILURE() << "a budget below the mesh's triangles was not refused";
        } catch (const OutOfMemory& e) { // what needs the room, and what to do
            EXPECT_NE(std::string(e.what()).find("budget of 1.0 KiB cannot hold"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::to_string(mesh.triangles.size()) + " triangles"), std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find("raise the budget"), std::string::npos) << e.what();
        }
        EXPECT_THROW(v.levelSetNanoVdb(mesh, grid, udf, tiled), OutOfMemory);
    }
}

/// Every percentage a call reports.
struct Percentages : openvdb::util::NullInterrupter {
    bool wasInterrupted(int percent) override
    {
        seen.push_back(percent);
        return false;
    }
    std::vector<int> seen;
};

// Past a budget, each region reports on its share of the call: the
// percentage climbs once across the regions, not from 0 in each, on the
// OpenVDB and NanoVDB paths.
TEST(RegionsTiles, ProgressClimbsOnceAcrossTheRegions)
{
    Voxelizer v;
    const TriangleMesh mesh = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    const GridSpec grid = makeGrid(mesh, GridRequest{48, 0});
    VoxelizeStats stats;
    VoxelizeOptions o = onGl(&stats);
    o.gpuMemory = 1 << 20;
    auto expectClimbs = [&](const char* call, auto&& run) {
        Percentages p;
        o.interrupter = &p;
        run();
        EXPECT_GE(stats.tiles, 2u) << call;
        EXPECT_TRUE(std::is_sorted(p.seen.begin(), p.seen.end())) << call << ": percentages only grow " << ::testing::PrintToString(p.seen);
        EXPECT_GT(std::set<int>(p.seen.begin(), p.seen.end()).size(), 2 * size_t(stats.tiles)) << call;
        ASSERT_FALSE(p.seen.empty());
        EXPECT_EQ(p.seen.back(), 100) << call;
    };
    expectClimbs("levelSet", [&] { v.levelSet(mesh, grid, {}, o); });
    expectClimbs("solid", [&] { v.solid(mesh, grid, o); });
    expectClimbs("levelSetNanoVdb", [&] { v.levelSetNanoVdb(mesh, grid, {}, o); });
    expectClimbs("solidNanoVdb", [&] { v.solidNanoVdb(mesh, grid, o); });
}

// The mechanism: a region's run reports on its columns' share of the box,
// after the regions done; a run cut smaller after a try starts again from
// its share's start without the percentage going back.
TEST(RegionsTiles, EachRegionReportsOnItsColumnsShare)
{
    std::vector<int> seen;
    const Checkpoint checkpoint([&](int percent) {
        seen.push_back(percent);
        return false;
    });
    const IndexBox box{{0, 0, 0}, {64, 32, 16}};
    detail::RegionProgress progress(checkpoint, box);
    const IndexBox left{{0, 0, 0}, {16, 32, 16}}, right{{16, 0, 0}, {64, 32, 16}};
    progress.of(left)(0.5);
    progress.finished(left);
    progress.of(right)(0.0);
    progress.of(right)(0.5);
    EXPECT_EQ(seen, (std::vector<int>{12, 25, 62}));
    // A box the run refuses past 16 voxels wide: cut to four regions, each
    // reporting half way and done; the first try's report is held.
    seen.clear();
    uint32_t tiles = 0;
    auto run = [&](const IndexBox& b, const Checkpoint& c) {
        c(0.5);
        if (b.hi[0] - b.lo[0] > 16) throw OutOfMemory("past the budget");
        c(1.0);
        return 0;
    };
    auto join = [](int&, int) {};
    detail::allRegions(run, join, box, checkpoint, tiles);
    EXPECT_EQ(tiles, 4u);
    EXPECT_EQ(seen, (std::vector<int>{50, 50, 50, 50, 50, 50, 75, 75, 75, 87, 100})) << ::testing::PrintToString(seen);
}

// A solid's band grows a voxel from its surface, so a region's brick can be
// in the band for a surface voxel just beyond the region's side: CGAL's
// elephant at 100³ cut by a budget has such bricks. The regions' solid is
// still the whole grid's, byte for byte (leaves where its leaves are, tiles
// where its tiles are).
TEST(RegionsTiles, ASolidsBandAtARegionsSideIsTheWholeGrids)
{
    Voxelizer v;
    const TriangleMesh mesh = loadMesh(std::string(SVO_CGAL_MESHES) + "/elephant.off");
    const GridSpec grid = makeGrid(mesh, GridRequest{100, 0});
    VoxelizeStats stats;
    VoxelizeOptions whole = onGl(&stats), tiled = onGl(&stats);
    tiled.gpuMemory = 1 << 20;
    const auto wholeNano = v.solidNanoVdb(mesh, grid, whole);
    ASSERT_EQ(stats.tiles, 1u);
    const auto tiledNano = v.solidNanoVdb(mesh, grid, tiled);
    EXPECT_GE(stats.tiles, 2u);
    EXPECT_TRUE(sameBytes(wholeNano, tiledNano));
    EXPECT_EQ(wholeNano.gridMetaData()->activeVoxelCount(), tiledNano.gridMetaData()->activeVoxelCount());
}

/// SVO_GL_MAX_BUFFER set for one scope: a driver that refuses buffers past
/// `bytes` although the budget promised more.
struct DriverRefusesBuffersPast {
    explicit DriverRefusesBuffersPast(uint64_t bytes) { setenv("SVO_GL_MAX_BUFFER", std::to_string(bytes).c_str(), 1); }
    ~DriverRefusesBuffersPast() { unsetenv("SVO_GL_MAX_BUFFER"); }
};

TEST(RegionsTiles, ABudgetTheDeviceCannotAllocateIsTiledNotRefused)
{
    Voxelizer v;
    const TriangleMesh mesh = smallCity();
    const GridSpec grid = makeGrid(mesh, GridRequest{200, 0});
    VoxelizeOptions cpu;
    cpu.backend = Backend::Cpu;
    const auto expected = octreeKeys(v.voxelize(mesh, grid, cpu));
    ASSERT_GT(expected.size(), 10000u);
    // Tiled first: a scratch buffer already as large as the whole grid's
    // pass is reused without a new allocation, so it would not be refused.
    std::vector<std::vector<uint64_t>> tiled;
    for (Backend backend : {Backend::Raster, Backend::Compute}) {
        SCOPED_TRACE(nameOf(backend));
        VoxelizeStats stats;
        VoxelizeOptions o;
        o.backend = backend;
        o.stats = &stats;
        o.gpuMemory = uint64_t(1) << 40; // far more than the driver gives
        const DriverRefusesBuffersPast driver(256 << 10);
        const Octree octree = v.voxelize(mesh, grid, o);
        EXPECT_GT(stats.tiles, 1u) << "the refused allocation cut the grid";
        EXPECT_TRUE(checkOctree(octree).empty());
        tiled.push_back(octreeKeys(octree));
    }
    for (Backend backend : {Backend::Raster, Backend::Compute}) {
        SCOPED_TRACE(nameOf(backend));
        VoxelizeOptions o;
        o.backend = backend;
        const auto whole = octreeKeys(v.voxelize(mesh, grid, o));
        const auto& keys = tiled[backend == Backend::Raster ? 0 : 1];
        EXPECT_EQ(keys.size(), whole.size());
        EXPECT_TRUE(keys == whole) << "the tiled voxels are the whole grid's";
        // The GPU against the CPU reference (known: 2 voxels apart on this city, see the note on issue 43).
        EXPECT_LE(std::max(whole.size(), expected.size()) - std::min(whole.size(), expected.size()), 2u);
    }
    {
        VoxelizeOptions o = onGl();
        o.gpuMemory = uint64_t(1) << 40;
        const DriverRefusesBuffersPast driver(16); // not even the mesh
        EXPECT_THROW(v.voxelize(mesh, grid, o), OutOfMemory);
    }
}

/// SVO_GL_MAX_STORAGE_BLOCK set for one scope: a driver whose shaders address
/// no more than `bytes` of one buffer (GL_MAX_SHADER_STORAGE_BLOCK_SIZE).
struct ShadersAddressNoMoreThan {
    explicit ShadersAddressNoMoreThan(uint64_t bytes)
    {
        setenv("SVO_GL_MAX_STORAGE_BLOCK", std::to_string(bytes).c_str(), 1);
    }
    ~ShadersAddressNoMoreThan() { unsetenv("SVO_GL_MAX_STORAGE_BLOCK"); }
};

// Past what one shader buffer holds (the 4096³ bunny's band on an H200),
// level sets, UDFs and solids are computed in regions with no budget given:
// the whole grid's result, value for value; the NanoVDB calls too, with a
// warning that says so.
TEST(RegionsTiles, FieldsPastOneShaderBufferAreCutIntoRegions)
{
    Voxelizer v;
    const TriangleMesh mesh = holedSphere(); // open: winding-number signs
    const GridSpec grid = makeGrid(mesh, GridRequest{48, 0});
    VoxelizeStats stats;
    const VoxelizeOptions o = onGl(&stats);
    LevelSetOptions udf;
    udf.unsignedDistance = true;
    const auto wholeSdf = v.levelSet(mesh, grid, {}, o);
    const auto wholeUdf = v.levelSet(mesh, grid, udf, o);
    const auto wholeSolid = v.solid(mesh, grid, o);
    const auto wholeNano = v.levelSetNanoVdb(mesh, grid, udf, o);
    const auto wholeSdfNano = v.levelSetNanoVdb(mesh, grid, {}, o);
    const auto wholeSolidNano = v.solidNanoVdb(mesh, grid, o);
    ASSERT_EQ(stats.tiles, 1u);
    const IndexBox all{{grid.anchor[0] - 16, grid.anchor[1] - 16, grid.anchor[2] - 16},
                       {grid.anchor[0] + 72, grid.anchor[1] + 72, grid.anchor[2] + 72}};
    const ShadersAddressNoMoreThan driver(64 << 10); // 32 bricks of distances; the band has hundreds
    expectSameAsClipped(*wholeSdf.front(), *v.levelSet(mesh, grid, {}, o).front(), all);
    EXPECT_GE(stats.tiles, 2u) << "the limit cut the grid";
    auto saysRegions = [&] {
        return std::count_if(stats.warnings.begin(), stats.warnings.end(), [](const std::string& w) {
            return w.find("one GPU buffer does not hold") != std::string::npos;
        });
    };
    EXPECT_EQ(saysRegions(), 1) << "no budget asked for the cut: a warning says why it was made";
    expectSameAsClipped(*wholeUdf.front(), *v.levelSet(mesh, grid, udf, o).front(), all);
    EXPECT_GE(stats.tiles, 2u);
    EXPECT_EQ(saysRegions(), 1);
    expectSameAsClipped(*wholeSolid, *v.solid(mesh, grid, o), all);
    EXPECT_GE(stats.tiles, 2u); // the surface pass's own tiles, past the limit

    const auto nano = v.levelSetNanoVdb(mesh, grid, udf, o);
    EXPECT_GE(stats.tiles, 2u);
    ASSERT_EQ(nano.size(), 1u);
    EXPECT_TRUE(sameBytes(nano.front(), wholeNano.front())) << "the regions' grid is the whole grid's, byte for byte";
    ASSERT_EQ(stats.warnings.size(), 1u);
    EXPECT_EQ(saysRegions(), 1) << stats.warnings.front();
    const auto sdfNano = v.levelSetNanoVdb(mesh, grid, {}, o);
    EXPECT_GE(stats.tiles, 2u);
    EXPECT_TRUE(sameBytes(sdfNano.front(), wholeSdfNano.front())) << "the level set's regions";
    EXPECT_EQ(saysRegions(), 1);
    const auto solidNano = v.solidNanoVdb(mesh, grid, o);
    EXPECT_GE(stats.tiles, 2u);
    EXPECT_TRUE(sameBytes(solidNano, wholeSolidNano)) << "the solid's regions";
    const auto* distances = nano.front().grid<float>();
    ASSERT_NE(distances, nullptr);
    const auto& want = static_cast<const openvdb::FloatGrid&>(*wholeUdf.front());
    EXPECT_EQ(distances->activeVoxelCount(), want.activeVoxelCount());
    const auto acc = distances->getAccessor();
    uint64_t differ = 0;
    for (auto it = want.cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        const nanovdb::Coord n(c.x(), c.y(), c.z());
        differ += !acc.isActive(n) || acc.getValue(n) != *it;
    }
    EXPECT_EQ(differ, 0u) << "voxels of the NanoVDB grid that are not the whole grid's";
}

// Joining regions' unsigned fields on their bricks refuses what is not two
// parts of one unsigned field, and keeps the bricks sorted with their values.
TEST(RegionsJoin, UnsignedFieldsJoinInBrickOrderAndRefuseTheRest)
{
    auto field = [](std::vector<BrickCoord> bricks, float base) {
        DistanceBricks f;
        f.signedField = false;
        f.grid.dims = {64, 64, 64};
        f.bricks = bricks;
        for (size_t i = 0; i < bricks.size(); ++i) {
            Brick near;
            near.words[0] = 0b101; // voxels 0 and 2
            f.near.push_back(near);
            f.offsets.push_back(uint32_t(f.distances.size()));
            f.distances.push_back(base + float(i));
            f.distances.push_back(base + float(i) + 0.5f);
        }
        return f;
    };
    DistanceBricks a = field({{0, 0, 0}, {0, 0, 3}, {2, 1, 0}}, 10.0f);
    a.closestTriangle = true;
    a.closest = {1, 2, 3, 4, 5, 6};
    DistanceBricks b = field({{0, 0, 1}, {1, 0, 0}, {3, 0, 0}}, 20.0f);
    b.closestTriangle = true;
    b.closest = {7, 8, 9, 10, 11, 12};
    joinFields(a, std::move(b));
    const std::vector<BrickCoord> order{{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {1, 0, 0}, {2, 1, 0}, {3, 0, 0}};
    EXPECT_EQ(a.bricks, order);
    EXPECT_EQ(a.offsets, (std::vector<uint32_t>{0, 2, 4, 6, 8, 10}));
    EXPECT_EQ(a.distances, (std::vector<float>{10, 10.5f, 20, 20.5f, 11, 11.5f, 21, 21.5f, 12, 12.5f, 22, 22.5f}));
    EXPECT_EQ(a.closest, (std::vector<int32_t>{1, 2, 7, 8, 3, 4, 9, 10, 5, 6, 11, 12}));
    EXPECT_TRUE(b.bricks.empty());

    DistanceBricks same = field({{2, 1, 0}}, 0.0f);
    same.closestTriangle = true;
    same.closest = {0, 0};
    EXPECT_THROW(joinFields(a, std::move(same)), InvalidInput) << "a brick in both";
    DistanceBricks other = field({{5, 5, 5}}, 0.0f);
    other.closestTriangle = true;
    other.closest = {0, 0};
    other.grid.anchor = {8, 0, 0};
    EXPECT_THROW(joinFields(a, std::move(other)), InvalidInput) << "another grid";
    DistanceBricks withoutClosest = field({{5, 5, 5}}, 0.0f);
    EXPECT_THROW(joinFields(a, std::move(withoutClosest)), InvalidInput) << "another request";
    DistanceBricks signedField = field({{5, 5, 5}}, 0.0f);
    signedField.signedField = true;
    signedField.closestTriangle = true;
    signedField.closest = {0, 0};
    EXPECT_THROW(joinFields(a, std::move(signedField)), InvalidInput) << "a signed field";
}

// Signed fields and solids join with their signs: the inside voxels brick by
// brick, and beyond the band the runs, inside bricks and partly inside
// bricks of both, sorted; a brick in both lists, or fields of other kinds, are refused.
TEST(RegionsJoin, SignsAndSolidsJoinWithTheirBricks)
{
    auto brick = [](uint64_t word) {
        Brick b;
        b.words[1] = word;
        return b;
    };
    auto signs = [&](std::vector<BrickCoord> inside, std::vector<BrickCoord> partial, std::vector<BrickCoord> runs) {
        FieldSigns s;
        s.insideBricks = inside;
        for (const auto& p : partial) s.partial.push_back({p, brick(p[0] + 100)});
        for (const auto& r : runs) s.runs.push_back({r, 2, ~uint64_t(0)});
        s.openColumns = 1;
        return s;
    };
    auto field = [&](std::vector<BrickCoord> bricks, FieldSigns s) {
        DistanceBricks f;
        f.winding = true;
        f.grid.dims = {64, 64, 64};
        f.bricks = bricks;
        f.signs = std::move(s);
        for (const auto& b : bricks) {
            f.near.push_back(brick(1));
            f.offsets.push_back(uint32_t(f.distances.size()));
            f.distances.push_back(float(b[0]));
            f.signs.inside.push_back(brick(b[0] + 10));
        }
        return f;
    };
    DistanceBricks a = field({{0, 0, 0}, {2, 0, 0}}, signs({{0, 2, 2}}, {{4, 0, 0}}, {{0, 1, 1}}));
    DistanceBricks b = field({{1, 0, 0}, {3, 0, 0}}, signs({{1, 2, 2}}, {{3, 3, 3}}, {{1, 1, 1}}));
    joinFields(a, std::move(b));
    EXPECT_EQ(a.bricks, (std::vector<BrickCoord>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}));
    EXPECT_EQ(a.distances, (std::vector<float>{0, 1, 2, 3}));
    ASSERT_EQ(a.signs.inside.size(), 4u);
    for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(a.signs.inside[i].words[1], 10u + i) << "brick " << i;
    EXPECT_EQ(a.signs.insideBricks, (std::vector<BrickCoord>{{0, 2, 2}, {1, 2, 2}}));
    ASSERT_EQ(a.signs.partial.size(), 2u);
    EXPECT_EQ(a.signs.partial[0].first, (BrickCoord{3, 3, 3}));
    EXPECT_EQ(a.signs.partial[0].second.words[1], 103u);
    EXPECT_EQ(a.signs.partial[1].first, (BrickCoord{4, 0, 0}));
    ASSERT_EQ(a.signs.runs.size(), 2u);
    EXPECT_EQ(a.signs.runs[1].first, (BrickCoord{1, 1, 1}));
    EXPECT_EQ(a.signs.openColumns, 2u);
    EXPECT_TRUE(a.winding && a.signedField);

    DistanceBricks twice = field({{7, 0, 0}}, signs({{1, 2, 2}}, {}, {}));
    EXPECT_THROW(joinFields(a, std::move(twice)), InvalidInput) << "an inside brick in both";
    DistanceBricks parity = field({{7, 0, 0}}, {});
    parity.winding = false;
    EXPECT_THROW(joinFields(a, std::move(parity)), InvalidInput) << "another sign method";
    DistanceBricks noSigns = field({{7, 0, 0}}, {});
    noSigns.signs.inside.clear();
    EXPECT_THROW(joinFields(a, std::move(noSigns)), InvalidInput) << "no inside voxels for its bricks";

    auto solid = [&](std::vector<BrickCoord> bricks, FieldSigns s) {
        SolidBricks out;
        out.grid.dims = {64, 64, 64};
        out.bricks = bricks;
        out.signs = std::move(s);
        for (const auto& c : bricks) out.signs.inside.push_back(brick(c[1] + 20));
        return out;
    };
    SolidBricks sa = solid({{0, 0, 0}, {0, 2, 0}}, signs({}, {}, {{0, 0, 1}}));
    SolidBricks sb = solid({{0, 1, 0}}, signs({}, {}, {{0, 1, 1}}));
    joinSolids(sa, std::move(sb));
    EXPECT_EQ(sa.bricks, (std::vector<BrickCoord>{{0, 0, 0}, {0, 1, 0}, {0, 2, 0}}));
    ASSERT_EQ(sa.signs.inside.size(), 3u);
    for (uint32_t i = 0; i < 3; ++i) EXPECT_EQ(sa.signs.inside[i].words[1], 20u + i);
    EXPECT_EQ(sa.signs.runs.size(), 2u);
    EXPECT_TRUE(sb.bricks.empty());
    SolidBricks again = solid({{0, 1, 0}}, {});
    EXPECT_THROW(joinSolids(sa, std::move(again)), InvalidInput) << "a band brick in both";
    SolidBricks runTwice = solid({{5, 5, 5}}, signs({}, {}, {{0, 1, 1}}));
    EXPECT_THROW(joinSolids(sa, std::move(runTwice)), InvalidInput) << "a run in both";
}

// A field cut to a box keeps its bricks inside with their values, wherever
// those lie in the packed arrays (the GPU packs bricks in the order its work
// groups finish, not in brick order), and its parity runs cut in z; a solid
// alike.
TEST(RegionsClip, AFieldCutToABoxKeepsItsBricksValuesWhereverTheyLie)
{
    DistanceBricks f;
    f.grid.dims = {64, 64, 64};
    f.closestTriangle = true;
    f.bricks = {{0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {1, 0, 0}};
    for (size_t i = 0; i < f.bricks.size(); ++i) {
        Brick near;
        near.words[0] = 0b11; // two values a brick
        f.near.push_back(near);
        Brick in;
        in.words[2] = i + 1;
        f.signs.inside.push_back(in);
    }
    f.offsets = {6, 4, 0, 2}; // brick 2's values first, brick 0's last
    f.distances = {20, 21, 30, 31, 10, 11, 0, 1};
    f.closest = {120, 121, 130, 131, 110, 111, 100, 101};
    f.signs.runs = {{{0, 1, 0}, 8, ~uint64_t(0)}, {{1, 1, 0}, 2, 5}};
    f.signs.insideBricks = {{0, 2, 0}, {1, 2, 0}};
    BrickBox box;
    box.lo = {0, 0, 1};
    box.hi = {1, 8, 4}; // x 0, z 1 to 3: bricks 1 and 2
    clipField(f, box);
    EXPECT_EQ(f.bricks, (std::vector<BrickCoord>{{0, 0, 1}, {0, 0, 2}}));
    EXPECT_EQ(f.offsets, (std::vector<uint32_t>{0, 2}));
    EXPECT_EQ(f.distances, (std::vector<float>{10, 11, 20, 21}));
    EXPECT_EQ(f.closest, (std::vector<int32_t>{110, 111, 120, 121}));
    ASSERT_EQ(f.signs.inside.size(), 2u);
    EXPECT_EQ(f.signs.inside[0].words[2], 2u);
    EXPECT_EQ(f.signs.inside[1].words[2], 3u);
    ASSERT_EQ(f.signs.runs.size(), 1u) << "the run past x is left out";
    EXPECT_EQ(f.signs.runs[0].first, (BrickCoord{0, 1, 1}));
    EXPECT_EQ(f.signs.runs[0].bricks, 3u) << "cut to z 1 to 3";
    EXPECT_TRUE(f.signs.insideBricks.empty());

    SolidBricks solid;
    solid.bricks = {{0, 0, 0}, {0, 0, 2}, {0, 0, 5}};
    solid.signs.inside.resize(3);
    solid.signs.inside[1].words[0] = 7;
    solid.signs.insideBricks = {{0, 3, 2}, {0, 3, 4}};
    clipSolid(solid, box);
    EXPECT_EQ(solid.bricks, (std::vector<BrickCoord>{{0, 0, 2}}));
    ASSERT_EQ(solid.signs.inside.size(), 1u);
    EXPECT_EQ(solid.signs.inside[0].words[0], 7u);
    EXPECT_EQ(solid.signs.insideBricks, (std::vector<BrickCoord>{{0, 3, 2}}));
}

INSTANTIATE_TEST_SUITE_P(Backends, Regions, ::testing::Values(Backend::Cpu, Backend::Raster, Backend::Compute),
                         [](const auto& info) { return std::string(nameOf(info.param)); });

TEST(RegionsRule, BoxesOfPartLeavesOrNoVoxelsAreRefused)
{
    Voxelizer v;
    const TriangleMesh mesh = icosphere({0, 0, 0}, 1.0, 2);
    const GridSpec grid = makeGrid(mesh, GridRequest{32, 0});
    VoxelizeOptions o;
    o.backend = Backend::Cpu;
    for (const IndexBox& bad : {IndexBox{{0, 0, 0}, {8, 8, 12}}, IndexBox{{4, 0, 0}, {16, 8, 8}},
                                IndexBox{{8, 0, 0}, {8, 8, 8}}, IndexBox{{16, 0, 0}, {8, 8, 8}}}) {
        o.region = bad;
        try {
            v.voxelize(mesh, grid, o);
            ADD_FAILURE() << describe(bad) << " was not refused";
        } catch (const InvalidInput& e) {
            EXPECT_EQ(e.argument(), "VoxelizeOptions::region") << e.what();
        }
    }
}

} // namespace
} // namespace svo::test
