#include "svo/core/mesh.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "svo/core/error.h"

namespace svo {

Bounds TriangleMesh::bounds() const
{
    // In parallel: warm library calls map and check meshes every time.
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, triangles.size(), 4096), Bounds(),
        [&](const tbb::blocked_range<size_t>& r, Bounds b) {
            for (size_t t = r.begin(); t != r.end(); ++t)
                for (uint32_t v : triangles[t])
                    for (int a = 0; a < 3; ++a) {
                        b.min[a] = std::min(b.min[a], positions[v][a]);
                        b.max[a] = std::max(b.max[a], positions[v][a]);
                    }
            return b;
        },
        [](Bounds a, const Bounds& b) {
            for (int i = 0; i < 3; ++i) a.min[i] = std::min(a.min[i], b.min[i]), a.max[i] = std::max(a.max[i], b.max[i]);
            return a;
        });
}

void validateMesh(const TriangleMesh& mesh)
{
    if (mesh.triangles.empty())
        throw InvalidInput(fmt::format("{}: the mesh has no triangles", mesh.source));
    const size_t n = mesh.positions.size();
    if (!mesh.colors.empty() && mesh.colors.size() != n)
        throw InvalidInput(fmt::format("{}: {} vertex colours for {} vertices", mesh.source, mesh.colors.size(), n));
    auto bad = [&](uint32_t v) {
        if (v >= n) return true;
        const Vec3d& p = mesh.positions[v];
        return !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z);
    };
    // The first bad face, found in parallel, so the message names the same face every time.
    const size_t first = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, mesh.triangles.size(), 4096), mesh.triangles.size(),
        [&](const tbb::blocked_range<size_t>& r, size_t found) {
            for (size_t t = r.begin(); t != r.end() && t < found; ++t)
                if (bad(mesh.triangles[t][0]) || bad(mesh.triangles[t][1]) || bad(mesh.triangles[t][2])) return t;
            return found;
        },
        [](size_t a, size_t b) { return std::min(a, b); });
    if (first == mesh.triangles.size()) return;
    for (uint32_t v : mesh.triangles[first]) {
        if (v >= n)
            throw InvalidInput(fmt::format("{}: face {} uses vertex index {}, but the mesh has {} vertices", mesh.source,
                                           first, v, n));
        const Vec3d& p = mesh.positions[v];
        if (bad(v))
            throw InvalidInput(fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {})", mesh.source, v, p.x,
                                           p.y, p.z));
    }
}

} // namespace svo
