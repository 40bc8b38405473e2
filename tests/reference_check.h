#pragma once
/// @file reference_check.h
/// GPU output against the double-precision reference: it must contain every
/// voxel whose cube shrunk by epsilon meets a triangle (R) and nothing outside
/// those whose cube grown by epsilon does (A). Voxels in A \ R are the band.
/// In thin mode the same with the voxels' centre segments (shortened by
/// epsilon for R; lengthened and thickened by it for A).
#include <algorithm>
#include <gtest/gtest.h>
#include <iterator>

#include "svo/core/cpu_voxelizer.h"
#include "svo/core/voxel_key.h"

namespace svo::test {

struct BandCounts {
    size_t required = 0, allowed = 0, got = 0, missed = 0, extra = 0, band = 0;
};

inline BandCounts compareToReference(const TriangleMesh& mesh, const Voxelization& gpu,
                                     VoxelMode mode = VoxelMode::Conservative)
{
    const double eps = gpu.grid.epsilon();
    const auto R = voxelizeCpu(mesh, gpu.grid, -eps, mode).keys;
    const auto A = voxelizeCpu(mesh, gpu.grid, +eps, mode).keys;
    BandCounts c;
    c.required = R.size();
    c.allowed = A.size();
    c.got = gpu.keys.size();
    std::vector<uint64_t> missed, extra;
    std::set_difference(R.begin(), R.end(), gpu.keys.begin(), gpu.keys.end(), std::back_inserter(missed));
    std::set_difference(gpu.keys.begin(), gpu.keys.end(), A.begin(), A.end(), std::back_inserter(extra));
    c.missed = missed.size();
    c.extra = extra.size();
    c.band = c.got - (c.required - c.missed) - c.extra;
    for (size_t i = 0; i < std::min<size_t>(missed.size(), 5); ++i) {
        const auto p = unpackVoxelKey(missed[i]);
        ADD_FAILURE() << mesh.source << ": missed local voxel (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    }
    for (size_t i = 0; i < std::min<size_t>(extra.size(), 5); ++i) {
        const auto p = unpackVoxelKey(extra[i]);
        ADD_FAILURE() << mesh.source << ": extra local voxel (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    }
    return c;
}

} // namespace svo::test
