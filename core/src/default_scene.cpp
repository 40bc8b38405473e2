#include "svo/core/default_scene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

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
    // The classic room's reflectances as vertex colours: white, a red left
    // wall and a green right one (a lit picture shows the bounce's colour).
    const Vec3f white{0.73f, 0.71f, 0.68f}, red{0.63f, 0.065f, 0.05f}, green{0.14f, 0.45f, 0.091f};
    auto paint = [&m](Vec3f c) { m.colors.resize(m.positions.size(), c); }; // the vertices added since
    addQuad(m, {-1, 0, -1}, {2, 0, 0}, {0, 0, 2}, wall);  // floor
    addQuad(m, {-1, 2, -1}, {0, 0, 2}, {2, 0, 0}, wall);  // ceiling
    addQuad(m, {-1, 0, -1}, {0, 2, 0}, {2, 0, 0}, wall);  // back
    paint(white);
    addQuad(m, {-1, 0, -1}, {0, 0, 2}, {0, 2, 0}, wall);  // left
    paint(red);
    addQuad(m, {1, 0, -1}, {0, 2, 0}, {0, 0, 2}, wall);   // right
    paint(green);
    addBlock(m, {0.35, 0, 0.3}, {0.6, 0.6, 0.6}, -0.29, block); // short block
    addBlock(m, {-0.35, 0, -0.3}, {0.6, 1.2, 0.6}, 0.30, block); // tall block
    paint(white);
    return m;
}

TriangleMesh twoRooms()
{
    TriangleMesh m;
    m.source = "two_rooms";
    const int n = 8;
    addQuad(m, {-1, 0, -1}, {2, 0, 0}, {0, 0, 2}, n); // floor
    addQuad(m, {-1, 1, -1}, {0, 0, 2}, {2, 0, 0}, n); // ceiling
    addQuad(m, {-1, 0, -1}, {0, 1, 0}, {2, 0, 0}, n); // back
    addQuad(m, {-1, 0, 1}, {2, 0, 0}, {0, 1, 0}, n);  // front
    addQuad(m, {-1, 0, -1}, {0, 0, 2}, {0, 1, 0}, n); // left
    addQuad(m, {1, 0, -1}, {0, 1, 0}, {0, 0, 2}, n);  // right
    addQuad(m, {0, 0, -1}, {0, 1, 0}, {0, 0, 2}, n);  // the wall between the rooms
    return m;
}

TriangleMesh sphereGrid()
{
    TriangleMesh m;
    m.source = "sphere_grid";
    const double pi = 3.14159265358979323846;
    const int slices = 40, stacks = 19;
    for (int gx = 0; gx < 6; ++gx)
        for (int gz = 0; gz < 6; ++gz) {
            const Vec3d c{2.5 * gx, 1.0, 2.5 * gz};
            const uint32_t base = uint32_t(m.positions.size());
            for (int j = 0; j <= stacks; ++j)
                for (int i = 0; i <= slices; ++i) {
                    const double th = pi * j / stacks, ph = 2 * pi * i / slices;
                    m.positions.push_back(c + Vec3d{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)});
                }
            auto at = [&](int i, int j) { return base + uint32_t(j * (slices + 1) + i); };
            for (int j = 0; j < stacks; ++j)
                for (int i = 0; i < slices; ++i) {
                    m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                    m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
                }
        }
    return m;
}

TriangleMesh icosphere(Vec3d c, double r, int levels)
{
    TriangleMesh m;
    m.source = "icosphere";
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3d> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                            {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<std::array<uint32_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    auto unit = [](Vec3d v) { return (1.0 / std::sqrt(dot(v, v))) * v; };
    for (auto& v : p) v = unit(v);
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back(unit(0.5 * (p[a] + p[b])));
            return mid[key] = uint32_t(p.size() - 1);
        };
        std::vector<std::array<uint32_t, 3>> next;
        next.reserve(f.size() * 4);
        for (const auto& t3 : f) {
            const uint32_t ab = midpoint(t3[0], t3[1]), bc = midpoint(t3[1], t3[2]), ca = midpoint(t3[2], t3[0]);
            next.push_back({t3[0], ab, ca});
            next.push_back({t3[1], bc, ab});
            next.push_back({t3[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        f = std::move(next);
    }
    for (const auto& v : p) m.positions.push_back(c + r * v);
    m.triangles = std::move(f);
    return m;
}


} // namespace svo
