#pragma once
/// @file distance_field.h
/// @brief Distances and inside/outside signs on the GPU, for a given set of bricks:
/// the GPU half of level sets and solids (svo::Voxelizer::levelSet, ::solid).
///
/// Method. The caller names the bricks that matter (the narrow band around the
/// surface); a hash table on the GPU finds them by brick coordinates, so memory
/// follows the surface, not the grid's volume. Work is triangle-parallel: each
/// triangle's box of bricks (grown by the band) is cut into one work item per
/// brick, taken by a workgroup of 64 threads, so a large triangle does not
/// serialize a thread (field_common.glsl).
///   distances  every voxel centre of an item's brick gets its exact distance
///              to the triangle in double precision; the least per voxel is
///              kept by atomicMin on float bits (band_distance.comp);
///   closest    optionally, the smallest triangle index at that distance;
///   packing    the voxels nearer than the band, and only those, are packed
///              per brick behind a mask (band_compact.comp), so the readback
///              moves what the level set keeps, not 512 floats per brick;
///   crossings  every voxel column (i, j) inside a triangle's projection on z
///              (with simulation-of-simplicity ties) marks the first voxel
///              centre above the crossing; an odd count of marks below a
///              centre means inside a closed mesh (parity_flips.comp). The
///              sums up each column are the host's (svo/core/parity_scan.h).
///
/// Precision. Distances are computed in double from the local double vertex
/// coordinates and rounded once to float (voxel units): the error is at most
/// half a float ulp of the distance plus a few double ulps, under 1e-6 voxel
/// in a band of a few voxels.
#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/voxelization.h"
#include "svo/gl/context.h"
#include "svo/gl/field_request.h"
#include "svo/gl/field_result.h"

namespace svo::gl {

/// @brief Runs the passes on @a context for a mesh on @a grid (both checked
/// by the caller).
/// @param request the bricks, the band, and which of distances, closest
///        triangles and crossings to compute
/// @param report  when set, receives the stages (upload, the passes run,
///        packing, readback) and the GPU buffer bytes they used
/// @return per requested brick, the band's voxels with their distances (and
///        closest triangles), and the crossings
/// @throw svo::Unsupported when the work exceeds 2^32 items (a band or grid
///        too large for one pass); svo::DeviceError or svo::OutOfMemory when
///        a GPU buffer cannot be allocated; svo::Interrupted from the checkpoint.
FieldResult computeField(Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                         const FieldRequest& request, RunStats* report = nullptr);

} // namespace svo::gl
