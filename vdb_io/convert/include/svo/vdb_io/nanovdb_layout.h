#pragma once
/// @file nanovdb_layout.h
/// @brief NanoVDB grids laid out directly from sparse leaves, without an
/// OpenVDB tree: the root, the upper (32³) and lower (16³) internal nodes and
/// the 8³ leaves, breadth-first as NanoVDB lays them out, with their masks,
/// child offsets, bounding boxes and minimum/maximum statistics.
///
/// Layout (NanoVDB 32.4, Debian's libnanovdb-dev): GridData | TreeData |
/// RootData + its tiles | every upper node | every lower node | every leaf.
/// Root tiles are sorted by origin (x, then y, then z), internal nodes by
/// parent and then by their index in the parent, leaves alike: the order
/// OpenVDB's tree iterators give, so nanovdb::openToNanoVDB lays out the
/// same tree in the same order. The buffer starts zeroed, so padding is 0.
///
/// Statistics follow nanovdb::StatsMode::MinMax: each node's bounding box of
/// active values and the minimum and maximum of its active values (vectors by
/// squared length, the first of equals kept, as nanovdb::Extrema does);
/// averages and standard deviations are left out (their flags off), because
/// a sum in a fixed order is what the GPU builder must reproduce bit for bit.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/HostBuffer.h>

#include "svo/core/octree.h"

namespace svo::vdb {

/// @brief What a grid holds besides its voxels.
struct NanoGridInfo {
    std::string name;                                   ///< at most 255 bytes
    nanovdb::GridClass gridClass = nanovdb::GridClass::Unknown;
    double voxelSize = 1.0;                             ///< index -> world scale
    std::array<double, 3> translation{0.0, 0.0, 0.0};   ///< world position of index (0, 0, 0)
    bool checksum = true;                               ///< a full CRC32 (nanovdb::ChecksumMode::Full)
};

/// @brief Sparse voxels of one value type: leaves and tiles in any order.
/// @tparam ValueT float, int32_t, nanovdb::Vec3f or bool (bool: values are
///         unused for mask grids, and true on active voxels for bool grids)
template <typename ValueT>
struct SparseVoxels {
    /// A constant region: level 1 is an 8³ tile of a lower node, level 2 a
    /// 128³ tile of an upper node. No leaf or smaller tile may lie inside.
    struct Tile {
        std::array<int32_t, 3> origin; ///< a multiple of 8 (level 1) or 128 (level 2)
        uint32_t level = 1;
        ValueT value{};
        bool active = false;
    };
    ValueT background{};
    std::vector<std::array<int32_t, 3>> origins; ///< per leaf: its origin, a multiple of 8; unique
    std::vector<Brick> masks;                    ///< per leaf: active voxels, OpenVDB's bit order
    std::vector<ValueT> values;                  ///< 512 per leaf, or empty: background everywhere (bool: the active voxels)
    /// With no values: every active voxel's value (a fog's 1.0), the
    /// background elsewhere; not read for bool and mask grids.
    std::optional<ValueT> activeValue;
    std::vector<Tile> tiles;
};

/// @brief NanoVDB's build type for a value type and a topology choice.
enum class NanoTopology { Values, Mask };

/// @brief Builds a NanoVDB grid from sparse voxels.
/// @tparam BuildT float, int32_t, nanovdb::Vec3f, bool or nanovdb::ValueMask
/// @param voxels the leaves and tiles (ValueMask: SparseVoxels<bool>, values ignored)
/// @param info   name, class, transform and checksum
/// @return a host buffer holding one grid
/// @throw svo::InvalidInput for a leaf origin that is not a multiple of 8, a
///        repeated leaf, a tile at a bad level or origin, or a name of 256 bytes or more
template <typename BuildT>
nanovdb::GridHandle<nanovdb::HostBuffer> buildNanoGrid(const SparseVoxels<typename nanovdb::BuildToValueMap<BuildT>::Type>& voxels,
                                                       const NanoGridInfo& info);

} // namespace svo::vdb
