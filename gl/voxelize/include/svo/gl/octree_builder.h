#pragma once
/// @file octree_builder.h
/// @brief The sparse voxel octree built on the GPU, from a voxel list or from bricks.
///
/// Method (Crassin & Green, "Octree-Based Sparse Voxelization", OpenGL
/// Insights 2012): top-down, one level at a time, three compute passes:
///   flag     every input entry descends to its node at the level and sets the
///            bit of the child its brick lies in (atomicOr);
///   prepare  one thread turns the node counter into the level's range and the
///            indirect dispatch size of the next pass;
///   allocate every flagged node takes a block of 8 children (or, at the brick
///            level, one brick) from an atomic counter.
/// A last pass ORs each entry's bit (or whole mask) into its brick. The node
/// and brick buffers are cleared once up front, so children start empty.
/// Dispatch sizes come from GPU counters: the CPU issues every pass at once and
/// waits once, to read the sizes back. Duplicate entries are harmless.
///
/// Buffers are sized from an estimate; when a counter passes its capacity the
/// build runs again with more room (reported as a retry), so nothing is ever
/// truncated. buildOctreeGpu knows its brick count and sizes to an upper bound.
/// Limits: 2^31 nodes and 2^28 bricks (32-bit word indices in the shaders).
#include <utility>
#include <vector>

#include "svo/core/interrupt.h"
#include "svo/core/octree.h"
#include "svo/core/voxelization.h"
#include "svo/gl/context.h"

namespace svo::gl {

/// @brief Builds the octree of whole bricks on the GPU: the path by which
/// OpenVDB grids become octrees.
/// @param context    the GL context to build in (made current for the call)
/// @param grid       the grid the brick keys are local to
/// @param bricks     (brick-origin key, mask) pairs; keys must lie in the grid,
///        and empty masks are skipped
/// @param checkpoint polled between stages with the fraction done
/// @param report     when set, receives the stages (upload, octree build,
///        readback) and the GPU buffer bytes the build used
/// @return the octree, in canonical order
/// @throw svo::InvalidInput for a brick outside the grid
/// @throw svo::Unsupported for more than 2^32 - 16 bricks, or an octree
///        beyond 32-bit node or brick indices
/// @throw svo::OutOfMemory when a GPU buffer cannot be allocated
/// @throw svo::DeviceError on a GL error
/// @throw svo::Interrupted from the checkpoint
Octree buildOctreeGpu(Context& context, const GridSpec& grid, const std::vector<std::pair<uint64_t, Brick>>& bricks,
                      const Checkpoint& checkpoint = {}, RunStats* report = nullptr);

} // namespace svo::gl
