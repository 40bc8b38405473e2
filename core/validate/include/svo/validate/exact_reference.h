#pragma once
/// @file exact_reference.h
/// @brief The exact voxelization (conservative or thin), computed with CGAL: the yardstick
/// `svo validate` holds the GPU against. This library is the only one that
/// links CGAL, so the voxelizer never does.
///
/// Method: each triangle, in the same double-precision local coordinates the
/// GPU path starts from (GridSpec::toLocal), is tested against boxes with
/// CGAL's exact `do_intersect(Triangle_3, Bbox_3)` (Epick: exact predicates).
/// The triangle's voxel range is split in halves recursively and a half is
/// dropped as soon as its box misses the triangle, so the cost follows the
/// triangle's area in voxels, not its bounding box's volume. Degenerate
/// triangles are routed explicitly: collinear ones to `Segment_3`, coincident
/// ones to a point-in-box test. Triangles run in parallel (TBB).
///
/// Guarantee (conservative mode): `required` holds exactly the voxels whose
/// cube shrunk by epsilon meets a triangle (R in docs/design.md), `exact`
/// those whose closed cube itself does (E, the conservative set: epsilon =
/// 0), and `allowed` those whose cube grown by epsilon does (A); R ⊆ E ⊆ A.
/// Box corners i +- (1/2 +- epsilon) are rounded to double, which moves them
/// by less than 2^-30 voxels.
///
/// Thin mode: the same halving finds the candidates (a voxel's centre
/// segments lie in its cube), and each is tested on its three axis-aligned
/// centre segments. `exact` (E, the thin set) holds the voxels one of whose
/// closed segments i +- 1/2 along x, y or z meets a triangle, by CGAL's exact
/// `do_intersect(Segment_3, Triangle_3)` (`Segment_3` against a needle, `has_on`
/// for a point); `required` (R) those whose segment shortened to i +- (1/2 -
/// epsilon) does; `allowed` (A) those whose segment grown by epsilon in every
/// direction, a box of half extents 1/2 + epsilon along the axis and epsilon
/// across, meets one. R ⊆ E ⊆ A, and each is a subset of the conservative set
/// of the same name.
#include <cstdint>
#include <functional>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/voxel_mode.h"

namespace svo::validate {

/// @brief The reference sets R, E and A of a mesh on a grid (see the file comment).
struct ReferenceSets {
    std::vector<uint64_t> required; ///< R: sorted voxel keys
    std::vector<uint64_t> exact;    ///< E: sorted voxel keys, between R and A
    std::vector<uint64_t> allowed;  ///< A: sorted voxel keys, a superset of R
    uint64_t boxTests = 0;          ///< exact box (and, thin, segment) tests run
    uint64_t degenerate = 0;        ///< triangles routed to the segment or point test
};

/// @brief The exact voxelization of @a mesh on @a grid and its guarded sets.
/// @param epsilon  the guard band in voxels (grid.epsilon() for validation; 0 gives R = E = A)
/// @param mode     which voxelization the sets describe: cubes, or thin centre segments
/// @param progress called now and then from worker threads as (triangles done, total)
/// @throw nothing beyond std::bad_alloc; the mesh's indices must be valid (validateMesh)
ReferenceSets exactReference(const TriangleMesh& mesh, const GridSpec& grid, double epsilon,
                             VoxelMode mode = VoxelMode::Conservative,
                             const std::function<void(uint64_t, uint64_t)>& progress = {});

} // namespace svo::validate
