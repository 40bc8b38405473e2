#pragma once
/// @file classify.h
/// A voxelization against the exact reference, in the terms of docs/design.md:
///   missed   = R \ G   voxels whose cube shrunk by epsilon meets a triangle, absent from G
///   missedExact = E \ G  voxels whose closed cube meets a triangle (the exact
///                        conservative set, epsilon = 0), absent from G; holds `missed`
///   boundary = (G n A) \ R   present, and within epsilon of touching: allowed
///   extra    = G \ A   present, though even the cube grown by epsilon meets no triangle
/// (Cubes for a conservative reference; for a thin one, the voxels' centre
/// segments, as exact_reference.h defines R, E and A. Classification itself
/// only compares the sets.)
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/validate/exact_reference.h"

namespace svo::validate {

/// One voxel worth a look: its OpenVDB index, the nearest triangle, and the
/// distance from the voxel's centre to that triangle, in voxels.
struct VoxelCase {
    std::array<int64_t, 3> index{};
    int64_t triangle = -1;
    double distance = 0;
};

struct Classification {
    uint64_t voxels = 0, required = 0, exact = 0, allowed = 0;
    std::vector<uint64_t> missed, missedExact, boundary, extra; ///< sorted keys
    /// The worst cases, ranked over all missed (exact: E \ G) or extra voxels, or over an even
    /// sample of 20,000 of them when there are more.
    std::vector<VoxelCase> worstMissed;            ///< nearest the surface first: the clearest misses
    std::vector<VoxelCase> worstExtra;             ///< farthest from the surface first
};

/// `gpu` must be sorted and unique. The worst cases get nearest-triangle
/// distances (CGAL AABB tree); at most `worst` of each are kept.
Classification classify(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<uint64_t>& gpu,
                        const ReferenceSets& reference, size_t worst = 10);

} // namespace svo::validate
