#include "svo/validate/classify.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <algorithm>
#include <cmath>
#include <iterator>

#include "local_points.h"
#include "svo/core/voxel_key.h"

namespace svo::validate {
namespace {

using K = detail::K;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

/// Nearest-triangle distances for a few voxels: an AABB tree over the proper
/// triangles, and a scan over the degenerate ones (as segments or points).
class Distances {
public:
    Distances(const TriangleMesh& mesh, const GridSpec& grid)
    {
        const std::vector<K::Point_3> p = detail::localPoints(mesh, grid);
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
            tree_.accelerate_distance_queries();
        }
    }

    VoxelCase at(const GridSpec& grid, uint64_t key) const
    {
        const auto l = unpackVoxelKey(key);
        const K::Point_3 c(l[0], l[1], l[2]);
        VoxelCase v;
        v.index = grid.toGlobal(l);
        double best = INFINITY;
        if (!triangles_.empty()) {
            const auto hit = tree_.closest_point_and_primitive(c);
            best = CGAL::squared_distance(c, hit.first);
            v.triangle = ids_[size_t(hit.second - triangles_.cbegin())];
        }
        for (const auto& d : degenerate_) {
            // Distance to a degenerate triangle: to the nearest of its edges.
            for (const auto& [a, b] : {std::pair{d.a, d.b}, std::pair{d.b, d.c}, std::pair{d.a, d.c}}) {
                const double s = a == b ? CGAL::squared_distance(c, a) : CGAL::squared_distance(c, K::Segment_3(a, b));
                if (s < best) best = s, v.triangle = d.id;
            }
        }
        v.distance = std::sqrt(best);
        return v;
    }

private:
    struct Degenerate {
        K::Point_3 a, b, c;
        int64_t id;
    };
    Triangles triangles_;
    std::vector<int64_t> ids_;
    std::vector<Degenerate> degenerate_;
    Tree tree_;
};

std::vector<VoxelCase> worstOf(const std::vector<uint64_t>& keys, const Distances& d, const GridSpec& grid,
                               size_t worst, bool nearestFirst)
{
    // Distances for a bounded sample: every key when few, else an even stride.
    const size_t limit = 20000;
    const size_t stride = std::max<size_t>(1, keys.size() / limit);
    std::vector<VoxelCase> cases;
    for (size_t i = 0; i < keys.size(); i += stride) cases.push_back(d.at(grid, keys[i]));
    std::sort(cases.begin(), cases.end(), [&](const auto& a, const auto& b) {
        return nearestFirst ? a.distance < b.distance : a.distance > b.distance;
    });
    if (cases.size() > worst) cases.resize(worst);
    return cases;
}

} // namespace

Classification classify(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<uint64_t>& gpu,
                        const ReferenceSets& ref, size_t worst)
{
    Classification c;
    c.voxels = gpu.size();
    c.required = ref.required.size();
    c.exact = ref.exact.size();
    c.allowed = ref.allowed.size();
    std::set_difference(ref.required.begin(), ref.required.end(), gpu.begin(), gpu.end(), std::back_inserter(c.missed));
    std::set_difference(ref.exact.begin(), ref.exact.end(), gpu.begin(), gpu.end(), std::back_inserter(c.missedExact));
    std::set_difference(gpu.begin(), gpu.end(), ref.allowed.begin(), ref.allowed.end(), std::back_inserter(c.extra));
    std::vector<uint64_t> inA;
    std::set_intersection(gpu.begin(), gpu.end(), ref.allowed.begin(), ref.allowed.end(), std::back_inserter(inA));
    std::set_difference(inA.begin(), inA.end(), ref.required.begin(), ref.required.end(), std::back_inserter(c.boundary));
    if (!c.missedExact.empty() || !c.extra.empty()) {
        const Distances d(mesh, grid);
        c.worstMissed = worstOf(c.missedExact, d, grid, worst, true);
        c.worstExtra = worstOf(c.extra, d, grid, worst, false);
    }
    return c;
}

} // namespace svo::validate
