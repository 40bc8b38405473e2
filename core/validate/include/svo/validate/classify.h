#pragma once
/// @file classify.h
/// @brief A voxelization against the exact reference, in the terms of docs/design.md:
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

/// @brief One voxel worth a look: its OpenVDB index, the nearest triangle,
/// and the distance from the voxel's centre to that triangle, in voxels.
struct VoxelCase {
    std::array<int64_t, 3> index{}; ///< OpenVDB index coordinate
    int64_t triangle = -1;          ///< the nearest triangle
    double distance = 0;            ///< from the voxel's centre to it, voxels
};

/// @brief A voxelization's voxels sorted into the sets of the file comment.
struct Classification {
    uint64_t voxels = 0, required = 0, exact = 0, allowed = 0; ///< sizes of G, R, E and A
    std::vector<uint64_t> missed, missedExact, boundary, extra; ///< sorted keys
    /// The worst cases, ranked over all missed (exact: E \ G) or extra voxels, or over an even
    /// sample of 20,000 of them when there are more.
    std::vector<VoxelCase> worstMissed;            ///< nearest the surface first: the clearest misses
    std::vector<VoxelCase> worstExtra;             ///< farthest from the surface first
};

/// @brief Classifies a voxelization against its reference sets. The worst
/// cases get nearest-triangle distances (CGAL AABB tree). Throws nothing but
/// std::bad_alloc.
/// @param gpu       the voxelization under test G: sorted, unique local keys
/// @param reference R, E and A (exactReference), on the same grid
/// @param worst     the most worst cases kept of each kind
Classification classify(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<uint64_t>& gpu,
                        const ReferenceSets& reference, size_t worst = 10);

} // namespace svo::validate
