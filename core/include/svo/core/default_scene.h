#pragma once
/// @file default_scene.h
/// @brief Generated scenes: the built-in Cornell box (so the main job runs with no
/// input file), the seed's PBR-demo-like grid of spheres, the two rooms of
/// the thin-wall leak test, and icospheres.
#include "svo/core/mesh.h"

namespace svo {

/// @brief The built-in Cornell box. Throws nothing but std::bad_alloc.
///
/// A 2 x 2 x 2 room open at the front (floor, ceiling, back, left and right
/// walls, each tessellated 14 x 14) with a short and a tall block (every face
/// tessellated 7 x 7): 5*392 + 12*98 = 3,136 triangles, the seed's count.
/// Vertex colours are the classic room's reflectances: the left wall red
/// (0.63, 0.065, 0.05), the right wall green (0.14, 0.45, 0.091), the rest
/// white (0.73, 0.71, 0.68); each wall has vertices of its own.
TriangleMesh cornellBox();

/// @brief The grid of spheres.
///
/// A 6 x 6 grid of UV spheres (40 slices, 19 stacks) on a floor-less stage,
/// like the seed's PBR demo: 36 * 1,520 = 54,720 triangles.
TriangleMesh sphereGrid();

/// @brief The thin-wall leak scene.
///
/// A closed 2 x 1 x 2 box ([-1, 1] x [0, 1] x
/// [-1, 1]) split into two rooms by one wall of zero thickness at x = 0,
/// every face tessellated 8 x 8: 7 * 128 = 896 triangles. A light in one
/// room leaves the other one dark after any number of bounces.
TriangleMesh twoRooms();

/// @brief A closed icosphere: an icosahedron split @a levels times, vertices
/// on the sphere, shared between faces.
/// @return 20 * 4^levels triangles (level 8 gives 1,310,720)
TriangleMesh icosphere(Vec3d centre, double radius, int levels);

} // namespace svo
