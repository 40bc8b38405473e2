// The winding tree of svo/core/winding_tree.h: a median-split hierarchy with
// a dipole per node, and the exact solid-angle sum it is held to.
#include "svo/core/winding_tree.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>

#include "svo/core/error.h"
#include "svo/core/gpu_layout.h"

static_assert(svo::kWindingNodeFloats == 4 * svo::gpu::kWindingNodeVec4s);

namespace svo {
namespace {

constexpr double kFourPi = 4.0 * 3.14159265358979323846;

struct Builder {
    const std::vector<Vec3d>& p;
    const std::vector<std::array<uint32_t, 3>>& t;
    std::vector<Vec3d> centroid;
    WindingTree tree;

    uint32_t build(uint32_t first, uint32_t count, uint32_t level)
    {
        tree.depth = std::max(tree.depth, level);
        const uint32_t node = uint32_t(tree.links.size() / 2);
        tree.links.resize(tree.links.size() + 2);
        tree.nodes.resize(tree.nodes.size() + kWindingNodeFloats);
        // Dipole: area vectors summed, centred at the area-weighted centroid
        // (the plain mean when every triangle is degenerate).
        Vec3d n{0, 0, 0}, weighted{0, 0, 0}, mean{0, 0, 0};
        double area = 0;
        Vec3d lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
        for (uint32_t i = first; i < first + count; ++i) {
            const auto& f = t[tree.order[i]];
            const Vec3d a = 0.5 * cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
            const double s = std::sqrt(dot(a, a));
            n = n + a;
            area += s;
            weighted = weighted + s * centroid[tree.order[i]];
            mean = mean + centroid[tree.order[i]];
            for (int k = 0; k < 3; ++k)
                lo[k] = std::min(lo[k], centroid[tree.order[i]][k]), hi[k] = std::max(hi[k], centroid[tree.order[i]][k]);
        }
        const Vec3d c = area > 0 ? (1.0 / area) * weighted : (1.0 / count) * mean;
        double r2 = 0;
        for (uint32_t i = first; i < first + count; ++i)
            for (uint32_t v : t[tree.order[i]]) {
                const Vec3d d = p[v] - c;
                r2 = std::max(r2, dot(d, d));
            }
        // Moments of the area vectors about c, over each triangle's points x
        // (the normal is constant on a triangle): first C_ij = sum a_i o_j,
        // o = x - c, which is a_i times the centroid's offset; second
        // M_ijk = sum a_i o_j o_k, which is a_i times the offset's outer
        // product plus the triangle's covariance, sum over corners of
        // e e^T / 12 with e = corner - centroid. M is kept for j <= k.
        double m1[3][3] = {}, m2[3][6] = {};
        constexpr int kPair[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
        for (uint32_t i = first; i < first + count; ++i) {
            const auto& f = t[tree.order[i]];
            const Vec3d a = 0.5 * cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
            const Vec3d& x = centroid[tree.order[i]];
            const Vec3d o = x - c;
            double cov[6];
            for (int q = 0; q < 6; ++q) {
                const int j = kPair[q][0], k = kPair[q][1];
                cov[q] = o[j] * o[k];
                for (uint32_t v : f) cov[q] += (p[v][j] - x[j]) * (p[v][k] - x[k]) / 12.0;
            }
            for (int row = 0; row < 3; ++row) {
                for (int col = 0; col < 3; ++col) m1[row][col] += a[row] * o[col];
                for (int q = 0; q < 6; ++q) m2[row][q] += a[row] * cov[q];
            }
        }
        float* w = &tree.nodes[kWindingNodeFloats * size_t(node)];
        // Rounded up, so the float ball still holds every corner.
        const float r = std::nextafter(float(std::sqrt(r2)), INFINITY);
        const double values[kWindingNodeFloats] = {
            c.x,       c.y,       c.z,       r,         n.x,       n.y,       n.z,       m1[0][0], m1[0][1],
            m1[0][2],  m1[1][0],  m1[1][1],  m1[1][2],  m1[2][0],  m1[2][1],  m1[2][2],  m2[0][0], m2[0][1],
            m2[0][2],  m2[0][3],  m2[0][4],  m2[0][5],  m2[1][0],  m2[1][1],  m2[1][2],  m2[1][3], m2[1][4],
            m2[1][5],  m2[2][0],  m2[2][1],  m2[2][2],  m2[2][3],  m2[2][4],  m2[2][5],  0,        0};
        for (uint32_t k = 0; k < kWindingNodeFloats; ++k) w[k] = float(values[k]);
        if (count <= kWindingLeafSize) {
            tree.links[2 * size_t(node)] = first;
            tree.links[2 * size_t(node) + 1] = count | 0x80000000u;
            return node;
        }
        int axis = 0;
        for (int k = 1; k < 3; ++k)
            if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
        const uint32_t half = count / 2;
        auto* begin = tree.order.data() + first;
        // Ties broken by index, so the tree does not depend on the sort.
        std::nth_element(begin, begin + half, begin + count, [&](uint32_t x, uint32_t y) {
            return centroid[x][axis] < centroid[y][axis] || (centroid[x][axis] == centroid[y][axis] && x < y);
        });
        const uint32_t left = build(first, half, level + 1);
        const uint32_t right = build(first + half, count - half, level + 1);
        tree.links[2 * size_t(node)] = left;
        tree.links[2 * size_t(node) + 1] = right;
        return node;
    }
};

} // namespace

WindingTree buildWindingTree(const std::vector<Vec3d>& positions, const std::vector<std::array<uint32_t, 3>>& triangles)
{
    if (triangles.empty()) throw Error("a winding tree needs at least one triangle");
    if (triangles.size() >= (size_t(1) << 31))
        throw Error(fmt::format("{} triangles are more than a winding tree holds (2^31)", triangles.size()));
    Builder b{positions, triangles, {}, {}};
    b.centroid.resize(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) {
        const auto& f = triangles[i];
        b.centroid[i] = (1.0 / 3.0) * (positions[f[0]] + positions[f[1]] + positions[f[2]]);
    }
    b.tree.order.resize(triangles.size());
    std::iota(b.tree.order.begin(), b.tree.order.end(), 0u);
    // About two nodes for every leaf's worth of triangles.
    b.tree.links.reserve(4 * (triangles.size() / kWindingLeafSize + 1));
    b.tree.nodes.reserve(2 * kWindingNodeFloats * (triangles.size() / kWindingLeafSize + 1));
    b.build(0, uint32_t(triangles.size()), 0);
    return std::move(b.tree);
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
