#pragma once
/// @file view_camera.h
/// @brief The octree view's camera (svo/core/camera.h's) and the framings
/// `svo view` starts from: the grid's world box, a camera that sees a box, the
/// named views.
#include <array>
#include <string>

#include "svo/core/camera.h"
#include "svo/core/grid.h"
#include "svo/core/vec3.h"

namespace svo::gl {

/// @brief A camera in world units (svo/core/camera.h), shared with the path-traced
/// reference so that both see each pixel along the same ray.
using ViewCamera = svo::Camera;

/// @brief The world box of the grid's voxels: local [-1/2, dims - 1/2] per axis.
/// @return the box's lowest and highest corners, world units
std::array<Vec3d, 2> gridWorldBox(const GridSpec& grid);

/// @brief A camera that sees the whole box. Orthographic views fit the box's
/// bounding sphere in the image height and width.
/// @param direction where the camera looks; need not be unit
/// @param aspect    the picture's width / height
/// @throw svo::InvalidInput for a zero @a direction
ViewCamera frameBox(const std::array<Vec3d, 2>& box, const Vec3d& direction, bool orthographic, double aspect);

/// @brief The named views of `svo view --view`, framing the box with frameBox.
/// @param name "front" (perspective, looking along (-0.35, -0.3, -1), the
///        Cornell box's open side) or an axis, "+x", "-x", "+y", "-y", "+z",
///        "-z" (orthographic, looking from that side)
/// @param aspect the picture's width / height
/// @throw svo::InvalidInput for another name ("view 'x': ...", its
///        argument() "svo::gl::namedView")
ViewCamera namedView(const std::array<Vec3d, 2>& box, const std::string& name, double aspect);

/// @brief The classic front view of a room open at +z, as the Cornell box is
/// photographed: perspective, from the middle of the open side, looking
/// along -z at the back wall, up +y, as far back as the open side fills the
/// picture (its height, or its width in a picture narrower than the room),
/// so that the floor, ceiling, back and both side walls are in sight.
/// @param box         the room's world box (its +z side open)
/// @param aspect      the picture's width / height
/// @param fovYDegrees the camera's vertical field of view, in (0, 180)
/// @throw svo::InvalidInput for a field of view outside (0, 180) or an aspect
///        that is not positive
ViewCamera roomView(const std::array<Vec3d, 2>& box, double aspect, double fovYDegrees = 40.0);

} // namespace svo::gl
