#pragma once
/// @file lights.h
/// @brief The lights of a reference: ideal directional and point lights (the
/// ones a shadow-mapped cone tracer lights with) and a constant environment.
/// Quantities are per RGB channel, in consistent radiometric units.
#include <vector>

#include "svo/core/vec3.h"

namespace svo::reference {

/// Parallel light, as from the sun.
struct DirectionalLight {
    /// The direction the light travels (from the light into the scene); need
    /// not be unit length, must not be zero.
    Vec3d direction{0, -1, 0};
    /// E: irradiance on a surface facing the light (>= 0). A surface whose
    /// normal makes angle theta with -direction receives E cos(theta).
    Vec3d irradiance{1, 1, 1};
};

/// Isotropic point light.
struct PointLight {
    Vec3d position{0, 0, 0};
    /// I: radiant intensity (>= 0). A surface at distance r whose normal makes
    /// angle theta with the direction to the light receives I cos(theta) / r².
    Vec3d intensity{1, 1, 1};
};

struct Lighting {
    std::vector<DirectionalLight> directional;
    std::vector<PointLight> point;
    /// Radiance arriving along every ray that leaves the scene (>= 0); 0 is a
    /// black background. A constant environment is the white furnace's sky.
    Vec3d environment{0, 0, 0};
};

} // namespace svo::reference
