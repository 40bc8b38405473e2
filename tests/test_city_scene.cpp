// The procedural city (svo/core/city_scene.h): the same bytes for a seed on
// any number of threads, counts that follow the target, a city that grows
// with it, closed buildings beside open roads and trees, no degenerate
// triangles.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <numeric>
#include <tbb/global_control.h>
#include <unordered_map>
#include <vector>

#include "svo/core/city_scene.h"
#include "svo/core/error.h"
#include "svo/core/fnv1a.h"
#include "svo/core/mesh_topology.h"

namespace {

using svo::CityOptions;
using svo::TriangleMesh;

uint64_t meshHash(const TriangleMesh& m)
{
    const uint64_t h = svo::fnv1a(m.positions.data(), m.positions.size() * sizeof(m.positions[0]));
    return svo::fnv1a(m.triangles.data(), m.triangles.size() * sizeof(m.triangles[0]), h);
}

double area(const TriangleMesh& m, size_t t)
{
    const auto [a, b, c] = m.corners(t);
    const svo::Vec3d n = cross(b - a, c - a);
    return 0.5 * std::sqrt(dot(n, n));
}

/// The mesh's connected pieces, vertices welded at equal positions (the
/// crowns are soups), each as a mesh of its own.
std::vector<TriangleMesh> components(const TriangleMesh& m)
{
    std::map<std::array<double, 3>, uint32_t> weld;
    std::vector<uint32_t> id(m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i)
        id[i] = weld.emplace(std::array{m.positions[i].x, m.positions[i].y, m.positions[i].z}, uint32_t(weld.size()))
                    .first->second;
    std::vector<uint32_t> parent(weld.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&](uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& t : m.triangles)
        for (int e = 1; e < 3; ++e) parent[root(id[t[e]])] = root(id[t[0]]);
    std::unordered_map<uint32_t, TriangleMesh> pieces;
    for (const auto& t : m.triangles) {
        TriangleMesh& piece = pieces[root(id[t[0]])];
        const uint32_t first = uint32_t(piece.positions.size());
        for (uint32_t v : t) piece.positions.push_back(m.positions[v]);
        piece.triangles.push_back({first, first + 1, first + 2}); // checkEdges welds them again
    }
    std::vector<TriangleMesh> out;
    for (auto& [r, piece] : pieces) out.push_back(std::move(piece));
    return out;
}

// The same seed and target give the same bytes, on one thread or all; the
// pinned hash holds the city to the same bytes on every platform and
// compiler (change it only with the generator, on purpose).
TEST(CityScene, TheSameSeedGivesTheSameBytesOnAnyNumberOfThreads)
{
    const uint64_t hash = meshHash(svo::cityScene({100'000, 7}));
    EXPECT_EQ(meshHash(svo::cityScene({100'000, 7})), hash);
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        EXPECT_EQ(meshHash(svo::cityScene({100'000, 7})), hash);
    }
    const TriangleMesh small = svo::cityScene({5'000, 1});
    EXPECT_EQ(small.triangles.size(), 5'000u);
    EXPECT_EQ(small.positions.size(), 6'864u);
    EXPECT_EQ(meshHash(small), 0x88f0857e0aa1fe06u) << std::hex << meshHash(small);
}

TEST(CityScene, ADifferentSeedGivesADifferentCity)
{
    const TriangleMesh a = svo::cityScene({100'000, 1}), b = svo::cityScene({100'000, 2});
    EXPECT_NE(meshHash(a), meshHash(b));
    // Not the same city moved: its buildings differ, so its height and counts do.
    EXPECT_NE(a.bounds().max.y, b.bounds().max.y);
    EXPECT_NE(a.positions.size(), b.positions.size());
}

// The count ends at most 1% under the target, never over, for any seed;
// the source names the seed and the target.
TEST(CityScene, TheTriangleCountFollowsTheTarget)
{
    for (uint64_t target : {5'000u, 20'000u, 100'000u, 1'000'000u})
        for (uint64_t seed : {1u, 2u, 3u}) {
            const TriangleMesh m = svo::cityScene({target, seed});
            EXPECT_LE(m.triangles.size(), target) << target << " seed " << seed;
            EXPECT_GE(m.triangles.size(), target * 99 / 100) << target << " seed " << seed;
        }
    EXPECT_EQ(svo::cityScene({1'000'000, 1}).source, "city (seed 1, 1,000,000 triangles)");
}

// More triangles, more blocks: the footprint grows on both axes, its area
// about with the count.
TEST(CityScene, TheCityGrowsWithTheTarget)
{
    svo::Vec3d last{0, 0, 0};
    for (uint64_t target : {5'000u, 100'000u, 1'000'000u}) {
        const svo::Vec3d e = svo::cityScene({target, 1}).bounds().extent();
        EXPECT_GE(e.x, last.x) << target;
        EXPECT_GE(e.z, last.z) << target;
        EXPECT_GT(e.x * e.z, 2 * last.x * last.z) << target;
        last = e;
    }
    const double lastArea = last.x * last.z;
    // A million triangles are some 20 blocks of 120 m (a block holds some 45,000).
    EXPECT_GT(lastArea, 10 * 120.0 * 120.0);
    EXPECT_LT(lastArea, 40 * 120.0 * 120.0);
}

// Buildings, curbs and garden walls are closed and consistently oriented;
// roads, trunks and crowns are open; nothing is non-manifold.
TEST(CityScene, ClosedBuildingsBesideOpenRoadsAndTrees)
{
    const TriangleMesh city = svo::cityScene({100'000, 1});
    const svo::EdgeReport whole = svo::checkEdges(city);
    EXPECT_FALSE(whole.closedAndOriented());
    EXPECT_EQ(whole.nonManifold, 0u);
    EXPECT_EQ(whole.misoriented, 0u);
    size_t closed = 0, open = 0, tall = 0, roads = 0, crowns = 0;
    for (const TriangleMesh& piece : components(city)) {
        const svo::EdgeReport r = svo::checkEdges(piece);
        EXPECT_EQ(r.nonManifold + r.misoriented, 0u) << r.describe();
        const svo::Bounds b = piece.bounds();
        if (r.closedAndOriented()) {
            ++closed;
            tall += b.max.y > 10; // a building, not a curb or a garden wall
        } else {
            ++open;
            roads += b.max.y == 0;
            crowns += b.min.y > 0.5; // a crown above its trunk's foot
        }
    }
    EXPECT_GT(closed, 20u);
    EXPECT_GT(tall, 5u);
    EXPECT_GT(roads, 2u);
    EXPECT_GT(crowns, 50u);
    EXPECT_GT(open, roads + crowns); // and the trunks
}

// The library's own mesh check passes, and no triangle repeats a corner or
// has (near) zero area.
TEST(CityScene, NoDegenerateTriangles)
{
    for (uint64_t target : {5'000u, 1'000'000u}) {
        const TriangleMesh m = svo::cityScene({target, 5});
        EXPECT_NO_THROW(svo::validateMesh(m));
        EXPECT_TRUE(m.colors.empty());
        size_t bad = 0;
        double smallest = INFINITY;
        for (size_t t = 0; t < m.triangles.size(); ++t) {
            const auto& f = m.triangles[t];
            bad += f[0] == f[1] || f[1] == f[2] || f[2] == f[0];
            smallest = std::min(smallest, area(m, t));
        }
        EXPECT_EQ(bad, 0u) << target;
        EXPECT_GT(smallest, 0.01) << target; // square metres
    }
}

TEST(CityScene, TargetsOutsideTheRangeAreRefused)
{
    for (uint64_t target : {0ull, 999ull, 1'000'000'001ull, ~0ull}) {
        try {
            svo::cityScene({target, 1});
            ADD_FAILURE() << target;
        } catch (const svo::InvalidInput& e) {
            EXPECT_EQ(e.argument(), "CityOptions::triangles") << e.what();
        }
    }
    EXPECT_LE(svo::cityScene({1'000, 1}).triangles.size(), 1'000u);
}

} // namespace
