#pragma once
/// @file triangle_distances.h (internal)
/// The distance from a point to the closest triangle of a mesh, with CGAL: an
/// AABB tree over the proper triangles, and a scan over the degenerate ones
/// (collinear corners: their edges as segments, or a point). Coordinates are
/// the grid's double local ones (local_points.h).
///
/// Thread safety: queries are const and may run in parallel once the
/// constructor has returned (it builds the tree and its distance accelerator).
#include <cstdint>
#include <vector>

#include "local_points.h"
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

namespace svo::validate::detail {

class TriangleDistances {
public:
    struct Nearest {
        double squared = INFINITY; ///< squared distance, in local units
        int64_t triangle = -1;     ///< index into mesh.triangles
    };

    /// @param points the mesh's vertices in local coordinates (localPoints)
    TriangleDistances(const TriangleMesh& mesh, const std::vector<K::Point_3>& points);

    Nearest nearest(const K::Point_3& p) const;
    double distance(const K::Point_3& p) const;

private:
    using Triangles = std::vector<K::Triangle_3>;
    using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
    struct Degenerate {
        K::Point_3 a, b, c;
        int64_t id;
    };
    Triangles triangles_;
    std::vector<int64_t> ids_;
    std::vector<Degenerate> degenerate_;
    Tree tree_;
};

} // namespace svo::validate::detail
