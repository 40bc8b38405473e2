#pragma once
/// @file grid_options.h
/// Which OpenVDB grids an octree becomes. No OpenVDB headers here.
#include <cstdint>
#include <string>

namespace svo {

struct GridOptions {
    enum class Topology { Mask, Bool };
    Topology topology = Topology::Mask; ///< MaskGrid, or BoolGrid (true on active voxels)
    std::string name = "surface";       ///< name of the topology grid
    bool fog = false;                    ///< also a fog FloatGrid "density": 1 on voxels, background 0
    bool attributes = true;              ///< the octree's channels as "normal", "triangle_id", "color"
};

namespace vdb {
/// Active tiles a reader expands into bricks by default: 2^28 bricks, 137 G
/// voxels, about 19 GB of bricks.
inline constexpr uint64_t kMaxTileBricks = uint64_t(1) << 28;
} // namespace vdb

} // namespace svo
