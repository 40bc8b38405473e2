#pragma once
/// @file lights.h
/// @brief Ideal lights as plain data: what svo's cone-traced view injects
/// into the octree (svo/gl/octree_view.h) and what the path-traced reference
/// (svo/reference/path_trace.h) shades with, so that both light a scene the
/// same way. Quantities are per RGB channel, in consistent radiometric units;
/// positions and directions in world units.
#include <vector>

#include "svo/core/vec3.h"

namespace svo {

/// @brief Parallel light, as from the sun.
struct DirectionalLight {
    /// The direction the light travels (from the light into the scene); need
    /// not be unit length, must not be zero.
    Vec3d direction{0, -1, 0};
    /// E: irradiance on a surface facing the light (>= 0). A surface whose
    /// normal makes angle theta with -direction receives E cos(theta).
    Vec3d irradiance{1, 1, 1};
};

/// @brief Isotropic point light.
struct PointLight {
    Vec3d position{0, 0, 0}; ///< world units
    /// I: radiant intensity (>= 0). A surface at distance r whose normal makes
    /// angle theta with the direction to the light receives I cos(theta) / r².
    Vec3d intensity{1, 1, 1};
};

/// @brief The lights of a scene.
struct Lights {
    std::vector<DirectionalLight> directional; ///< parallel lights
    std::vector<PointLight> point;             ///< point lights
    /// Radiance arriving along every ray that leaves the scene (>= 0); 0 is a
    /// black background. A constant environment is the white furnace's sky.
    Vec3d environment{0, 0, 0};
};

} // namespace svo
