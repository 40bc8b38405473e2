// svo::validate::checkLevelSet and compareWithOpenVdb (what `svo validate
// --sdf` runs): svo's GPU level sets pass on closed and open meshes, and
// planted defects are reported exactly, each one alone.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>

#include "scenes.h"
#include "svo/core/mesh_io.h"
#include "svo/svo.h"
#include "svo/validate/level_set_check.h"
#include "svo/validate/level_set_peer.h"
#include "svo/validate/level_set_report.h"

namespace svo::test {
namespace {

using validate::LevelSetVoxel;

std::vector<LevelSetVoxel> levelSetVoxels(Voxelizer& v, const TriangleMesh& mesh, const GridSpec& grid,
                                          double exterior, double interior, VoxelizeStats* stats = nullptr)
{
    LevelSetOptions ls;
    ls.exteriorBand = exterior;
    ls.interiorBand = interior;
    VoxelizeOptions o;
    o.stats = stats;
    const auto sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(v.levelSet(mesh, grid, ls, o).front());
    return validate::activeLevelSetVoxels(*sdf);
}

validate::LevelSetCheckOptions bands(double exterior, double interior)
{
    validate::LevelSetCheckOptions o;
    o.exteriorBand = exterior;
    o.interiorBand = interior;
    return o;
}

/// svo's level set of a closed mesh meets every criterion, and OpenVDB's is
/// never nearer CGAL's distance, nor right where the signs differ.
void expectPasses(Voxelizer& v, const TriangleMesh& mesh, int resolution, double exterior, double interior)
{
    SCOPED_TRACE(mesh.source);
    const GridSpec grid = makeGrid(mesh, GridRequest{resolution, 0});
    const auto voxels = levelSetVoxels(v, mesh, grid, exterior, interior);
    const auto c = validate::checkLevelSet(mesh, grid, voxels, bands(exterior, interior));
    std::cout << "[ sdf      ] " << mesh.source << " at " << resolution << ": " << c.voxels << " voxels, max error "
              << c.maxError << ", RMS " << c.rmsError << " voxels, " << c.candidates << " inactive examined\n";
    EXPECT_TRUE(c.signChecked) << c.signReason;
    EXPECT_GT(c.voxels, 1000u);
    EXPECT_GT(c.candidates, c.voxels / 2);
    EXPECT_LE(c.maxError, 1e-4);
    EXPECT_GT(c.maxError, 0.0); // float values: some rounding must show, or nothing was compared
    EXPECT_EQ(c.overTolerance, 0u);
    EXPECT_EQ(c.signDisagreements, 0u);
    EXPECT_EQ(c.missing, 0u);
    EXPECT_EQ(c.extra, 0u);
    EXPECT_EQ(c.bandUnjudged, 0u);
    EXPECT_TRUE(c.passed());

    const auto o = validate::compareWithOpenVdb(mesh, grid, voxels, bands(exterior, interior));
    std::cout << "[ openvdb  ] " << o.common << " common, " << o.onlyOurs << " only svo, " << o.onlyOpenVdb
              << " only OpenVDB, " << o.signDisagreements << " signs differ (CGAL sides with svo at "
              << o.signOursRight << "), max difference " << o.maxDifference << ", OpenVDB's max error "
              << o.maxErrorOpenVdb << " voxels\n";
    EXPECT_EQ(o.ours, voxels.size());
    EXPECT_EQ(o.common + o.onlyOurs, o.ours);
    EXPECT_EQ(o.common + o.onlyOpenVdb, o.openvdb);
    EXPECT_GT(o.common, o.ours * 95 / 100);
    EXPECT_LE(o.maxErrorOurs, 1e-4);
    EXPECT_EQ(o.oursFarther, 0u);
    EXPECT_TRUE(o.signDisagreements == 0 || o.signJudged);
    EXPECT_EQ(o.signOursRight, o.signDisagreements);
}

TEST(LevelSetCheck, SvoLevelSetsOfClosedMeshesPass)
{
    Voxelizer v;
    expectPasses(v, icosphere({0.1, -0.2, 0.3}, 1.0, 3), 40, 3, 3);
    expectPasses(v, box({-1.3, 0.2, 0.7}, {0.4, 1.1, 2.9}), 32, 2, 4.5); // unequal bands: sides pick them
#ifdef SVO_CGAL_MESHES
    expectPasses(v, loadMesh(std::string(SVO_CGAL_MESHES) + "/elephant.off"), 64, 3, 3);
#endif
}

// Open meshes: no inside, so no sign check, said why; distances and the band still hold.
TEST(LevelSetCheck, OpenMeshesAreCheckedWithoutSigns)
{
    TriangleMesh open = box({0, 0, 0}, {1, 1, 1});
    open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4); // the top face is gone
    open.source = "open box";
    const GridSpec grid = makeGrid(open, GridRequest{24, 0});
    Voxelizer v;
    VoxelizeStats stats;
    const auto voxels = levelSetVoxels(v, open, grid, 3, 3, &stats);
    EXPECT_NE(stats.sign.find("winding"), std::string::npos) << stats.sign;
    const auto c = validate::checkLevelSet(open, grid, voxels, bands(3, 3));
    EXPECT_FALSE(c.signChecked);
    EXPECT_NE(c.signReason.find("open"), std::string::npos) << c.signReason;
    EXPECT_EQ(c.signDisagreements + c.signNearSurface, 0u);
    EXPECT_LE(c.maxError, 1e-4);
    EXPECT_EQ(c.missing, 0u);
    EXPECT_EQ(c.extra, 0u);
    EXPECT_EQ(c.bandUnjudged, 0u); // equal bands: the side never picks one
    EXPECT_TRUE(c.passed());
    // Unequal bands: between them, an inactive voxel's side is unknown, and is said so.
    const auto wider = validate::checkLevelSet(open, grid, voxels, bands(3, 5));
    EXPECT_GT(wider.bandUnjudged, 0u);
}

// A unit box at 16 voxels a side: faces on voxel planes 0 and 16, so the
// distances at the voxels below are whole numbers of voxels, exact in float.
TEST(LevelSetCheck, PlantedDefectsAreReportedExactly)
{
    const TriangleMesh b = box({0, 0, 0}, {1, 1, 1});
    const GridSpec grid = makeGrid(b, GridRequest{16, 0});
    ASSERT_EQ(grid.voxelSize, 1.0 / 16);
    Voxelizer v;
    const std::vector<LevelSetVoxel> good = levelSetVoxels(v, b, grid, 3, 3);
    const auto clean = validate::checkLevelSet(b, grid, good, bands(3, 3));
    ASSERT_TRUE(clean.passed()) << clean.maxError << " " << clean.signDisagreements << " " << clean.missing << " "
                                << clean.extra;
    ASSERT_EQ(clean.overTolerance, 0u);

    const double h = grid.voxelSize;
    auto find = [&](std::vector<LevelSetVoxel>& voxels, std::array<int32_t, 3> i) {
        const auto it = std::find_if(voxels.begin(), voxels.end(), [&](const auto& x) { return x.index == i; });
        EXPECT_NE(it, voxels.end()) << i[0] << " " << i[1] << " " << i[2];
        return it;
    };
    const std::array<int32_t, 3> flipped{8, 8, 18}, dropped{8, 8, -1}, added{8, 8, 21}, skewed{8, 8, 17};
    {
        auto voxels = good;
        auto it = find(voxels, flipped);
        ASSERT_FLOAT_EQ(it->value, float(2 * h));
        it->value = -it->value; // 2 voxels outside, said inside
        const auto c = validate::checkLevelSet(b, grid, voxels, bands(3, 3));
        EXPECT_EQ(c.signDisagreements, 1u);
        EXPECT_EQ(c.missing + c.extra + c.overTolerance, 0u);
        ASSERT_EQ(c.worstSign.size(), 1u);
        EXPECT_EQ(c.worstSign[0].index, (std::array<int64_t, 3>{8, 8, 18}));
        EXPECT_DOUBLE_EQ(c.worstSign[0].exact, 2.0);
        EXPECT_EQ(c.worstSign[0].side, 0);
        EXPECT_FALSE(c.passed());
    }
    {
        auto voxels = good;
        voxels.erase(find(voxels, dropped)); // 1 voxel below the box: in the band
        const auto c = validate::checkLevelSet(b, grid, voxels, bands(3, 3));
        EXPECT_EQ(c.missing, 1u);
        EXPECT_EQ(c.signDisagreements + c.extra + c.overTolerance, 0u);
        ASSERT_EQ(c.worstMissing.size(), 1u);
        EXPECT_EQ(c.worstMissing[0].index, (std::array<int64_t, 3>{8, 8, -1}));
        EXPECT_DOUBLE_EQ(c.worstMissing[0].exact, 1.0);
        EXPECT_TRUE(std::isnan(c.worstMissing[0].value));
        EXPECT_FALSE(c.passed());
    }
    {
        auto voxels = good;
        ASSERT_EQ(std::count_if(voxels.begin(), voxels.end(), [&](const auto& x) { return x.index == added; }), 0);
        voxels.push_back({added, float(5 * h)}); // 5 voxels above the box, its distance right: beyond the band
        const auto c = validate::checkLevelSet(b, grid, voxels, bands(3, 3));
        EXPECT_EQ(c.extra, 1u);
        EXPECT_EQ(c.signDisagreements + c.missing + c.overTolerance, 0u);
        ASSERT_EQ(c.worstExtra.size(), 1u);
        EXPECT_EQ(c.worstExtra[0].index, (std::array<int64_t, 3>{8, 8, 21}));
        EXPECT_DOUBLE_EQ(c.worstExtra[0].exact, 5.0);
        EXPECT_FALSE(c.passed());
    }
    {
        auto voxels = good;
        auto it = find(voxels, skewed);
        it->value = float(1.01 * h); // 1 voxel above the box, said 1.01
        const auto c = validate::checkLevelSet(b, grid, voxels, bands(3, 3));
        EXPECT_EQ(c.overTolerance, 1u);
        EXPECT_NEAR(c.maxError, 0.01, 1e-6);
        EXPECT_EQ(c.signDisagreements + c.missing + c.extra, 0u);
        ASSERT_FALSE(c.worstError.empty());
        EXPECT_EQ(c.worstError[0].index, (std::array<int64_t, 3>{8, 8, 17}));
        EXPECT_FALSE(c.passed());
    }
    {
        // All four at once: the report names each, and fails.
        auto voxels = good;
        find(voxels, flipped)->value *= -1;
        find(voxels, skewed)->value = float(1.01 * h);
        voxels.erase(find(voxels, dropped));
        voxels.push_back({added, float(5 * h)});
        validate::LevelSetReportOptions ro;
        ro.check = bands(3, 3);
        const auto r = validate::validateLevelSet(b, grid, voxels, ro);
        EXPECT_FALSE(r.passed);
        EXPECT_EQ(r.check.signDisagreements, 1u);
        EXPECT_EQ(r.check.missing, 1u);
        EXPECT_EQ(r.check.extra, 1u);
        EXPECT_EQ(r.check.overTolerance, 1u);
        for (const char* part : {"1 distances off", "1 signs differ", "1 band voxels missing", "1 active voxels beyond"})
            EXPECT_NE(r.reason.find(part), std::string::npos) << part << ": " << r.reason;
        ASSERT_TRUE(r.compared);
        const auto before = validate::compareWithOpenVdb(b, grid, good, bands(3, 3));
        EXPECT_EQ(r.openvdb.onlyOurs, before.onlyOurs + 1);       // the added voxel
        EXPECT_EQ(r.openvdb.onlyOpenVdb, before.onlyOpenVdb + 1); // the dropped one
        EXPECT_EQ(r.openvdb.signDisagreements, before.signDisagreements + 1);
        EXPECT_EQ(r.openvdb.signOursRight, before.signOursRight); // CGAL sides with OpenVDB at the flipped one
        const std::string json = validate::levelSetReportJson(r);
        EXPECT_NE(json.find("\"passed\": false"), std::string::npos) << json;
    }
    // A voxel listed twice is an error, not a count.
    auto twice = good;
    twice.push_back(good.front());
    EXPECT_THROW(validate::checkLevelSet(b, grid, twice, bands(3, 3)), Error);
    EXPECT_THROW(validate::checkLevelSet(b, grid, good, bands(0, 3)), Error);
}

// The band edge: voxels exactly on it, or within the tolerance of it, are
// neither missing nor extra; beyond the tolerance they are.
TEST(LevelSetCheck, TheBandEdgeHasTheToleranceAsSlack)
{
    const TriangleMesh b = box({0, 0, 0}, {1, 1, 1});
    const GridSpec grid = makeGrid(b, GridRequest{16, 0});
    Voxelizer v;
    auto voxels = levelSetVoxels(v, b, grid, 3, 3);
    // (8, 8, 19) is exactly 3 voxels above the box: on the edge, so svo leaves it inactive (d < W is active).
    const std::array<int32_t, 3> edge{8, 8, 19};
    ASSERT_EQ(std::count_if(voxels.begin(), voxels.end(), [&](const auto& x) { return x.index == edge; }), 0);
    // Either answer passes: absent (above), or present with its distance.
    voxels.push_back({edge, float(3 * grid.voxelSize)});
    EXPECT_TRUE(validate::checkLevelSet(b, grid, voxels, bands(3, 3)).passed());
    // A band a little wider than the tolerance allows makes the edge voxels missing.
    const auto wider = validate::checkLevelSet(b, grid, levelSetVoxels(v, b, grid, 3, 3), bands(3.001, 3.001));
    EXPECT_GT(wider.missing, 0u);
    EXPECT_EQ(wider.extra, 0u);
    // Within the tolerance: not.
    const auto within = validate::checkLevelSet(b, grid, levelSetVoxels(v, b, grid, 3, 3), bands(3.00005, 3.00005));
    EXPECT_EQ(within.missing, 0u);
}

} // namespace
} // namespace svo::test
