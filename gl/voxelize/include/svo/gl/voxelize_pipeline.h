#pragma once
/// @file voxelize_pipeline.h
/// @brief Meshes and bricks to octrees on svo's own types, backend choice
/// included: what svo::Voxelizer runs, usable without OpenVDB.
///
/// The backends (raster_voxelizer.h, octree_builder.h and the CPU reference,
/// svo/core/cpu_voxelizer.h) each do one job; this file picks one for a call
/// and gathers what it measured. Callers check the mesh and grid first
/// (validateMesh, checkGrid).
#include <cstdint>
#include <utility>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/gl/backend.h"
#include "svo/gl/device.h"
#include "svo/gl/voxelize_settings.h"
#include "svo/gl/voxelize_stats.h"

namespace svo {

namespace gl {

/// @brief The backend a call with @a settings runs on: Backend::Auto resolved
/// (a dilation mode's raster backend when one is asked for; else the CPU
/// where there is no GL (Device::withoutGl) or the GL device is a software
/// rasterizer such as llvmpipe, unless the device was named (Device::named)
/// or a GPU memory budget given: then raster on a software device and
/// compute on a hardware GPU).
/// @param create with false and no context yet, none is created (Device::software,
///        Device::withoutGl)
/// @return never Backend::Auto
/// @throw svo::InvalidInput for a dilation mode with Backend::Compute
/// @throw svo::DeviceError when @a create makes a context for a named device
///        that cannot have one
Backend resolveBackend(Device& device, const VoxelizeSettings& settings, bool create = true);

/// @brief Whether a call with @a settings runs on the CPU: Backend::Cpu, or
/// Backend::Auto (with no dilation mode) where resolveBackend would pick the
/// CPU. For the passes whose GPU path has no raster/compute choice (level
/// sets, solids). Throws nothing.
/// @param create as for resolveBackend
bool runsOnCpu(Device& device, const VoxelizeSettings& settings, bool create = true);

/// @brief Where a call runs, in its statistics: backend, device and renderer
/// names (the GPU's, or "cpu").
/// @param stats receives VoxelizeStats::backend, device and renderer
/// @throw svo::DeviceError when @a backend is a GPU one and no context can
///        be made
void describeBackend(Device& device, Backend backend, VoxelizeStats& stats);

/// @brief The voxels of a checked mesh on a checked grid, as an octree.
/// @param checkpoint polled between stages and tiles with the fraction done
/// @param stats      receives the stages, counts, backend and warnings
/// @param voxelList  when set, also the backend's voxel set (sorted, unique keys)
/// @return the octree, in canonical order, with the channels asked for
/// @throw svo::InvalidInput for a dilation mode with the compute backend
/// @throw svo::DeviceError, svo::OutOfMemory, svo::Unsupported as the
///        backends (voxelizeToOctree, voxelizeCpu): no usable GPU, out of
///        GPU or host memory, a grid beyond one octree
/// @throw svo::Interrupted from the checkpoint
Octree voxelizeMesh(Device& device, const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeSettings& settings,
                    const Checkpoint& checkpoint, VoxelizeStats& stats, std::vector<uint64_t>* voxelList = nullptr);

/// @brief Whole bricks (brick-origin key, mask) on a checked grid, built into
/// an octree on the GPU, or on the CPU with Backend::Cpu.
/// @param backend Backend::Cpu, or any other for the GPU (already resolved)
/// @param stats   receives the stages, counts and backend
/// @return the octree, in canonical order
/// @throw as buildOctreeGpu (the GPU) or buildOctreeFromBricks (the CPU)
Octree bricksToOctree(Device& device, const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> bricks,
                      Backend backend, const Checkpoint& checkpoint, VoxelizeStats& stats);

} // namespace gl
} // namespace svo
