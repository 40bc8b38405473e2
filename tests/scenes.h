#pragma once
/// @file scenes.h
/// Scenes the tests generate: no binary blobs in the repository.
#include <array>
#include <cmath>
#include <map>
#include <vector>
#include <random>

#include "svo/core/default_scene.h"
#include "svo/core/mesh.h"

namespace svo::test {

/// n random triangles, each inside its own well-separated 16^3 cell, with
/// random orientation and shape; every 8th one is degenerate (a needle or a
/// point) to exercise those paths too.
inline TriangleMesh randomTriangles(int n, uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 12.0);
    TriangleMesh m;
    m.source = "random triangles";
    const int per = int(std::ceil(std::cbrt(double(n))));
    for (int t = 0; t < n; ++t) {
        const Vec3d cell{20.0 * (t % per), 20.0 * ((t / per) % per), 20.0 * (t / (per * per))};
        Vec3d a = cell + Vec3d{u(rng), u(rng), u(rng)};
        Vec3d b = cell + Vec3d{u(rng), u(rng), u(rng)};
        Vec3d c = cell + Vec3d{u(rng), u(rng), u(rng)};
        if (t % 8 == 3) c = a + 0.37 * (b - a); // collinear needle
        if (t % 8 == 5) b = c = a;              // a point
        const uint32_t base = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c});
        m.triangles.push_back({base, base + 1, base + 2});
    }
    return m;
}

/// An axis-aligned box [lo, hi]^3, each face split into two triangles.
inline TriangleMesh box(Vec3d lo, Vec3d hi)
{
    TriangleMesh m;
    m.source = "box";
    for (int i = 0; i < 8; ++i) m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    const uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto& f : q) {
        m.triangles.push_back({f[0], f[1], f[2]});
        m.triangles.push_back({f[0], f[2], f[3]});
    }
    return m;
}

/// An open box (the closed box [0,1]x[0,0.5]x[0,0.8] less three of its
/// twelve triangles) and 40 needles beside it: triangles whose corners lie
/// on one slanted line as rounding leaves them, or 1e-9 off it. The box's
/// triangles come first (indices 0-8).
inline TriangleMesh boxAndNeedles()
{
    TriangleMesh open = box({0, 0, 0}, {1, 0.5, 0.8});
    open.triangles.resize(9);
    uint32_t seed = 12345;
    const auto next = [&] { return double(seed = seed * 1664525u + 1013904223u) / 4294967296.0; };
    for (int k = 0; k < 40; ++k) {
        const Vec3d from{1.2 + 0.5 * next(), 0.8 * next(), 0.8 * next()};
        const Vec3d along{next() - 0.5, next() - 0.5, next() - 0.5};
        const double off = k % 2 ? 1e-9 : 0.0;
        const auto first = uint32_t(open.positions.size());
        open.positions.push_back(from + Vec3d{0, off, 0});
        open.positions.push_back(from + (0.6 + 0.3 * next()) * along);
        open.positions.push_back(from + (0.1 + 0.4 * next()) * along + Vec3d{0, 0, off});
        open.triangles.push_back({first, first + 1, first + 2});
    }
    open.source = "open box and needles";
    return open;
}

/// A UV sphere of radius r at centre c.
inline TriangleMesh sphere(Vec3d c, double r, int slices, int stacks)
{
    TriangleMesh m;
    m.source = "sphere";
    const double pi = 3.14159265358979323846;
    for (int j = 0; j <= stacks; ++j)
        for (int i = 0; i <= slices; ++i) {
            const double th = pi * j / stacks, ph = 2 * pi * i / slices;
            m.positions.push_back(c + r * Vec3d{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)});
        }
    auto at = [&](int i, int j) { return uint32_t(j * (slices + 1) + i); };
    for (int j = 0; j < stacks; ++j)
        for (int i = 0; i < slices; ++i) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

/// icosphere() lives in svo/core/default_scene.h: the CLI generates it too.
using svo::icosphere;

/// `mesh` as a soup: three vertices of its own per triangle (the same
/// positions), as STL files and unwelded exports store meshes.
inline TriangleMesh asSoup(const TriangleMesh& mesh)
{
    TriangleMesh out;
    out.source = mesh.source + " as a soup";
    for (const auto& t : mesh.triangles) {
        const auto base = uint32_t(out.positions.size());
        for (uint32_t k : t) out.positions.push_back(mesh.positions[k]);
        out.triangles.push_back({base, base + 1, base + 2});
    }
    return out;
}

} // namespace svo::test
