#pragma once
/// @file camera.h
/// @brief A camera in world units, as plain data: what svo's GL view
/// (svo::gl::ViewCamera) draws and what the path-traced reference
/// (svo::reference::Camera) traces, so that pixel (x, y) of both sees along
/// the same ray.
///
/// @details Forward f = normalize(target - eye), right r = normalize(f x up),
/// image up u = r x f. Perspective views span fovYDegrees vertically;
/// orthographic views span `height` world units vertically, and the width
/// follows from the image's aspect (width / height in pixels).
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "svo/core/error.h"
#include "svo/core/vec3.h"

namespace svo {

/// @brief A camera in world units (see the file comment for its frame).
struct Camera {
    Vec3d eye{0, 0, 1};        ///< where the camera is
    Vec3d target{0, 0, 0};     ///< the point seen at the image's centre
    Vec3d up{0, 1, 0};         ///< need not be orthogonal to the view; not along it
    bool orthographic = false; ///< orthographic (height) or perspective (fovYDegrees)
    double fovYDegrees = 40.0; ///< perspective: vertical field of view
    double height = 1.0;       ///< orthographic: world units the image spans vertically
};

// The rules of a camera's numbers, for every front door (the GL view, the
// reference, `svo view --ortho/--fov`), each naming the value as its caller
// calls it; NaN never passes.

/// @brief The rule of Camera::height of an orthographic view: a positive
/// finite number of world units.
/// @param name the value's name for the caller (a flag, a keyword, a field)
/// @throw svo::InvalidInput "<name> <value>: <the rule>" (argument() @a name)
inline void checkOrthographicHeight(double height, const std::string& name)
{
    if (!(height > 0) || !std::isfinite(height))
        throw InvalidInput(name, fmt::format("{}: an orthographic view spans a positive finite number of world units",
                                             height));
}
/// @brief The rule of Camera::fovYDegrees of a perspective view: between 0
/// and 180 degrees, both excluded.
/// @param name the value's name for the caller
/// @throw svo::InvalidInput "<name> <value>: <the rule>" (argument() @a name)
inline void checkFieldOfView(double degrees, const std::string& name)
{
    if (!(degrees > 0 && degrees < 180))
        throw InvalidInput(name, fmt::format("{}: a field of view is between 0 and 180 degrees", degrees));
}

} // namespace svo
