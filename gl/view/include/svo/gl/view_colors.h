#pragma once
/// @file view_colors.h
/// @brief The colours of the octree view's layers (ViewColors).

namespace svo::gl {

/// @brief The colours of the layers, 0..1 (tests classify pixels by them).
struct ViewColors {
    static constexpr float voxel[3] = {0.15f, 0.85f, 0.20f};
    static constexpr float outline[3] = {0.95f, 0.10f, 0.10f};
    static constexpr float brick[3] = {0.95f, 0.80f, 0.10f};
    static constexpr float mesh[3] = {0.70f, 0.70f, 0.72f};
    static constexpr float background[3] = {0.08f, 0.08f, 0.10f};
};

} // namespace svo::gl
