#include "svo/core/voxel_mode.h"

#include "svo/core/error.h"

namespace svo {

const char* voxelModeName(VoxelMode mode) { return mode == VoxelMode::Thin ? "thin" : "conservative"; }

VoxelMode parseVoxelMode(const std::string& name)
{
    if (name == "conservative") return VoxelMode::Conservative;
    if (name == "thin") return VoxelMode::Thin;
    throw InvalidInput("unknown voxelization mode '" + name + "'; the modes are conservative and thin");
}

int separatingConnectivity(VoxelMode mode) { return mode == VoxelMode::Thin ? 6 : 26; }

} // namespace svo
