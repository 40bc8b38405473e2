#pragma once
/// @file octree_scenes.h
/// Voxel sets for octree tests, generated: random scatters, a sphere shell.
#include <cmath>
#include <random>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/voxel_key.h"

namespace svo::test {

inline GridSpec gridOf(uint32_t x, uint32_t y, uint32_t z)
{
    GridSpec g;
    g.voxelSize = 0.5;
    g.anchor = {-64, 8, 1024};
    g.dims = {x, y, z};
    return g;
}

/// n random voxels in the grid, with duplicates (each drawn twice).
inline std::vector<uint64_t> randomVoxels(const GridSpec& g, size_t n, uint32_t seed)
{
    std::mt19937 rng(seed);
    std::vector<uint64_t> keys;
    for (size_t i = 0; i < n; ++i) {
        const uint64_t k = packVoxelKey(rng() % g.dims[0], rng() % g.dims[1], rng() % g.dims[2]);
        keys.push_back(k);
        if (i % 3 == 0) keys.push_back(k);
    }
    return keys;
}

/// The voxels whose centres lie within half a voxel of a sphere of radius r
/// centred in the grid: a one-voxel shell.
inline std::vector<uint64_t> sphereShell(const GridSpec& g, double r)
{
    std::vector<uint64_t> keys;
    const double c[3] = {g.dims[0] / 2.0, g.dims[1] / 2.0, g.dims[2] / 2.0};
    for (uint32_t x = 0; x < g.dims[0]; ++x)
        for (uint32_t y = 0; y < g.dims[1]; ++y)
            for (uint32_t z = 0; z < g.dims[2]; ++z) {
                const double d = std::sqrt((x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]) + (z - c[2]) * (z - c[2]));
                if (std::abs(d - r) <= 0.5) keys.push_back(packVoxelKey(x, y, z));
            }
    return keys;
}

} // namespace svo::test
