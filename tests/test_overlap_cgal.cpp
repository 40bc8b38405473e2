// The shared overlap test (overlap.glsl) against CGAL's exact do_intersect.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>
#include <random>

#include "svo/core/overlap.h"

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using namespace svo;

namespace {

/// CGAL's exact answer for the closed cube [-h, h]^3, with degenerate
/// triangles routed to the segment and point tests.
bool cgalOverlap(Vec3d a, Vec3d b, Vec3d c, double h)
{
    const CGAL::Bbox_3 box(-h, -h, -h, h, h, h);
    const K::Point_3 p(a.x, a.y, a.z), q(b.x, b.y, b.z), r(c.x, c.y, c.z);
    if (!CGAL::collinear(p, q, r)) return CGAL::do_intersect(K::Triangle_3(p, q, r), box);
    // Collinear: the segment between the two farthest points (or a point).
    K::Point_3 s = p, t = q;
    for (auto [u, v] : {std::pair{p, r}, std::pair{q, r}})
        if (CGAL::squared_distance(u, v) > CGAL::squared_distance(s, t)) s = u, t = v;
    if (s == t) return CGAL::do_intersect(s, box);
    return CGAL::do_intersect(K::Segment_3(s, t), box);
}

} // namespace

TEST(OverlapVsCgal, RandomTrianglesAgreeOutsideAThinBand)
{
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    const double d = 1e-9;
    int hits = 0;
    for (int i = 0; i < 200000; ++i) {
        Vec3d a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
        if (i % 10 == 1) c = a + 0.3 * (b - a);
        if (i % 10 == 2) b = c = a;
        const bool ours = triangleBoxOverlap(a, b, c, {0, 0, 0}, 0.5);
        hits += ours;
        if (cgalOverlap(a, b, c, 0.5 - d)) {
            ASSERT_TRUE(ours) << i;
        }
        if (ours) {
            ASSERT_TRUE(cgalOverlap(a, b, c, 0.5 + d)) << i;
        }
    }
    EXPECT_GT(hits, 10000); // both outcomes are well represented
    EXPECT_LT(hits, 190000);
}

TEST(OverlapVsCgal, SnappedCoordinatesAgreeExactly)
{
    // Coordinates on a 1/4 grid: faces on cube planes, edges along cube edges,
    // corners on cube corners. Double arithmetic is exact here, so the answer
    // must equal CGAL's on the closed cube, touching cases included.
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> u(-6, 6);
    auto p = [&] { return Vec3d{u(rng) * 0.25, u(rng) * 0.25, u(rng) * 0.25}; };
    int touching = 0;
    for (int i = 0; i < 100000; ++i) {
        Vec3d a = p(), b = p(), c = p();
        if (i % 3 == 0) b.x = c.x = a.x; // axis-aligned planes
        const bool ours = triangleBoxOverlap(a, b, c, {0, 0, 0}, 0.5);
        const bool exact = cgalOverlap(a, b, c, 0.5);
        ASSERT_EQ(ours, exact) << "triangle " << i << ": (" << a.x << "," << a.y << "," << a.z << ") (" << b.x << ","
                               << b.y << "," << b.z << ") (" << c.x << "," << c.y << "," << c.z << ")";
        touching += exact && !cgalOverlap(a, b, c, 0.499);
    }
    EXPECT_GT(touching, 100); // the exact-touch cases were exercised
}
