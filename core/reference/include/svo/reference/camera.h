#pragma once
/// @file camera.h
/// @brief The reference's pixel rays for svo::Camera (svo/core/camera.h),
/// which is also svo::gl::ViewCamera, so that pixel (x, y) of a reference
/// image and of a GL view of the same camera see along the same ray.
///
/// @details Convention (octree_view.h's): forward f = normalize(target - eye),
/// right r = normalize(f x up), image up u = r x f. Pixel (x, y), rows from
/// the top, is sampled at its centre, at normalized device coordinates
///   ndc.x = 2 (x + 1/2) / width - 1,   ndc.y = 1 - 2 (y + 1/2) / height,
/// which is what the GL view's fragment at gl_FragCoord = (x + 1/2,
/// height - 1 - y + 1/2) unprojects (GL's rows start at the bottom).
/// - perspective: from the eye along f + ndc.x tan(fov/2) aspect r + ndc.y tan(fov/2) u;
/// - orthographic: from eye + ndc.x (w/2) r + ndc.y (h/2) u along f, with
///   h = height and w = h aspect, aspect = width / height.
/// The GL view clips with near and far planes around its grid; the reference
/// has none: a perspective ray starts at the eye and an orthographic one at
/// the eye's plane, so both see the same things whenever the eye is outside
/// the scene in front of it (as gl::frameBox places it).
#include <cstdint>

#include "svo/core/camera.h"
#include "svo/core/vec3.h"

namespace svo::reference {

/// @brief The camera of svo/core/camera.h, which svo::gl::ViewCamera is too.
using Camera = svo::Camera;

/// @brief A ray in world units.
struct Ray {
    Vec3d origin;    ///< where it starts
    Vec3d direction; ///< unit length
};

/// @brief Checks that the camera can make an image of @a width x @a height pixels.
/// @throw svo::InvalidInput, in one line, for a size outside [1, 32768] per
///        side, a non-finite field, eye at target, up along the view
///        direction (or zero), a field of view outside (0, 180) degrees, an
///        orthographic height not positive
void checkCamera(const Camera& camera, int width, int height);

/// @brief The ray through the centre of pixel (x, y), rows from the top (see
/// the file comment).
/// @throw svo::InvalidInput as checkCamera, and for a pixel outside the image
Ray cameraRay(const Camera& camera, int width, int height, int x, int y);

} // namespace svo::reference
