#pragma once
/// @file exact_reference.h
/// The exact conservative voxelization, computed with CGAL: the yardstick
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
/// Guarantee: `required` holds exactly the voxels whose cube shrunk by
/// epsilon meets a triangle (R in docs/design.md), `exact` those whose closed
/// cube itself does (E, the conservative set: epsilon = 0), and `allowed`
/// those whose cube grown by epsilon does (A); R ⊆ E ⊆ A. Box
/// corners i +- (1/2 +- epsilon) are rounded to double, which moves them by
/// less than 2^-30 voxels.
#include <cstdint>
#include <functional>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"

namespace svo::validate {

struct ReferenceSets {
    std::vector<uint64_t> required; ///< R: sorted voxel keys
    std::vector<uint64_t> exact;    ///< E: sorted voxel keys, between R and A
    std::vector<uint64_t> allowed;  ///< A: sorted voxel keys, a superset of R
    uint64_t boxTests = 0;          ///< exact box tests run
    uint64_t degenerate = 0;        ///< triangles routed to the segment or point test
};

/// `progress(done, total)` is called now and then from worker threads.
ReferenceSets exactReference(const TriangleMesh& mesh, const GridSpec& grid, double epsilon,
                             const std::function<void(uint64_t, uint64_t)>& progress = {});

} // namespace svo::validate
