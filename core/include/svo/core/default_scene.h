#pragma once
/// @file default_scene.h
/// The built-in scene: a Cornell box like the seed report's, so the main job
/// runs with no input file.
#include "svo/core/mesh.h"

namespace svo {

/// A 2 x 2 x 2 room open at the front (floor, ceiling, back, left and right
/// walls, each tessellated 14 x 14) with a short and a tall block (every face
/// tessellated 7 x 7): 5*392 + 12*98 = 3,136 triangles, the seed's count.
TriangleMesh cornellBox();

} // namespace svo
