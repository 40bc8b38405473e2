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
#include "svo/core/vec3.h"

namespace svo {

struct Camera {
    Vec3d eye{0, 0, 1};
    Vec3d target{0, 0, 0};
    Vec3d up{0, 1, 0};
    bool orthographic = false;
    double fovYDegrees = 40.0; ///< perspective: vertical field of view
    double height = 1.0;       ///< orthographic: world units the image spans vertically
};

} // namespace svo
