#include "svo/core/mesh_topology.h"

#include <algorithm>
#include <fmt/format.h>
#include <tbb/parallel_sort.h>
#include <unordered_map>
#include <vector>

namespace svo {
namespace {

struct PositionHash {
    size_t operator()(const Vec3d& p) const
    {
        const std::hash<double> h;
        return h(p.x) * 73856093u ^ h(p.y) * 19349663u ^ h(p.z) * 83492791u;
    }
};

} // namespace

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

std::vector<WeldedEdge> weldedEdges(const TriangleMesh& mesh)
{
    // Weld: each vertex to the first vertex at its exact position.
    std::unordered_map<Vec3d, uint32_t, PositionHash> first;
    first.reserve(mesh.positions.size());
    std::vector<uint32_t> weld(mesh.positions.size());
    for (uint32_t i = 0; i < mesh.positions.size(); ++i) weld[i] = first.emplace(mesh.positions[i], i).first->second;

    // Directed edges as (low, high, direction) sorted, so an edge's uses are adjacent.
    struct Use {
        uint32_t lo, hi;
        bool forward;
    };
    std::vector<Use> uses;
    uses.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) {
        const uint32_t v[3] = {weld[t[0]], weld[t[1]], weld[t[2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = v[e], b = v[(e + 1) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), a < b});
        }
    }
    tbb::parallel_sort(uses.begin(), uses.end(),
                       [](const Use& a, const Use& b) { return a.lo != b.lo ? a.lo < b.lo : a.hi < b.hi; });
    std::vector<WeldedEdge> edges;
    for (size_t i = 0; i < uses.size();) {
        WeldedEdge e{uses[i].lo, uses[i].hi, 0, 0};
        for (; i < uses.size() && uses[i].lo == e.lo && uses[i].hi == e.hi; ++i) {
            ++e.uses;
            e.net += uses[i].forward ? 1 : -1;
        }
        edges.push_back(e);
    }
    return edges;
}

EdgeReport checkEdges(const TriangleMesh& mesh)
{
    EdgeReport r;
    for (const WeldedEdge& e : weldedEdges(mesh)) {
        ++r.edges;
        if (e.uses == 1) ++r.boundary;
        else if (e.uses > 2) ++r.nonManifold;
        else if (e.net != 0) ++r.misoriented;
    }
    return r;
}

} // namespace svo
