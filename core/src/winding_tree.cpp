// The winding tree of svo/core/winding_tree.h: a median-split hierarchy
// whose nodes keep their triangles' far field to second order, and the
// exact solid-angle sum it is held to.
#include "svo/core/winding_tree.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "svo/core/error.h"
#include "svo/core/gpu_layout.h"
#include "svo/core/winding_pieces.h"

static_assert(svo::kWindingNodeFloats == 4 * svo::gpu::kWindingNodeVec4s);

namespace svo {
namespace {

constexpr double kFourPi = 4.0 * 3.14159265358979323846;
/// Subtrees of more triangles than this are built on two tasks.
constexpr uint32_t kParallelTriangles = 4096;
constexpr int kPair[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};

/// A set of triangles' far field about its own centre, in double: what a
/// node keeps, before it is rounded to float. A parent's comes from its
/// children's, moved to the parent's centre, so each level costs as many
/// combinations as it has nodes rather than triangles.
struct Moments {
    Vec3d centre{0, 0, 0};
    double area = 0;               ///< sum of |a|
    Vec3d weighted{0, 0, 0};       ///< sum of |a| times the triangle's centroid
    Vec3d mean{0, 0, 0};           ///< sum of centroids (the centre when every area is zero)
    uint32_t count = 0;
    Vec3d n{0, 0, 0};              ///< N_i
    double c[3][3] = {};           ///< C_ij
    double m[3][6] = {};           ///< M_i(jk), j <= k as in kPair

    /// Adds `o`, taken about o.centre, to a sum about `centre` (set first):
    /// with d = o.centre - centre, C_ij += C'_ij + N'_i d_j and
    /// M_ijk += M'_ijk + C'_ij d_k + C'_ik d_j + N'_i d_j d_k.
    void add(const Moments& o)
    {
        const Vec3d d = o.centre - centre;
        area += o.area;
        weighted = weighted + o.weighted;
        mean = mean + o.mean;
        count += o.count;
        n = n + o.n;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) c[i][j] += o.c[i][j] + o.n[i] * d[j];
            for (int q = 0; q < 6; ++q) {
                const int j = kPair[q][0], k = kPair[q][1];
                m[i][q] += o.m[i][q] + o.c[i][j] * d[k] + o.c[i][k] * d[j] + o.n[i] * d[j] * d[k];
            }
        }
    }
};

/// The area-weighted centroid of a set of triangles (the plain mean of
/// the centroids when every triangle is degenerate).
Vec3d centreOf(double area, const Vec3d& weighted, const Vec3d& mean, uint32_t count)
{
    return area > 0 ? (1.0 / area) * weighted : (1.0 / count) * mean;
}

/// Nodes of the subtree over `count` triangles: the split is always at
/// count / 2, so this fixes every node's index before any is built, and
/// the two halves can be built at once with the same result.
uint32_t nodesFor(uint32_t count)
{
    return count <= kWindingLeafSize ? 1 : 1 + nodesFor(count / 2) + nodesFor(count - count / 2);
}

struct Builder {
    const std::vector<Vec3d>& p;
    const std::vector<std::array<uint32_t, 3>>& t;
    std::vector<Vec3d> centroid;
    WindingTree& tree;

    /// Triangle i's moments about its centroid x: N = a (half the cross
    /// product), C = 0, and M_ijk = a_i times the corners' covariance, the
    /// sum of e_j e_k / 12 with e = corner - x (the normal is constant on a
    /// triangle, and the second moment of its points about x is that).
    Moments ofTriangle(uint32_t i) const
    {
        const auto& f = t[i];
        Moments m;
        m.centre = centroid[i];
        m.n = 0.5 * cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
        m.area = std::sqrt(dot(m.n, m.n));
        m.weighted = m.area * m.centre;
        m.mean = m.centre;
        m.count = 1;
        for (int q = 0; q < 6; ++q) {
            const int j = kPair[q][0], k = kPair[q][1];
            double cov = 0;
            for (uint32_t v : f) cov += (p[v][j] - m.centre[j]) * (p[v][k] - m.centre[k]) / 12.0;
            for (int row = 0; row < 3; ++row) m.m[row][q] = m.n[row] * cov;
        }
        return m;
    }

    /// Builds the subtree of order[first, first + count) as node `node` and
    /// its descendants (in depth-first order), and returns its moments.
    Moments build(uint32_t node, uint32_t first, uint32_t count, uint32_t level, uint32_t& depth)
    {
        depth = std::max(depth, level);
        uint32_t* order = tree.order.data() + first;
        Moments sum;
        if (count <= kWindingLeafSize) {
            Moments own[kWindingLeafSize];
            double area = 0;
            Vec3d weighted{0, 0, 0}, mean{0, 0, 0};
            for (uint32_t i = 0; i < count; ++i) {
                own[i] = ofTriangle(order[i]);
                area += own[i].area, weighted = weighted + own[i].weighted, mean = mean + own[i].mean;
            }
            sum.centre = centreOf(area, weighted, mean, count);
            for (uint32_t i = 0; i < count; ++i) sum.add(own[i]);
            tree.links[2 * size_t(node)] = first;
            tree.links[2 * size_t(node) + 1] = count | 0x80000000u;
        } else {
            Vec3d lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
            for (uint32_t i = 0; i < count; ++i)
                for (int k = 0; k < 3; ++k) {
                    const double x = centroid[order[i]][k];
                    lo[k] = std::min(lo[k], x), hi[k] = std::max(hi[k], x);
                }
            int axis = 0;
            for (int k = 1; k < 3; ++k)
                if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
            const uint32_t half = count / 2;
            // Ties broken by index, so the tree does not depend on the sort.
            std::nth_element(order, order + half, order + count, [&](uint32_t x, uint32_t y) {
                const double cx = centroid[x][axis], cy = centroid[y][axis];
                return cx < cy || (cx == cy && x < y);
            });
            const uint32_t left = node + 1, right = node + 1 + nodesFor(half);
            Moments a, b;
            uint32_t depthA = level, depthB = level;
            auto buildLeft = [&] { a = build(left, first, half, level + 1, depthA); };
            auto buildRight = [&] { b = build(right, first + half, count - half, level + 1, depthB); };
            if (count > kParallelTriangles)
                tbb::parallel_invoke(buildLeft, buildRight);
            else
                buildLeft(), buildRight();
            depth = std::max({depth, depthA, depthB});
            sum.centre = centreOf(a.area + b.area, a.weighted + b.weighted, a.mean + b.mean, a.count + b.count);
            sum.add(a);
            sum.add(b);
            tree.links[2 * size_t(node)] = left;
            tree.links[2 * size_t(node) + 1] = right;
        }
        // The ball about the centre that holds every corner: rounded up, so
        // the float ball still holds them.
        double r2 = 0;
        for (uint32_t i = 0; i < count; ++i)
            for (uint32_t v : t[order[i]]) {
                const Vec3d d = p[v] - sum.centre;
                r2 = std::max(r2, dot(d, d));
            }
        const float r = std::nextafter(float(std::sqrt(r2)), INFINITY);
        const Vec3d& c = sum.centre;
        const double values[kWindingNodeFloats] = {
            c.x,          c.y,          c.z,          r,            sum.n.x,      sum.n.y,      sum.n.z,
            sum.c[0][0],  sum.c[0][1],  sum.c[0][2],  sum.c[1][0],  sum.c[1][1],  sum.c[1][2],  sum.c[2][0],
            sum.c[2][1],  sum.c[2][2],  sum.m[0][0],  sum.m[0][1],  sum.m[0][2],  sum.m[0][3],  sum.m[0][4],
            sum.m[0][5],  sum.m[1][0],  sum.m[1][1],  sum.m[1][2],  sum.m[1][3],  sum.m[1][4],  sum.m[1][5],
            sum.m[2][0],  sum.m[2][1],  sum.m[2][2],  sum.m[2][3],  sum.m[2][4],  sum.m[2][5],  0,
            0};
        float* w = &tree.nodes[kWindingNodeFloats * size_t(node)];
        for (uint32_t k = 0; k < kWindingNodeFloats; ++k) w[k] = float(values[k]);
        return sum;
    }
};

/// The longest edge of a piece: at least `least`, and kWindingPieceMedians
/// times the median of the triangles' longest edges.
double pieceEdgeFor(const std::vector<Vec3d>& p, const std::vector<std::array<uint32_t, 3>>& t, double least)
{
    if (!(least < INFINITY)) return least;
    std::vector<double> longest(t.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, t.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const Vec3d &a = p[t[i][0]], &b = p[t[i][1]], &c = p[t[i][2]];
            longest[i] = std::sqrt(std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)}));
        }
    });
    const auto middle = longest.begin() + std::ptrdiff_t(longest.size() / 2);
    std::nth_element(longest.begin(), middle, longest.end());
    return std::max(least, kWindingPieceMedians * *middle);
}

} // namespace

WindingTree buildWindingTree(const std::vector<Vec3d>& input, const std::vector<std::array<uint32_t, 3>>& faces,
                             double pieceEdge)
{
    if (faces.empty()) throw InvalidInput("a winding tree needs at least one triangle");
    if (faces.size() >= (size_t(1) << 31))
        throw Unsupported(fmt::format("{} triangles are more than a winding tree holds (2^31)", faces.size()));
    WindingTree tree;
    {
        const size_t budget = std::min(std::max(faces.size() * kWindingPiecesPerTriangle, size_t(1) << 20),
                                       (size_t(1) << 31) - 1);
        WindingPieces pieces = cutLongTriangles(input, faces, pieceEdgeFor(input, faces, pieceEdge), budget);
        tree.positions = std::move(pieces.positions);
        tree.triangles = std::move(pieces.triangles);
        tree.pieceEdge = pieces.edge;
    }
    const std::vector<Vec3d>& positions = tree.positions;
    const std::vector<std::array<uint32_t, 3>>& triangles = tree.triangles;
    Builder b{positions, triangles, std::vector<Vec3d>(triangles.size()), tree};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const auto& f = triangles[i];
            b.centroid[i] = (1.0 / 3.0) * (positions[f[0]] + positions[f[1]] + positions[f[2]]);
        }
    });
    const uint32_t count = uint32_t(triangles.size());
    const uint32_t nodes = nodesFor(count);
    tree.order.resize(count);
    std::iota(tree.order.begin(), tree.order.end(), 0u);
    tree.links.resize(2 * size_t(nodes));
    tree.nodes.resize(kWindingNodeFloats * size_t(nodes));
    b.build(0, 0, count, 0, tree.depth);
    return tree;
}
double triangleWinding(const Vec3d& q, const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    const Vec3d x = a - q, y = b - q, z = c - q;
    const double lx = std::sqrt(dot(x, x)), ly = std::sqrt(dot(y, y)), lz = std::sqrt(dot(z, z));
    const double det = dot(x, cross(y, z));
    const double den = lx * ly * lz + dot(x, y) * lz + dot(y, z) * lx + dot(z, x) * ly;
    if (det == 0.0) return 0.0; // q in the plane (or on a corner): no solid angle
    return 2.0 * std::atan2(det, den) / kFourPi;
}

double windingNumber(const std::vector<Vec3d>& positions, const std::vector<std::array<uint32_t, 3>>& triangles,
                     const Vec3d& q)
{
    double w = 0;
    for (const auto& f : triangles) w += triangleWinding(q, positions[f[0]], positions[f[1]], positions[f[2]]);
    return w;
}

} // namespace svo
