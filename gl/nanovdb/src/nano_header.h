#pragma once
/// @file nano_header.h (internal)
/// @brief The bytes of a NanoVDB grid's GridData, TreeData and RootData
/// (without its tiles), which the host writes once the GPU passes have
/// counted the nodes and merged the upper nodes' statistics.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "svo/gl/nano_grid_builder.h"

namespace svo::gl {

/// @brief The tree facts the header holds.
struct NanoTreeFacts {
    std::array<uint32_t, 3> nodes{0, 0, 0}; ///< leaves, lower, upper nodes
    std::array<uint64_t, 4> at{0, 0, 0, 0}; ///< byte offsets of the first leaf, lower, upper node and the root
    uint64_t gridBytes = 0;
    uint64_t voxels = 0;                    ///< active voxels, active tiles' included
    uint32_t activeTiles = 0;               ///< active 8³ tiles
    bool any = false;                       ///< some voxel is active
    std::array<int32_t, 6> bbox{};          ///< index box of active voxels (min, max), when any
    std::array<uint32_t, 3> minimum{}, maximum{}; ///< value bits, when any (Float, Int32: the first word; Vec3f)
};

/// @brief The header bytes: kNanoGridBytes + kNanoTreeBytes + the root's
/// (kNanoRootBytes; Vec3f kNanoRootBytesVec3f).
std::vector<uint8_t> nanoHeader(NanoKind kind, const NanoGridHeader& header, const NanoTreeFacts& tree);

/// @brief zlib's CRC-32 (crc32_z) of @a n bytes, continuing from @a crc
/// (0 to start), the CRC NanoVDB's checksum uses.
uint32_t crc32Of(const void* bytes, size_t n, uint32_t crc = 0);

} // namespace svo::gl
