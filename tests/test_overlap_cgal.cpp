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

/// The two farthest of three collinear points: the segment (or point) they span.
std::pair<K::Point_3, K::Point_3> span(const K::Point_3& p, const K::Point_3& q, const K::Point_3& r)
{
    K::Point_3 s = p, t = q;
    for (auto [u, v] : {std::pair{p, r}, std::pair{q, r}})
        if (CGAL::squared_distance(u, v) > CGAL::squared_distance(s, t)) s = u, t = v;
    return {s, t};
}

/// CGAL's exact answer for the thin test at the origin: does the triangle meet
/// one of the closed segments from -h to h along x, y or z? Degenerate
/// triangles as segments or points, as above.
bool cgalThin(Vec3d a, Vec3d b, Vec3d c, double h)
{
    const K::Point_3 p(a.x, a.y, a.z), q(b.x, b.y, b.z), r(c.x, c.y, c.z);
    const K::Segment_3 axes[3] = {{{-h, 0, 0}, {h, 0, 0}}, {{0, -h, 0}, {0, h, 0}}, {{0, 0, -h}, {0, 0, h}}};
    const bool flat = CGAL::collinear(p, q, r);
    const auto [s, t] = span(p, q, r);
    for (const auto& axis : axes) {
        const bool meets = !flat   ? CGAL::do_intersect(K::Triangle_3(p, q, r), axis)
                           : s == t ? axis.has_on(s)
                                    : CGAL::do_intersect(K::Segment_3(s, t), axis);
        if (meets) return true;
    }
    return false;
}

/// The thin test's outer bound in CGAL: one of the segments grown by d in
/// every direction (boxes of half extents h + d along, d across).
bool cgalThinGrown(Vec3d a, Vec3d b, Vec3d c, double h, double d)
{
    const K::Point_3 p(a.x, a.y, a.z), q(b.x, b.y, b.z), r(c.x, c.y, c.z);
    const bool flat = CGAL::collinear(p, q, r);
    const auto [s, t] = span(p, q, r);
    for (int axis = 0; axis < 3; ++axis) {
        double e[3] = {d, d, d};
        e[axis] = h + d;
        const CGAL::Bbox_3 box(-e[0], -e[1], -e[2], e[0], e[1], e[2]);
        const bool meets = !flat   ? CGAL::do_intersect(K::Triangle_3(p, q, r), box)
                           : s == t ? CGAL::do_intersect(s, box)
                                    : CGAL::do_intersect(K::Segment_3(s, t), box);
        if (meets) return true;
    }
    return false;
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

TEST(ThinOverlapVsCgal, RandomTrianglesAgreeOutsideAThinBand)
{
    // The thin test with guard 0 (half length 1/2, thickness 0) against
    // CGAL's segment tests: it holds what the segments shortened by d meet,
    // and only what the segments grown by d meet. Then with a guard g, as
    // the GPU runs it, in float: it must keep everything of the exact set.
    std::mt19937 rng(43);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    const double d = 1e-9;
    const float g = 1e-4f;
    int hits = 0, cubeOnly = 0;
    for (int i = 0; i < 100000; ++i) {
        Vec3d a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
        if (i % 10 == 1) c = a + 0.3 * (b - a);
        if (i % 10 == 2) b = c = a;
        const bool ours = triangleThinOverlap(a, b, c, {0, 0, 0}, 0.5, 0.0);
        hits += ours;
        const bool exact = cgalThin(a, b, c, 0.5);
        if (cgalThin(a, b, c, 0.5 - d)) {
            ASSERT_TRUE(ours) << i;
        }
        if (ours) {
            ASSERT_TRUE(cgalThinGrown(a, b, c, 0.5, d)) << i;
        }
        if (exact) {
            const Vec3f fa{float(a.x), float(a.y), float(a.z)}, fb{float(b.x), float(b.y), float(b.z)},
                fc{float(c.x), float(c.y), float(c.z)};
            ASSERT_TRUE(triangleThinOverlap(fa, fb, fc, {0, 0, 0}, 0.5f + g, g)) << i;
        }
        // The segments lie in the cube: thin implies conservative.
        if (ours) {
            ASSERT_TRUE(triangleBoxOverlap(a, b, c, {0, 0, 0}, 0.5)) << i;
        }
        cubeOnly += !ours && triangleBoxOverlap(a, b, c, {0, 0, 0}, 0.5);
    }
    EXPECT_GT(hits, 5000);
    EXPECT_LT(hits, 95000);
    EXPECT_GT(cubeOnly, 1000); // the cube test keeps triangles that pass between the segments
}

TEST(ThinOverlapVsCgal, SnappedCoordinatesAgreeExactly)
{
    // Coordinates on a 1/4 grid: triangles through segment ends, edges along
    // segments, faces containing them. Double arithmetic is exact here, so the
    // thin test must equal CGAL's exact segment tests, touching cases included.
    std::mt19937 rng(8);
    std::uniform_int_distribution<int> u(-6, 6);
    auto p = [&] { return Vec3d{u(rng) * 0.25, u(rng) * 0.25, u(rng) * 0.25}; };
    int touching = 0, hits = 0;
    for (int i = 0; i < 100000; ++i) {
        Vec3d a = p(), b = p(), c = p();
        if (i % 3 == 0) b.x = c.x = a.x; // axis-aligned planes
        if (i % 7 == 1) c = b;           // needles
        if (i % 11 == 2) b = c = a;      // points
        const bool ours = triangleThinOverlap(a, b, c, {0, 0, 0}, 0.5, 0.0);
        const bool exact = cgalThin(a, b, c, 0.5);
        ASSERT_EQ(ours, exact) << "triangle " << i << ": (" << a.x << "," << a.y << "," << a.z << ") (" << b.x << ","
                               << b.y << "," << b.z << ") (" << c.x << "," << c.y << "," << c.z << ")";
        hits += exact;
        touching += exact && !cgalThin(a, b, c, 0.499);
    }
    EXPECT_GT(touching, 100); // segment ends touched exactly
    EXPECT_GT(hits, 5000);
}
