#pragma once
/// @file mesh_to_volume.h
/// @brief One-off calls: a mesh to a grid, like openvdb::tools::meshToVolume.
///
/// Each call creates a Voxelizer (GL context, programs, buffers) and drops it
/// afterwards, so it pays EGL start-up and shader compilation every time;
/// code that voxelizes more than once should keep a svo::Voxelizer. The
/// method, guarantees, parameters and exceptions are Voxelizer's
/// (svo/voxelizer.h). The GPU is chosen as DeviceOptions{} chooses it
/// ($SVO_EGL_DEVICE, else hardware first).
#include "svo/voxelizer.h"

namespace svo {

/// @brief The voxels whose closed index-space cube meets a triangle, as a
/// MaskGrid with transform @a xform.
/// @throw as Voxelizer::meshToMask
template <typename PointT>
openvdb::MaskGrid::Ptr meshToMask(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                  const openvdb::math::Transform& xform, const VoxelizeOptions& options = {})
{
    return Voxelizer().meshToMask(points, triangles, xform, options);
}

/// @brief Triangles and quads (a quad whose fourth index is
/// openvdb::util::INVALID_IDX is a triangle).
/// @throw as Voxelizer::meshToMask
template <typename PointT>
openvdb::MaskGrid::Ptr meshToMask(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                  const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform,
                                  const VoxelizeOptions& options = {})
{
    return Voxelizer().meshToMask(points, triangles, quads, xform, options);
}

/// @brief The same voxels as a BoolGrid (true on active voxels).
/// @throw as Voxelizer::meshToMask
template <typename PointT>
openvdb::BoolGrid::Ptr meshToBool(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                  const openvdb::math::Transform& xform, const VoxelizeOptions& options = {})
{
    return Voxelizer().meshToBool(points, triangles, xform, options);
}

/// @brief The same voxels as a fog FloatGrid (1 on voxels, background 0).
/// @throw as Voxelizer::meshToMask
template <typename PointT>
openvdb::FloatGrid::Ptr meshToFog(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                  const openvdb::math::Transform& xform, const VoxelizeOptions& options = {})
{
    return Voxelizer().meshToFog(points, triangles, xform, options);
}

/// @brief The topology grid plus fog and attribute grids, as @a grids asks.
/// @throw as Voxelizer::meshToMask
template <typename PointT>
openvdb::GridPtrVec meshToGrids(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                const openvdb::math::Transform& xform, const VoxelizeOptions& options = {},
                                const GridOptions& grids = {})
{
    return Voxelizer().meshToGrids(points, triangles, xform, options, grids);
}

/// @brief The voxels as an octree (see Voxelizer::meshToOctree for its lattice).
/// @throw as Voxelizer::meshToMask
template <typename PointT>
Octree meshToOctree(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                    const openvdb::math::Transform& xform, const VoxelizeOptions& options = {})
{
    return Voxelizer().meshToOctree(points, triangles, {}, xform, options);
}

} // namespace svo
