// Welded edges (svo/core/mesh_topology.h) against a plain reference: vertices
// welded through a std::map of positions, every directed edge use counted in
// a std::map, on meshes with shared and split vertices, -0 and +0, repeated
// corners, duplicate faces, three triangles on an edge and flipped faces;
// and the counts of a closed icosphere, known from Euler's formula.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <tuple>

#include "scenes.h"
#include "svo/core/mesh_topology.h"

namespace {

using svo::TriangleMesh;
using svo::WeldedEdge;

std::vector<WeldedEdge> reference(const TriangleMesh& mesh)
{
    std::map<std::tuple<double, double, double>, uint32_t> first; // -0 < +0 is false: one key
    std::vector<uint32_t> weld(mesh.positions.size());
    for (uint32_t i = 0; i < mesh.positions.size(); ++i) {
        const auto& p = mesh.positions[i];
        weld[i] = first.emplace(std::make_tuple(p.x, p.y, p.z), i).first->second;
    }
    std::map<std::pair<uint32_t, uint32_t>, std::pair<uint32_t, int64_t>> edges;
    for (const auto& t : mesh.triangles) {
        const uint32_t v[3] = {weld[t[0]], weld[t[1]], weld[t[2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = v[e], b = v[(e + 1) % 3];
            auto& use = edges[{std::min(a, b), std::max(a, b)}];
            ++use.first;
            use.second += a < b ? 1 : -1;
        }
    }
    std::vector<WeldedEdge> out;
    for (const auto& [k, u] : edges) out.push_back({k.first, k.second, u.first, u.second});
    return out;
}

void expectSame(const TriangleMesh& mesh)
{
    const std::vector<WeldedEdge> got = svo::weldedEdges(mesh), want = reference(mesh);
    ASSERT_EQ(got.size(), want.size()) << mesh.source;
    for (size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i].lo, want[i].lo) << mesh.source << " edge " << i;
        EXPECT_EQ(got[i].hi, want[i].hi) << mesh.source << " edge " << i;
        EXPECT_EQ(got[i].uses, want[i].uses) << mesh.source << " edge " << i;
        EXPECT_EQ(got[i].net, want[i].net) << mesh.source << " edge " << i;
    }
}

/// @a mesh with every triangle on its own three vertices (test::asSoup), in a shuffled order.
TriangleMesh soup(const TriangleMesh& mesh, uint32_t seed)
{
    TriangleMesh out = svo::test::asSoup(mesh);
    std::vector<uint32_t> perm(out.positions.size());
    for (uint32_t i = 0; i < perm.size(); ++i) perm[i] = i;
    std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
    std::vector<svo::Vec3d> moved(perm.size());
    for (uint32_t i = 0; i < perm.size(); ++i) moved[perm[i]] = out.positions[i];
    out.positions = moved;
    for (auto& t : out.triangles)
        for (uint32_t& v : t) v = perm[v];
    return out;
}

} // namespace

TEST(MeshTopology, ClosedIcosphereHasEulersEdges)
{
    for (int level : {0, 2, 4}) {
        const TriangleMesh ico = svo::icosphere({0.0, 0.0, 0.0}, 1.0, level);
        for (const TriangleMesh& m : {ico, soup(ico, 7)}) {
            const svo::EdgeReport r = svo::checkEdges(m);
            EXPECT_EQ(r.edges, 3 * m.triangles.size() / 2) << m.source << " level " << level;
            EXPECT_TRUE(r.closedAndOriented()) << m.source << ": " << r.describe();
            expectSame(m);
        }
    }
}

TEST(MeshTopology, WeldsAndCountsAsThePlainReference)
{
    // A cube's six faces on the origin's planes (-0 and +0 both), split
    // vertices, a repeated corner, a duplicate face, a third triangle on an
    // edge and one face flipped.
    TriangleMesh m;
    m.source = "odd cube";
    const double z0 = -0.0;
    for (double x : {z0, 1.0})
        for (double y : {0.0, 1.0})
            for (double z : {z0, 1.0}) m.positions.push_back({x, y, z});
    for (uint32_t i = 0; i < 8; ++i) {
        const svo::Vec3d p = m.positions[i];
        m.positions.push_back(p); // split copies
    }
    m.positions.push_back({0.0, 0.0, 0.0});                                         // +0 copy of vertex 0
    const std::vector<std::array<uint32_t, 3>> faces = {
        {0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6},
        {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
    for (size_t f = 0; f < faces.size(); ++f) {
        auto t = faces[f];
        if (f % 2)
            for (uint32_t& v : t) v += 8; // every other face on the split copies
        m.triangles.push_back(t);
    }
    m.triangles.push_back({16, 9, 11});  // the first face again, through the +0 vertex
    m.triangles.push_back({0, 0, 5});    // a repeated corner: left out
    m.triangles.push_back({0, 5, 6});    // a third triangle on edge 0-5
    m.triangles.push_back({2, 3, 7});    // a face given twice
    std::swap(m.triangles[3][1], m.triangles[3][2]); // a flipped face
    expectSame(m);
    const svo::EdgeReport r = svo::checkEdges(m);
    EXPECT_FALSE(r.closedAndOriented());
    EXPECT_GT(r.nonManifold, 0u);
    EXPECT_GT(r.misoriented, 0u);
    expectSame(soup(m, 3));
}
