#pragma once
/// @file field_result.h
/// @brief svo::gl::FieldResult: what computeField (distance_field.h) gives
/// back: band voxels with their distances, closest triangles and crossings.
#include <cstdint>
#include <vector>

#include "svo/core/octree.h"

namespace svo::gl {

/// @brief What computeField gives back, for the bricks of its request in their order.
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

} // namespace svo::gl
