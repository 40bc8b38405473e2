#include "svo/core/mesh.h"

#include <cmath>
#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo {

Bounds TriangleMesh::bounds() const
{
    Bounds b;
    for (const auto& f : triangles)
        for (uint32_t v : f)
            for (int a = 0; a < 3; ++a) {
                b.min[a] = std::min(b.min[a], positions[v][a]);
                b.max[a] = std::max(b.max[a], positions[v][a]);
            }
    return b;
}

void validateMesh(const TriangleMesh& mesh)
{
    if (mesh.triangles.empty())
        throw Error(fmt::format("{}: the mesh has no triangles", mesh.source));
    const size_t n = mesh.positions.size();
    if (!mesh.colors.empty() && mesh.colors.size() != n)
        throw Error(fmt::format("{}: {} vertex colours for {} vertices", mesh.source, mesh.colors.size(), n));
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
        for (uint32_t v : mesh.triangles[t]) {
            if (v >= n)
                throw Error(fmt::format("{}: face {} uses vertex index {}, but the mesh has {} vertices",
                                        mesh.source, t, v, n));
            const Vec3d& p = mesh.positions[v];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw Error(fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {})",
                                        mesh.source, v, p.x, p.y, p.z));
        }
}

} // namespace svo
