#pragma once
/// @file band_bricks.h
/// @brief The bricks a field pass computes, on the GPU or the CPU: those
/// within a reach of the surface voxels (a solid's band), or of the triangles
/// themselves (a level set's).
#include <cstdint>
#include <vector>

#include "svo/core/field_bricks.h"
#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_box.h"
#include "svo/core/vec3.h"

namespace svo {

/// @brief The bricks holding every voxel within @a reach voxels (Chebyshev)
/// of an occupied voxel of @a octree: each brick's occupied box grown by reach.
/// @return brick coordinates on the octree's grid, sorted (x-major) and unique
std::vector<BrickCoord> grownBricks(const Octree& octree, uint32_t reach);

/// @brief The bricks holding every voxel centre within @a grow voxels of a
/// triangle (local coordinates: centres at integers). See band_bricks.cpp.
/// @param local the mesh's positions in @a g's local frame (localPositions)
/// @return brick coordinates, sorted (x-major) and unique
/// @throw svo::Error when the boxes span more than 2^32 bricks in all, what
///        the distance pass refuses too (a band far wider than the mesh's features).
std::vector<BrickCoord> bricksNearTriangles(const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                                            const GridSpec& g, double grow);

/// @brief bricksNearTriangles() of the bricks that meet @a within only: the
/// same bricks as the whole grid's list cut to them, without visiting the
/// triangles far from them (a region, or a region's columns).
/// @param within local voxels; the bricks meeting it are searched
std::vector<BrickCoord> bricksNearTriangles(const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                                            const GridSpec& g, double grow, const VoxelBox& within);

} // namespace svo
