#pragma once
/// @file field_result.h
/// @brief svo::gl::FieldResult: what computeField (distance_field.h) gives
/// back: band voxels with their distances, closest triangles and crossings.
#include <cstdint>
#include <vector>

#include "svo/core/octree.h"

namespace svo::gl {

class Buffer;

/// @brief A field's band as NanoVDB leaves on the device
/// (FieldRequest::deviceLeaves), in no fixed order, as svo::gl::NanoLeaves
/// takes them: 3 ints (the origin in index space), 16 uints (the voxels
/// nearer than the band, OpenVDB's bit order) and 512 value words per leaf.
/// The buffers are the context's scratch buffers: valid, with the context
/// current, until the next computeField on it.
struct FieldLeaves {
    uint32_t count = 0;              ///< the bricks that took a leaf (FieldRequest::insideVoxels: those with inside voxels too)
    uint32_t activeCount = 0;        ///< the first leaves: the bricks with a voxel nearer than the band
    const Buffer* origins = nullptr; ///< 3 ints per leaf
    const Buffer* masks = nullptr;   ///< 16 uints per leaf
    const Buffer* values = nullptr;  ///< 512 floats per leaf: the distance in world units, else the background; negated inside
    const Buffer* closest = nullptr; ///< 512 ints per leaf: the closest triangle, else -1; null unless computed
};

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
    FieldLeaves leaves;         ///< with FieldRequest::deviceLeaves (then bandMasks, bandOffsets, distances and closest stay empty)
    /// Device leaves signed by parity: the scan's columns with an odd count
    /// of crossings (ParityScan::openColumns).
    uint64_t openColumns = 0;
};

} // namespace svo::gl
