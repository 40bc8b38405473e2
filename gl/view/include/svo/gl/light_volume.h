#pragma once
/// @file light_volume.h
/// @brief svo::gl::LightVolume: the lighting volume as
/// OctreeView::readLightVolume reads it back, level by level, for tests and
/// tools (the volume itself is the view's, on the GPU: gl/view/src).
#include <cstdint>
#include <vector>

#include "svo/gl/light_volume_level.h"

namespace svo::gl {

/// @brief The lighting volume as read back (OctreeView::readLightVolume).
struct LightVolume {
    uint32_t texelVoxels = 1; ///< voxels per texel edge at level 0
    std::vector<LightVolumeLevel> levels; ///< level 0 first
    /// With Illumination::clearance, per texel of level 0: the coarsest
    /// level a cone may sample anywhere in that texel and read no texel of
    /// level 0 that holds a voxel (at most 7: distances stop at 255 texels).
    /// Empty otherwise.
    std::vector<uint8_t> clearLevel;
};

} // namespace svo::gl
