#pragma once
/// @file parity_crossings.h
/// @brief Where a mesh crosses the voxel columns along z, on the CPU: the
/// crossings the GPU's parity pass marks (svo/gl/distance_field.h), bit for
/// bit, for scanParity (svo/core/parity_scan.h) to turn into signs.
///
/// Every voxel column (i, j) inside a triangle's projection on z marks the
/// first voxel centre above the crossing (a centre at its exact height counts
/// as above). Ties follow simulation of simplicity: each centre is perturbed
/// to (i + e^2, j + e^3, k + e), so a column over an edge shared by two
/// triangles crosses exactly one of them and no centre lies on the surface.
/// Each edge function is evaluated with its end points in a fixed order, so
/// the two triangles of an edge decide alike.
#include <cstdint>
#include <vector>

#include "svo/core/field_bricks.h"
#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/vec3.h"

namespace svo {

/// Per brick, the voxels marked an odd number of times.
struct ParityCrossings {
    std::vector<Brick> crossings; ///< per requested brick, in list order
    uint64_t lost = 0;            ///< crossings whose voxel is in no listed brick (a caller's error)
};

/// @brief The parity crossings of a mesh on the CPU, with TBB.
/// @param local  the mesh's positions in @a grid's local frame (localPositions)
/// @param bricks unique brick coordinates; every crossing's voxel should lie in
///        one (the band of the surface voxels grown by 1 holds them all)
/// @return per brick the odd-crossing voxels, and the crossings that fell outside
/// @throw std::bad_alloc.
ParityCrossings parityCrossings(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                                const std::vector<BrickCoord>& bricks);

} // namespace svo
