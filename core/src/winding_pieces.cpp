// Longest-edge bisection of long triangles (svo/core/winding_pieces.h).
#include "svo/core/winding_pieces.h"

#include <algorithm>
#include <cmath>

namespace svo {
namespace {

/// Appends triangle f's pieces (edges at most sqrt(max2)) to `out`; false,
/// and stops, once `out` would hold more than `budget` triangles.
bool cut(std::array<uint32_t, 3> f, double max2, size_t budget, WindingPieces& out)
{
    // An explicit stack: the halves of a triangle cut k times are k deep.
    std::vector<std::array<uint32_t, 3>> todo{f};
    while (!todo.empty()) {
        f = todo.back();
        todo.pop_back();
        const Vec3d a = out.positions[f[0]], b = out.positions[f[1]], c = out.positions[f[2]];
        const double e[3] = {dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)};
        int k = e[1] > e[0] ? 1 : 0;
        if (e[2] > e[k]) k = 2;
        // A zero-area triangle subtends no solid angle: cutting it adds nothing.
        const Vec3d n = cross(b - a, c - a);
        if (!(e[k] > max2) || dot(n, n) == 0.0) {
            if (out.triangles.size() >= budget) return false;
            out.triangles.push_back(f);
            continue;
        }
        // Edge k runs from f[k] to f[k + 1]; the halves keep f's orientation.
        const uint32_t u = f[k], v = f[(k + 1) % 3], w = f[(k + 2) % 3];
        const auto m = uint32_t(out.positions.size());
        out.positions.push_back(0.5 * (out.positions[u] + out.positions[v]));
        todo.push_back({m, v, w}); // popped second: the pieces run from u to v
        todo.push_back({u, m, w});
    }
    return true;
}

} // namespace

WindingPieces cutLongTriangles(const std::vector<Vec3d>& positions,
                               const std::vector<std::array<uint32_t, 3>>& triangles, double maxEdge, size_t budget)
{
    budget = std::max(budget, triangles.size());
    for (double edge = maxEdge;; edge *= 2) {
        WindingPieces out;
        out.positions = positions;
        out.triangles.reserve(triangles.size());
        out.edge = edge;
        const double max2 = edge * edge;
        bool fits = true;
        for (const auto& f : triangles)
            if (!(fits = cut(f, max2, budget, out))) break;
        // An infinite limit cuts nothing, so it always fits.
        if (fits) return out;
    }
}

} // namespace svo
