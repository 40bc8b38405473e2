#pragma once
/// @file stability_scenes.h
/// Adversarial scenes for the stability suite, all generated here: the cases
/// where rasterizing voxelizers lose voxels.
#include <cmath>
#include <string>
#include <vector>

#include "scenes.h"
#include "svo/core/grid.h"

namespace svo::test {

struct Scene {
    std::string group, name;
    TriangleMesh mesh;
    GridRequest grid;
};

inline TriangleMesh soup(const std::string& name, const std::vector<std::array<Vec3d, 3>>& tris)
{
    TriangleMesh m;
    m.source = name;
    for (const auto& t : tris) {
        const uint32_t b = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), t.begin(), t.end());
        m.triangles.push_back({b, b + 1, b + 2});
    }
    return m;
}

inline TriangleMesh translated(TriangleMesh m, Vec3d by, const std::string& name)
{
    for (auto& p : m.positions) p = p + by;
    m.source = name;
    return m;
}

inline TriangleMesh scaled(TriangleMesh m, double s, const std::string& name)
{
    for (auto& p : m.positions) p = s * p;
    m.source = name;
    return m;
}

/// A staircase of unit steps on grid lines (voxel size 1): faces on voxel planes.
inline TriangleMesh staircase(int steps)
{
    std::vector<std::array<Vec3d, 3>> t;
    for (int i = 0; i < steps; ++i) {
        const double x0 = i + 0.5, x1 = i + 1.5, z = i + 0.5, y0 = 0.5, y1 = 6.5;
        t.push_back({Vec3d{x0, y0, z}, Vec3d{x1, y0, z}, Vec3d{x1, y1, z}}); // tread
        t.push_back({Vec3d{x0, y0, z}, Vec3d{x1, y1, z}, Vec3d{x0, y1, z}});
        t.push_back({Vec3d{x1, y0, z}, Vec3d{x1, y0, z + 1}, Vec3d{x1, y1, z + 1}}); // riser
        t.push_back({Vec3d{x1, y0, z}, Vec3d{x1, y1, z + 1}, Vec3d{x1, y1, z}});
    }
    return soup("staircase", t);
}

inline std::vector<Scene> stabilityScenes()
{
    std::vector<Scene> s;
    const GridRequest unit{0, 1.0};
    const Vec3d o{10.3, 10.7, 10.1};
    // Degenerate triangles.
    s.push_back({"degenerate", "zero area (collinear)", soup("collinear", {{o, o + Vec3d{3, 1, 2}, o + Vec3d{6, 2, 4}}}), unit});
    s.push_back({"degenerate", "repeated vertices (a point)", soup("point", {{o, o, o}, {o + Vec3d{0.5, 0.5, 0.5}, o + Vec3d{0.5, 0.5, 0.5}, o + Vec3d{0.5, 0.5, 0.5}}}), unit});
    s.push_back({"degenerate", "needle, aspect 1e7", soup("needle", {{o, o + Vec3d{20, 7, 3}, o + Vec3d{20, 7, 3 + 2e-6}}}), unit});
    s.push_back({"degenerate", "sliver, aspect 1e7", soup("sliver", {{o, o + Vec3d{20, 0, 0}, o + Vec3d{10, 2e-6, 1e-6}}}), unit});
    // On voxel faces, edges and corners (voxel size 1: boundaries at k + 1/2).
    s.push_back({"on the lattice", "triangle in a voxel face plane", soup("face plane", {{Vec3d{0.5, 0.5, 4.5}, Vec3d{8.5, 0.5, 4.5}, Vec3d{0.5, 8.5, 4.5}}}), unit});
    s.push_back({"on the lattice", "edges along voxel edges", soup("voxel edges", {{Vec3d{0.5, 0.5, 0.5}, Vec3d{8.5, 0.5, 0.5}, Vec3d{0.5, 0.5, 8.5}}}), unit});
    s.push_back({"on the lattice", "through voxel corners", soup("corners", {{Vec3d{0.5, 0.5, 0.5}, Vec3d{6.5, 3.5, 2.5}, Vec3d{2.5, 6.5, 4.5}}}), unit});
    s.push_back({"on the lattice", "box on grid lines", box({0.5, 0.5, 0.5}, {8.5, 6.5, 4.5}), unit});
    s.push_back({"on the lattice", "box through voxel centres", box({-4, -4, -4}, {4, 4, 4}), unit});
    s.push_back({"on the lattice", "staircase on grid lines", staircase(8), unit});
    s.push_back({"on the lattice", "faces 0.005 voxels off the planes", box({0.505, 0.505, 0.505}, {6.495, 6.495, 6.495}), unit});
    // Dominant-axis ties.
    s.push_back({"axis ties", "|nx| = |ny| = |nz|", soup("tie xyz", {{o, o + Vec3d{6, -6, 0}, o + Vec3d{0, 6, -6}}}), unit});
    s.push_back({"axis ties", "|nx| = |ny|, nz = 0", soup("tie xy", {{o, o + Vec3d{6, -6, 0}, o + Vec3d{0, 0, 7}}}), unit});
    s.push_back({"axis ties", "|ny| = |nz|, nx = 0", soup("tie yz", {{o, o + Vec3d{0, 6, -6}, o + Vec3d{7, 0, 0}}}), unit});
    s.push_back({"axis ties", "|nx| = |nz|, ny = 0", soup("tie xz", {{o, o + Vec3d{6, 0, -6}, o + Vec3d{0, 7, 0}}}), unit});
    s.push_back({"axis ties", "ties on voxel corners", soup("tie corners", {{Vec3d{0.5, 0.5, 6.5}, Vec3d{6.5, 0.5, 0.5}, Vec3d{0.5, 6.5, 0.5}}}), unit});
    // Tiny, huge, dense.
    s.push_back({"size", "tiny triangles (1e-6 voxel)", soup("tiny", {{o, o + Vec3d{1e-6, 0, 0}, o + Vec3d{0, 1e-6, 0}}, {Vec3d{4.5, 4.5, 4.5}, Vec3d{4.5 + 1e-6, 4.5, 4.5}, Vec3d{4.5, 4.5 + 1e-6, 4.5}}}), unit});
    s.push_back({"size", "one triangle spanning the grid", soup("huge", {{Vec3d{0, 0, 0}, Vec3d{1, 0.3, 0.1}, Vec3d{0.2, 1, 0.9}}}), {512, 0}});
    {
        std::vector<std::array<Vec3d, 3>> fan;
        const int n = 10000;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * M_PI * i / n, b = 2 * M_PI * (i + 1) / n;
            fan.push_back({o, o + Vec3d{8 * std::cos(a), 8 * std::sin(a), 2 * std::sin(3 * a)},
                           o + Vec3d{8 * std::cos(b), 8 * std::sin(b), 2 * std::sin(3 * b)}});
        }
        s.push_back({"size", "dense fan, 10,000 triangles at one vertex", soup("fan", fan), unit});
    }
    // Far from the origin; extreme voxel sizes (the same sphere, scaled).
    const TriangleMesh ball = icosphere({0.3, 0.2, 0.1}, 1.0, 3);
    s.push_back({"placement", "sphere at the origin", ball, {64, 0}});
    s.push_back({"placement", "translated by 1e6", translated(ball, {1e6, -1e6, 1e6}, "sphere +1e6"), {64, 0}});
    s.push_back({"placement", "translated by 1e9", translated(ball, {1e9, 1e9, -1e9}, "sphere +1e9"), {64, 0}});
    s.push_back({"placement", "voxel size 1e-6", scaled(ball, 3.2e-5, "sphere, h = 1e-6"), {0, 1e-6}});
    s.push_back({"placement", "voxel size 1e6", scaled(ball, 3.2e7, "sphere, h = 1e6"), {0, 1e6}});
    // Resolutions.
    for (int r : {1, 2, 3, 37, 100}) s.push_back({"resolution", "resolution " + std::to_string(r), ball, {r, 0}});
    // The largest grid: 2^21 - 16 voxels between two tiny triangles.
    s.push_back({"grid size", "2,097,136 voxels along one axis",
                 soup("far apart", {{Vec3d{0, 0, 0}, Vec3d{1e-6, 0, 0}, Vec3d{0, 1e-6, 0}},
                                    {Vec3d{1, 0, 0}, Vec3d{1, 1e-6, 0}, Vec3d{1, 0, 1e-6}}}),
                 {(1 << 21) - 16, 0}});
    // Many triangles.
    s.push_back({"scale", "icosphere, 1,310,720 triangles", icosphere({0, 0, 0}, 1.0, 8), {128, 0}});
    // Topology.
    {
        TriangleMesh open = box({0.3, 0.3, 0.3}, {6.2, 5.1, 4.7});
        open.triangles.resize(10);
        open.source = "open box";
        s.push_back({"topology", "open box", open, unit});
        TriangleMesh flipped = box({0.3, 0.3, 0.3}, {6.2, 5.1, 4.7});
        for (size_t i = 0; i < flipped.triangles.size(); i += 3) std::swap(flipped.triangles[i][1], flipped.triangles[i][2]);
        flipped.source = "inconsistent winding";
        s.push_back({"topology", "inconsistent winding", flipped, unit});
        TriangleMesh dup = box({0.3, 0.3, 0.3}, {6.2, 5.1, 4.7});
        const auto copy = dup.triangles;
        dup.triangles.insert(dup.triangles.end(), copy.begin(), copy.end());
        dup.source = "duplicate faces";
        s.push_back({"topology", "duplicate faces", dup, unit});
        s.push_back({"topology", "non-manifold edge (3 faces)",
                     soup("non-manifold", {{o, o + Vec3d{6, 0, 0}, o + Vec3d{3, 5, 0}},
                                           {o, o + Vec3d{6, 0, 0}, o + Vec3d{3, -4, 3}},
                                           {o, o + Vec3d{6, 0, 0}, o + Vec3d{3, 1, -5}}}),
                     unit});
    }
    return s;
}

} // namespace svo::test
