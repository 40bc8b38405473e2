#pragma once
/// @file band_bricks.h (internal)
/// The bricks a field pass computes: those within a reach of the surface
/// voxels (a solid's band), or of the triangles themselves (a level set's).
#include <cstdint>
#include <vector>

#include "svo/core/field_bricks.h"
#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/vec3.h"

namespace svo::gl {

/// The bricks holding every voxel within `reach` voxels (Chebyshev) of an
/// occupied voxel of the octree, sorted and unique: each brick's occupied box
/// grown by reach.
std::vector<BrickCoord> grownBricks(const Octree& octree, uint32_t reach);

/// The bricks holding every voxel centre within `grow` voxels of a triangle
/// (local coordinates: centres at integers), sorted and unique. See band_bricks.cpp.
/// @throw svo::Error when the boxes span more than 2^32 bricks in all, what
///        the distance pass refuses too (a band far wider than the mesh's features).
std::vector<BrickCoord> bricksNearTriangles(const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                                            const GridSpec& g, double grow);

} // namespace svo::gl
