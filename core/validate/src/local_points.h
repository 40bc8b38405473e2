#pragma once
/// @file local_points.h (internal)
/// The mesh's vertices as CGAL points in the grid's double local coordinates:
/// the same coordinates the GPU path starts from.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <vector>

#include "svo/core/grid.h"

namespace svo::validate::detail {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

inline std::vector<K::Point_3> localPoints(const TriangleMesh& mesh, const GridSpec& grid)
{
    std::vector<K::Point_3> p;
    p.reserve(mesh.positions.size());
    for (const auto& v : mesh.positions) {
        const Vec3d l = grid.toLocal(v);
        p.emplace_back(l.x, l.y, l.z);
    }
    return p;
}

} // namespace svo::validate::detail
