#pragma once
/// @file grid_options.h
/// @brief Which OpenVDB or NanoVDB grids an octree becomes, and how a .nvdb
/// file compresses them. No OpenVDB headers here.
#include <cstdint>
#include <string>

#include "svo/core/enum_names.h"
#include "svo/core/option_info.h"

namespace svo {

struct GridSpec;

namespace vdb {
/// @brief How a .nvdb file's grids are compressed: NanoVDB's own codecs.
enum class NanoCodec { None, Zip, Blosc };

/// @brief The names of NanoCodec, as --codec takes them.
inline constexpr EnumName<NanoCodec> kNanoCodecNames[] = {
    {NanoCodec::None, "none"}, {NanoCodec::Zip, "zip"}, {NanoCodec::Blosc, "blosc"}};
constexpr const auto& enumNames(NanoCodec) { return kNanoCodecNames; }
} // namespace vdb

/// @brief Which grids an octree becomes, the topology grid's name, and a
/// .nvdb file's codec.
struct GridOptions {
    enum class Topology { Mask, Bool }; ///< the topology grid's type
    Topology topology = Topology::Mask; ///< MaskGrid, or BoolGrid (true on active voxels)
    std::string name = "surface";       ///< name of the topology grid
    bool fog = false;                    ///< also a fog FloatGrid "density": 1 on voxels, background 0
    bool attributes = true;              ///< the octree's channels as "normal", "triangle_id", "color"
    vdb::NanoCodec codec = vdb::NanoCodec::None; ///< a .nvdb output's compression (.vdb files are not affected)
};

/// @brief The names of GridOptions::Topology, as --topology takes them.
inline constexpr EnumName<GridOptions::Topology> kTopologyNames[] = {{GridOptions::Topology::Bool, "bool"},
                                                                     {GridOptions::Topology::Mask, "mask"}};
constexpr const auto& enumNames(GridOptions::Topology) { return kTopologyNames; }

/// @brief The options of GridOptions a front end sets, declared once
/// (svo/core/option_info.h); the grid's name and channels are the caller's.
template <typename Visit>
void forEachOption(GridOptions& g, Visit&& visit)
{
    visit(OptionInfo{"GridOptions::topology", "topology",
                     "Grid type of the topology: bool (BoolGrid, which python3-openvdb reads) or mask (MaskGrid)"},
          g.topology);
    visit(OptionInfo{"GridOptions::fog", "fog", "Also write a fog-volume FloatGrid 'density' (.vdb and .nvdb output)"},
          g.fog);
    visit(OptionInfo{"GridOptions::codec", "codec",
                     "Compression of a .nvdb output's grids, NanoVDB's codecs (NanoVDB's readers decode each)"},
          g.codec);
}

namespace vdb {
/// @brief Active tiles a reader expands into bricks by default: 2^28 bricks,
/// 137 G voxels, about 19 GB of bricks.
inline constexpr uint64_t kMaxTileBricks = uint64_t(1) << 28;

/// @brief The smallest voxel size an OpenVDB linear transform takes: OpenVDB 10's
/// ScaleMap refuses scales whose product is below 3e-15 (math/Maps.h), so
/// the voxel size must be at least the cube root, about 1.4422e-5.
inline constexpr double kMinVoxelSize = 1.4422495703074085e-05;

/// @brief Checks a voxel size against kMinVoxelSize, before any work when the
/// output is an OpenVDB grid.
/// @param what prefixes the message (whose voxel size it is)
/// @throw svo::InvalidInput when @a voxelSize is below kMinVoxelSize
void checkVdbVoxelSize(double voxelSize, const std::string& what);

/// @brief checkVdbVoxelSize, and that OpenVDB can hold the grid's whole
/// transform: a grid far from the origin for its voxel size (a mesh 1e15
/// away) gives a matrix OpenVDB refuses to copy ("Non-zero scale values
/// required"), which every write does. Call before any work.
/// @param what prefixes the message
/// @throw svo::InvalidInput naming @a what when OpenVDB cannot hold the transform
void checkVdbGrid(const GridSpec& grid, const std::string& what);
} // namespace vdb

} // namespace svo
