#pragma once
/// @file band_distances.h
/// @brief Exact distances from voxel centres to a mesh within a band, on the
/// CPU: the same field as the GPU's distance pass (svo/gl/distance_field.h),
/// voxel for voxel.
///
/// Every voxel centre p of the given bricks gets the least, over the
/// triangles, of float(sqrt(d2)), d2 the squared distance from p to the
/// closed triangle computed in double from the local double positions (the
/// distance to the plane where p projects inside the triangle, else to the
/// nearest edge, needles and points being their edges), by the operations
/// of band_distance.glsl in the same order. A voxel is in the band when that
/// float is less than float(band). Its closest triangle is the smallest
/// index among the triangles at exactly that float distance, so the result
/// depends on nothing but the mesh.
#include <cstdint>
#include <vector>

#include "svo/core/field_bricks.h"
#include "svo/core/grid.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/core/vec3.h"

namespace svo {

/// The band of a distance field over a list of bricks, packed as DistanceBricks holds it.
struct BandDistances {
    std::vector<Brick> near;       ///< per brick: the voxels nearer than the band
    std::vector<uint32_t> offsets; ///< per brick: where its values start (bricks in list order)
    std::vector<float> distances;  ///< packed, brick by brick in bit order
    std::vector<int32_t> closest;  ///< packed alike; empty unless asked
};

/// @brief The band's distances (and closest triangles) on the CPU, with TBB.
/// @param local      the mesh's positions in @a grid's local frame (localPositions)
/// @param bricks     unique brick coordinates (local voxel coordinate / 8) on
///        @a grid: voxels in no listed brick are not computed (bricksNearTriangles
///        lists every brick a band voxel can lie in)
/// @param band       the band's half width in voxels (> 0)
/// @param closestTriangle also the closest triangle of every band voxel
/// @param bandOnly   only which voxels are nearer than the band is asked (a
///        band's topology): a centre found nearer takes no more triangles,
///        so its kept distance is not the least (no closest triangles then)
/// @param checkpoint polled on the calling thread between batches of bricks
/// @return per brick its band voxels, and their values packed in list order
/// @throw svo::Interrupted from the checkpoint; std::bad_alloc.
BandDistances bandDistances(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                            const std::vector<BrickCoord>& bricks, double band, bool closestTriangle,
                            const Checkpoint& checkpoint, bool bandOnly = false);

} // namespace svo
