#include "svo/core/default_scene.h"

#include <cmath>

namespace svo {
namespace {

/// Appends the quad origin + s*du + t*dv, s,t in [0,1], as an n x n grid of
/// triangle pairs.
void addQuad(TriangleMesh& m, Vec3d origin, Vec3d du, Vec3d dv, int n)
{
    const uint32_t base = uint32_t(m.positions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.positions.push_back(origin + (double(i) / n) * du + (double(j) / n) * dv);
    auto at = [&](int i, int j) { return base + uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
}

/// A block standing on the floor, rotated by `angle` about the vertical axis.
void addBlock(TriangleMesh& m, Vec3d centre, Vec3d size, double angle, int n)
{
    const double c = std::cos(angle), s = std::sin(angle);
    auto rot = [&](Vec3d p) { return Vec3d{c * p.x - s * p.z, p.y, s * p.x + c * p.z}; };
    const Vec3d hx = rot({size.x, 0, 0}), hy{0, size.y, 0}, hz = rot({0, 0, size.z});
    const Vec3d o = centre - 0.5 * hx - 0.5 * hz; // bottom corner
    addQuad(m, o, hz, hx, n);                     // bottom
    addQuad(m, o + hy, hx, hz, n);                // top
    addQuad(m, o, hx, hy, n);                     // front
    addQuad(m, o + hz, hy, hx, n);                // back
    addQuad(m, o, hy, hz, n);                     // left
    addQuad(m, o + hx, hz, hy, n);                // right
}

} // namespace

TriangleMesh cornellBox()
{
    TriangleMesh m;
    m.source = "cornell_box";
    const int wall = 14, block = 7;
    addQuad(m, {-1, 0, -1}, {2, 0, 0}, {0, 0, 2}, wall);  // floor
    addQuad(m, {-1, 2, -1}, {0, 0, 2}, {2, 0, 0}, wall);  // ceiling
    addQuad(m, {-1, 0, -1}, {0, 2, 0}, {2, 0, 0}, wall);  // back
    addQuad(m, {-1, 0, -1}, {0, 0, 2}, {0, 2, 0}, wall);  // left
    addQuad(m, {1, 0, -1}, {0, 2, 0}, {0, 0, 2}, wall);   // right
    addBlock(m, {0.35, 0, 0.3}, {0.6, 0.6, 0.6}, -0.29, block); // short block
    addBlock(m, {-0.35, 0, -0.3}, {0.6, 1.2, 0.6}, 0.30, block); // tall block
    return m;
}

} // namespace svo
