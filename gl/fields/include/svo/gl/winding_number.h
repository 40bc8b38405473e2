#pragma once
/// @file winding_number.h
/// @brief Generalized winding numbers on the GPU (svo/core/winding_tree.h has the
/// method): the sign of level sets and solids for meshes that are not closed.
///
/// Two evaluations, both in the grid's local voxel frame:
///   per voxel  for every voxel centre of a list of bricks, whether its
///              winding number is at least 1/2 (inside);
///   per brick  the winding number at the centre of every brick of the
///              grid's box (brick coordinates up to ceil(dims / 8)), for the
///              caller to classify whole bricks far from the surface.
///
/// Accuracy. A tree node farther than `beta` times its radius adds its far
/// field, expanded to second order, in float instead of its triangles;
/// nearer triangles add their exact solid angle. The error falls as
/// (1 / beta)^3 or faster relative to the node's own contribution;
/// beta = infinity evaluates every triangle.
#include "svo/core/grid.h"
#include "svo/core/local_positions.h"
#include "svo/core/mesh.h"
#include "svo/core/voxelization.h"
#include "svo/core/winding_tree.h"
#include "svo/gl/context.h"
#include "svo/gl/winding_request.h"
#include "svo/gl/winding_result.h"

namespace svo::gl {

/// @brief Runs on @a context for a mesh on @a grid (both checked by the
/// caller).
/// @param tree    the winding tree built from the mesh in the grid's local
///        frame (localPositions): it holds the triangles (their pieces) the
///        walks read
/// @param request the bricks to classify voxel by voxel, whether to evaluate
///        every brick centre too, and the accuracy
/// @param report  when set, receives the stages (upload, each evaluation) and
///        the GPU buffer bytes they used
/// @return the inside voxels of each requested brick, and the brick centres'
///        winding numbers when asked
/// @throw svo::InvalidInput for beta not positive; svo::Unsupported for a box
///        of more than 2^31 bricks or a tree deeper than the shader's stack;
///        svo::DeviceError or svo::OutOfMemory for a GPU buffer that cannot be
///        allocated or a walk the driver cut short; svo::Interrupted from the
///        checkpoint.
WindingResult computeWinding(Context& context, const GridSpec& grid, const WindingTree& tree,
                             const WindingRequest& request, RunStats* report = nullptr);

/// The mesh's positions in the grid's local voxel frame (double): what the
/// tree is built from (svo/core/local_positions.h).
using svo::localPositions;

} // namespace svo::gl
