#pragma once
// Template bodies of svo/voxelizer.h. Each maps the mesh with prepareMesh
// (Vec3s or Vec3d points) and shares Voxelizer::voxelize.

namespace svo {

template <typename PointT>
Octree Voxelizer::meshToOctree(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                               const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform,
                               const VoxelizeOptions& options)
{
    return voxelizePrepared(prepareMesh(points, triangles, quads, xform), options);
}

template <typename PointT>
openvdb::GridPtrVec Voxelizer::meshToGrids(const std::vector<PointT>& points,
                                           const std::vector<openvdb::Vec3I>& triangles,
                                           const openvdb::math::Transform& xform, const VoxelizeOptions& options,
                                           const GridOptions& grids)
{
    return octreeToGrids(meshToOctree(points, triangles, {}, xform, options), grids, xform.copy());
}

template <typename PointT>
openvdb::BoolGrid::Ptr Voxelizer::meshToBool(const std::vector<PointT>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    GridOptions g;
    g.topology = GridOptions::Topology::Bool;
    g.attributes = false;
    return openvdb::gridPtrCast<openvdb::BoolGrid>(meshToGrids(points, triangles, xform, options, g).front());
}

template <typename PointT>
openvdb::FloatGrid::Ptr Voxelizer::meshToFog(const std::vector<PointT>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    GridOptions g;
    g.fog = true;
    g.attributes = false;
    return openvdb::gridPtrCast<openvdb::FloatGrid>(meshToGrids(points, triangles, xform, options, g).at(1));
}

} // namespace svo
