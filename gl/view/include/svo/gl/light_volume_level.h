#pragma once
/// @file light_volume_level.h
/// @brief svo::gl::LightVolumeLevel: one level of the lighting volume as
/// OctreeView::readLightVolume reads it back (light_volume.h).
#include <array>
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

} // namespace svo::gl
