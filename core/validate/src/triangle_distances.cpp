#include "triangle_distances.h"

#include <cmath>

namespace svo::validate::detail {

TriangleDistances::TriangleDistances(const TriangleMesh& mesh, const std::vector<K::Point_3>& p)
{
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& f = mesh.triangles[t];
        if (CGAL::collinear(p[f[0]], p[f[1]], p[f[2]])) {
            degenerate_.push_back({p[f[0]], p[f[1]], p[f[2]], int64_t(t)});
        } else {
            triangles_.emplace_back(p[f[0]], p[f[1]], p[f[2]]);
            ids_.push_back(int64_t(t));
        }
    }
    if (!triangles_.empty()) {
        tree_.insert(triangles_.cbegin(), triangles_.cend());
        tree_.build();
        tree_.accelerate_distance_queries();
        // The first query builds what is left lazily; later ones only read, so they may run in parallel.
        (void)tree_.closest_point(triangles_.front().vertex(0));
    }
}

TriangleDistances::Nearest TriangleDistances::nearest(const K::Point_3& c) const
{
    Nearest n;
    if (!triangles_.empty()) {
        const auto hit = tree_.closest_point_and_primitive(c);
        n.squared = CGAL::squared_distance(c, hit.first);
        n.triangle = ids_[size_t(hit.second - triangles_.cbegin())];
    }
    for (const auto& d : degenerate_) {
        // Distance to a degenerate triangle: to the nearest of its edges.
        for (const auto& [a, b] : {std::pair{d.a, d.b}, std::pair{d.b, d.c}, std::pair{d.a, d.c}}) {
            const double s = a == b ? CGAL::squared_distance(c, a) : CGAL::squared_distance(c, K::Segment_3(a, b));
            if (s < n.squared) n.squared = s, n.triangle = d.id;
        }
    }
    return n;
}

double TriangleDistances::distance(const K::Point_3& p) const { return std::sqrt(nearest(p).squared); }

} // namespace svo::validate::detail
