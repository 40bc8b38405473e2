#include "svo/core/voxel_mode.h"

namespace svo {

int separatingConnectivity(VoxelMode mode) { return mode == VoxelMode::Thin ? 6 : 26; }

} // namespace svo
