#include "svo/validate/exact_reference.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "local_points.h"
#include "svo/core/voxel_key.h"

namespace svo::validate {
namespace {

using K = detail::K;

bool meets(const K::Triangle_3& t, const CGAL::Bbox_3& b) { return CGAL::do_intersect(t, b); }
bool meets(const K::Segment_3& s, const CGAL::Bbox_3& b) { return CGAL::do_intersect(s, b); }
bool meets(const K::Point_3& p, const CGAL::Bbox_3& b)
{
    return b.xmin() <= p.x() && p.x() <= b.xmax() && b.ymin() <= p.y() && p.y() <= b.ymax() && b.zmin() <= p.z() &&
           p.z() <= b.zmax();
}
// The thin mode's centre segments against each kind of primitive, exactly.
bool meets(const K::Triangle_3& t, const K::Segment_3& s) { return CGAL::do_intersect(t, s); }
bool meets(const K::Segment_3& a, const K::Segment_3& b) { return CGAL::do_intersect(a, b); }
bool meets(const K::Point_3& p, const K::Segment_3& s) { return s.has_on(p); }

/// The box of voxel c grown (or shrunk) to half extents h.
CGAL::Bbox_3 box(const std::array<int64_t, 3>& c, const std::array<double, 3>& h)
{
    return CGAL::Bbox_3(double(c[0]) - h[0], double(c[1]) - h[1], double(c[2]) - h[2], double(c[0]) + h[0],
                        double(c[1]) + h[1], double(c[2]) + h[2]);
}

/// Membership of one voxel of A: 2 = in R (and so in E), 1 = in E only, 0 = in A only.
/// (Keys use 63 bits, so the flags cannot share their word.)
using Level = uint8_t;

/// Conservative: cubes. The caller has already found the cube grown by eps
/// to meet `prim` (the voxel is in A).
template <typename Prim>
Level cubeLevel(const Prim& prim, const std::array<int64_t, 3>& c, double eps, uint64_t& tests)
{
    const double s = 0.5 - eps;
    ++tests;
    const bool required = s >= 0 && meets(prim, box(c, {s, s, s}));
    // E, the closed cube itself: implied by R, decided by A when eps is 0.
    bool exact = required || eps == 0;
    if (!exact) {
        ++tests;
        exact = meets(prim, box(c, {0.5, 0.5, 0.5}));
    }
    return required ? 2 : exact ? 1 : 0;
}

/// Thin: the three centre segments along x, y and z. E and R are exact
/// segment tests (half length 1/2, and 1/2 - eps); A is the segments grown
/// by eps in every direction, boxes of half extents 1/2 + eps along and eps
/// across, which is what the GPU's thickened segments stay inside. Returns
/// -1 for a voxel outside A.
template <typename Prim>
int thinLevel(const Prim& prim, const std::array<int64_t, 3>& c, double eps, uint64_t& tests)
{
    auto segment = [&c](int axis, double half) {
        std::array<double, 3> a{double(c[0]), double(c[1]), double(c[2])}, b = a;
        a[axis] -= half;
        b[axis] += half;
        return K::Segment_3(K::Point_3(a[0], a[1], a[2]), K::Point_3(b[0], b[1], b[2]));
    };
    auto anySegment = [&](double half) {
        for (int axis = 0; axis < 3; ++axis) {
            ++tests;
            if (meets(prim, segment(axis, half))) return true;
        }
        return false;
    };
    const bool exact = anySegment(0.5);
    bool allowed = exact;
    for (int axis = 0; axis < 3 && !allowed && eps > 0; ++axis) {
        std::array<double, 3> h{eps, eps, eps};
        h[axis] = 0.5 + eps;
        ++tests;
        allowed = meets(prim, box(c, h));
    }
    if (!allowed) return -1;
    // A segment shrunk to nothing (eps >= 1/2) meets nothing: R is empty then.
    const bool required = exact && (eps == 0 || (0.5 - eps > 0 && anySegment(0.5 - eps)));
    return required ? 2 : exact ? 1 : 0;
}

struct Collector {
    std::vector<std::pair<uint64_t, Level>> keys;
    uint64_t tests = 0;
};

/// Voxels [lo, hi] (inclusive) whose grown cube meets `prim`, by halving;
/// each is then classified by the mode's own test.
template <typename Prim>
void visit(const Prim& prim, std::array<int64_t, 3> lo, std::array<int64_t, 3> hi, double eps, VoxelMode mode,
           Collector& out)
{
    const double g = 0.5 + eps;
    ++out.tests;
    if (!meets(prim, CGAL::Bbox_3(double(lo[0]) - g, double(lo[1]) - g, double(lo[2]) - g, double(hi[0]) + g,
                                  double(hi[1]) + g, double(hi[2]) + g)))
        return;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    if (hi[axis] == lo[axis]) {
        // The thin mode's segments lie inside the cube, so the cube's
        // halving finds every voxel they can meet.
        const int level = mode == VoxelMode::Thin ? thinLevel(prim, lo, eps, out.tests)
                                                  : int(cubeLevel(prim, lo, eps, out.tests));
        if (level >= 0)
            out.keys.emplace_back(packVoxelKey(uint32_t(lo[0]), uint32_t(lo[1]), uint32_t(lo[2])), Level(level));
        return;
    }
    const int64_t mid = lo[axis] + (hi[axis] - lo[axis]) / 2;
    auto upper = lo;
    upper[axis] = mid + 1;
    auto lower = hi;
    lower[axis] = mid;
    visit(prim, lo, lower, eps, mode, out);
    visit(prim, upper, hi, eps, mode, out);
}

} // namespace

ReferenceSets exactReference(const TriangleMesh& mesh, const GridSpec& grid, double eps, VoxelMode mode,
                             const std::function<void(uint64_t, uint64_t)>& progress)
{
    const std::vector<K::Point_3> p = detail::localPoints(mesh, grid);
    tbb::enumerable_thread_specific<Collector> collectors;
    std::atomic<uint64_t> done{0}, degenerate{0};
    const uint64_t total = mesh.triangles.size();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 256), [&](const auto& r) {
        Collector& out = collectors.local();
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            const K::Point_3 &a = p[f[0]], &b = p[f[1]], &c = p[f[2]];
            std::array<int64_t, 3> lo, hi;
            bool empty = false;
            for (int k = 0; k < 3; ++k) {
                const double mn = std::min({a[k], b[k], c[k]}), mx = std::max({a[k], b[k], c[k]});
                lo[k] = std::max<int64_t>(int64_t(std::ceil(mn - 0.5 - eps)), 0);
                hi[k] = std::min<int64_t>(int64_t(std::floor(mx + 0.5 + eps)), int64_t(grid.dims[k]) - 1);
                empty |= lo[k] > hi[k];
            }
            if (empty) continue;
            if (!CGAL::collinear(a, b, c)) {
                visit(K::Triangle_3(a, b, c), lo, hi, eps, mode, out);
            } else if (a == b && b == c) {
                ++degenerate;
                visit(a, lo, hi, eps, mode, out);
            } else {
                ++degenerate;
                // The two outer points of three collinear ones span the segment.
                const K::Segment_3 s = CGAL::collinear_are_ordered_along_line(a, b, c)   ? K::Segment_3(a, c)
                                       : CGAL::collinear_are_ordered_along_line(b, a, c) ? K::Segment_3(b, c)
                                                                                         : K::Segment_3(a, b);
                visit(s, lo, hi, eps, mode, out);
            }
        }
        const uint64_t d = done.fetch_add(r.size()) + r.size();
        if (progress) progress(d, total);
    });

    std::vector<std::pair<uint64_t, Level>> all;
    ReferenceSets sets;
    for (auto& c : collectors) {
        all.insert(all.end(), c.keys.begin(), c.keys.end());
        sets.boxTests += c.tests;
    }
    sets.degenerate = degenerate;
    tbb::parallel_sort(all.begin(), all.end());
    // Coalesce: a voxel is in R (E) if any triangle puts it there.
    for (size_t i = 0; i < all.size();) {
        const uint64_t key = all[i].first;
        Level level = 0;
        for (; i < all.size() && all[i].first == key; ++i) level = std::max(level, all[i].second);
        sets.allowed.push_back(key);
        if (level >= 1) sets.exact.push_back(key);
        if (level == 2) sets.required.push_back(key);
    }
    return sets;
}

} // namespace svo::validate
