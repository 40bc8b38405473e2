#pragma once
/// @file distance_field.h
/// Distances and inside/outside signs on the GPU, for a given set of bricks:
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
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/voxelization.h"
#include "svo/gl/context.h"

namespace svo::gl {

/// How the distance pass cuts its work (both give the same field). A GPU
/// runs fastest with a workgroup per brick of each triangle's box grown by
/// the band; a CPU rasterizer, whose SIMD lanes are a workgroup's threads,
/// with a thread per triangle whose grown box fits in a brick (most of a
/// dense mesh's) and a workgroup per brick for the rest.
enum class FieldWork {
    Auto,          ///< by the renderer: SmallTriangles on a CPU rasterizer, else Bricks
    Bricks,        ///< a workgroup per brick of every triangle's grown box
    SmallTriangles ///< a thread per triangle whose grown box fits a brick, a workgroup per brick for the others
};

struct FieldRequest {
    /// The bricks to compute (brick coordinates: local voxel coordinate / 8),
    /// unique. Every voxel a result needs must lie in one of them: each voxel
    /// within `band` of a triangle for distances, and the first voxel centre
    /// above every crossing for signs.
    std::vector<std::array<uint32_t, 3>> bricks;
    double band = 0;             ///< distances up to this many voxels; 0: no distances
    bool closestTriangle = false; ///< also the closest triangle of each voxel in the band
    bool crossings = true;       ///< the parity crossings
    FieldWork work = FieldWork::Auto;
    Checkpoint checkpoint;
};

/// What computeField gives back, for the bricks of its request in their order.
struct FieldResult {
    /// Per brick: the voxels nearer than the band (distances < band).
    std::vector<Brick> bandMasks;
    /// Per brick: where its voxels' values start in `distances` and `closest`.
    std::vector<uint32_t> bandOffsets;
    /// Packed: the distance in voxels of each voxel of bandMasks, brick by
    /// brick in LeafNode bit order (a brick's run starts at its offset).
    std::vector<float> distances;
    /// Packed like `distances`: the smallest index of the closest triangles.
    std::vector<int32_t> closest;
    /// Per brick: bit set where an odd number of crossings mark that voxel.
    std::vector<Brick> crossings;
    uint64_t lostCrossings = 0; ///< crossings whose voxel is in no requested brick (a caller's error)
};

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
