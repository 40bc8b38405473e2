#pragma once
/// @file field_request.h
/// @brief svo::gl::FieldRequest: the bricks and passes computeField
/// (distance_field.h) runs.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/interrupt.h"
#include "svo/core/octree.h"
#include "svo/gl/field_work.h"

namespace svo::gl {

/// @brief What computeField computes: for which bricks, and which of
/// distances, closest triangles and parity crossings.
struct FieldRequest {
    /// The bricks to compute (brick coordinates: local voxel coordinate / 8),
    /// unique. Every voxel a result needs must lie in one of them: each voxel
    /// within `band` of a triangle for distances, and the first voxel centre
    /// above every crossing for signs.
    std::vector<std::array<uint32_t, 3>> bricks;
    double band = 0;             ///< distances up to this many voxels; 0: no distances
    bool closestTriangle = false; ///< also the closest triangle of each voxel in the band
    bool crossings = true;       ///< the parity crossings
    FieldWork work = FieldWork::Auto; ///< how the distance pass cuts its work
    Checkpoint checkpoint;            ///< polled while the passes run; throws svo::Interrupted to stop
    /// Leave the band on the device as NanoVDB leaves (FieldResult::leaves,
    /// band_leaves.comp) instead of packing it and reading it back; only the
    /// leaf count comes back. With crossings (a field signed by parity), the
    /// crossings are read back and scanned on the host (scanParity), and the
    /// voxels it finds inside are uploaded and negated in the leaves.
    bool deviceLeaves = false;
    /// With deviceLeaves and without crossings (winding signs): per brick of
    /// `bricks`, the voxels inside, uploaded and negated in the leaves; a
    /// brick with an inside voxel and none nearer than the band takes a leaf
    /// too (after the others: FieldLeaves::activeCount). Not owned.
    const std::vector<Brick>* insideVoxels = nullptr;
    /// Only which voxels are nearer than leafBands[0] (or than `band`,
    /// without deviceLeaves) is asked, a band's topology: a triangle is not
    /// measured at a voxel already nearer, so the kept distances are not
    /// the least, but the voxels nearer than the band are exactly the
    /// field's. With deviceLeaves the leaves take no values. Unsigned
    /// fields only (no crossings, no closest triangles).
    bool bandOnly = false;
    /// Leaves the caller adds after the band's (FieldLeaves' buffers hold them).
    uint32_t extraLeaves = 0;
    double leafScale = 1.0;      ///< world units per voxel: a leaf's value is float(double(distance) * leafScale)
    float leafBackground = 0.0f; ///< the value of a leaf's voxels beyond the band (negated inside)
    /// A leaf's voxel is active when its distance is less than leafBands[0]
    /// outside and leafBands[1] inside (in voxels, as levelSetNanoGrids
    /// compares them).
    std::array<float, 2> leafBands{0.0f, 0.0f};
};

} // namespace svo::gl
