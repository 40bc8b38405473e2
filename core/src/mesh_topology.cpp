#include "svo/core/mesh_topology.h"

#include <algorithm>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <vector>

namespace svo {

std::string EdgeReport::describe() const
{
    if (closedAndOriented()) return "closed and consistently oriented";
    if (!edges) return "no triangle with three distinct corners";
    std::string s;
    auto add = [&](uint64_t n, const char* what) {
        if (n) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", n, what);
    };
    add(boundary, "boundary edges");
    add(nonManifold, "edges with more than two triangles");
    add(misoriented, "edges whose two triangles disagree in orientation");
    return s;
}

namespace {

/// Each vertex's weld: the first (lowest) vertex at its exact position
/// (-0 and +0 the same), from the vertices sorted by position, then index.
std::vector<uint32_t> welds(const std::vector<Vec3d>& positions)
{
    std::vector<uint32_t> order(positions.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    auto less = [&](uint32_t a, uint32_t b) {
        const Vec3d &p = positions[a], &q = positions[b];
        if (p.x != q.x) return p.x < q.x;
        if (p.y != q.y) return p.y < q.y;
        if (p.z != q.z) return p.z < q.z;
        return a < b;
    };
    tbb::parallel_sort(order.begin(), order.end(), less);
    std::vector<uint32_t> weld(positions.size());
    for (size_t i = 0; i < order.size(); ++i) {
        const bool same = i > 0 && positions[order[i]] == positions[order[i - 1]];
        weld[order[i]] = same ? weld[order[i - 1]] : order[i];
    }
    return weld;
}

} // namespace

void forEachWeldedEdge(const TriangleMesh& mesh, const std::function<void(const WeldedEdge&)>& visit)
{
    const std::vector<uint32_t> weld = welds(mesh.positions);
    // Each edge's uses listed under its lower end (CSR), as hi << 1 | (runs
    // lo -> hi): a few words a use, where a list of all uses to sort would
    // hold three times as many.
    const auto forEachUse = [&](auto&& f) {
        for (const auto& t : mesh.triangles) {
            const uint32_t v[3] = {weld[t[0]], weld[t[1]], weld[t[2]]};
            if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
            for (int e = 0; e < 3; ++e) {
                const uint32_t a = v[e], b = v[(e + 1) % 3];
                f(std::min(a, b), uint64_t(std::max(a, b)) << 1 | uint64_t(a < b));
            }
        }
    };
    std::vector<uint64_t> first(mesh.positions.size() + 1, 0);
    forEachUse([&](uint32_t lo, uint64_t) { ++first[lo + 1]; });
    for (size_t i = 1; i < first.size(); ++i) first[i] += first[i - 1];
    std::vector<uint64_t> uses(first.back());
    {
        std::vector<uint64_t> fill(first.begin(), first.end() - 1);
        forEachUse([&](uint32_t lo, uint64_t use) { uses[fill[lo]++] = use; });
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.positions.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t lo = r.begin(); lo != r.end(); ++lo)
                              std::sort(uses.begin() + first[lo], uses.begin() + first[lo + 1]);
                      });
    for (size_t lo = 0; lo < mesh.positions.size(); ++lo)
        for (uint64_t i = first[lo]; i < first[lo + 1];) {
            WeldedEdge e{uint32_t(lo), uint32_t(uses[i] >> 1), 0, 0};
            for (; i < first[lo + 1] && uint32_t(uses[i] >> 1) == e.hi; ++i) {
                ++e.uses;
                e.net += (uses[i] & 1) ? 1 : -1;
            }
            visit(e);
        }
}

std::vector<WeldedEdge> weldedEdges(const TriangleMesh& mesh)
{
    std::vector<WeldedEdge> edges;
    forEachWeldedEdge(mesh, [&](const WeldedEdge& e) { edges.push_back(e); });
    return edges;
}

EdgeReport checkEdges(const TriangleMesh& mesh)
{
    EdgeReport r;
    forEachWeldedEdge(mesh, [&](const WeldedEdge& e) {
        ++r.edges;
        if (e.uses == 1) ++r.boundary;
        else if (e.uses > 2) ++r.nonManifold;
        else if (e.net != 0) ++r.misoriented;
    });
    return r;
}

} // namespace svo
