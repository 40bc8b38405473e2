#pragma once
/// @file light_volume_readback.h
/// @brief The lighting volume as OctreeView::readLightVolume reads it back, level
/// by level, for tests and tools (the volume itself is the view's, on the GPU).
#include <array>
#include <cstdint>
#include <vector>

namespace svo::gl {

/// @brief One level of the lighting volume as read back
/// (OctreeView::readLightVolume), texels x fastest.
struct LightVolumeLevel {
    int size[3] = {0, 0, 0}; ///< texels along x, y, z
    std::vector<float> opacity;  ///< 4 per texel: seen along x, y, z, and coverage
    std::vector<float> radiance; ///< 4 per texel: radiance x coverage (rgb), coverage
    /// With Illumination::directional, from level 1 up, 4 per texel each:
    /// the premultiplied radiance (rgb) and opacity (a) a ray travelling
    /// along +x, -x, +y, -y, +z, -z sees. Empty otherwise.
    std::array<std::vector<float>, 6> along;
    /// With Illumination::directional, level 0 only, 4 per texel: its lit
    /// side (the normal turned to its lights, averaged by light; 0 unlit)
    /// times its light, the mean of its premultiplied radiance's rgb, so
    /// that a trilinear sample divided by the sampled light is the lit side
    /// of the light it holds.
    std::vector<float> litSide;
};
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
