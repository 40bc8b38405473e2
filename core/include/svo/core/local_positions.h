#pragma once
/// @file local_positions.h
/// @brief A mesh's vertices in a grid's local voxel frame, in double: what
/// the distance, crossing and winding passes (GPU and CPU) compute from.
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/vec3.h"

namespace svo {

/// @brief The mesh's vertices in @a grid's local coordinates (voxel centres
/// at integers), GridSpec::toLocal of each, in parallel.
/// @return one point per vertex of @a mesh, in its order
std::vector<Vec3d> localPositions(const TriangleMesh& mesh, const GridSpec& grid);

} // namespace svo
