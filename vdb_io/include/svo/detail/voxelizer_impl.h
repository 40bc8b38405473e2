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

namespace detail {
/// The uniform scale of a transform (world units per index unit).
/// @throw svo::Unsupported for a transform without uniform scale.
double uniformScale(const openvdb::math::Transform& xform);
} // namespace detail

template <typename PointT>
openvdb::FloatGrid::Ptr Voxelizer::meshToLevelSet(const std::vector<PointT>& points,
                                                  const std::vector<openvdb::Vec3I>& triangles,
                                                  const openvdb::math::Transform& xform, float exteriorBand,
                                                  float interiorBand, const VoxelizeOptions& options)
{
    const double scale = detail::uniformScale(xform);
    const IndexSpaceMesh p = prepareMesh(points, triangles, {}, xform);
    LevelSetOptions ls;
    ls.exteriorBand = exteriorBand;
    ls.interiorBand = interiorBand;
    return openvdb::gridPtrCast<openvdb::FloatGrid>(
        levelSetChecked(p.mesh, p.grid, ls, options, xform.copy(), scale).front());
}

template <typename PointT>
openvdb::FloatGrid::Ptr Voxelizer::meshToUnsignedDistanceField(const std::vector<PointT>& points,
                                                               const std::vector<openvdb::Vec3I>& triangles,
                                                               const openvdb::math::Transform& xform, float band,
                                                               const VoxelizeOptions& options)
{
    const double scale = detail::uniformScale(xform);
    const IndexSpaceMesh p = prepareMesh(points, triangles, {}, xform);
    LevelSetOptions ls;
    ls.exteriorBand = ls.interiorBand = band;
    ls.unsignedDistance = true;
    return openvdb::gridPtrCast<openvdb::FloatGrid>(
        levelSetChecked(p.mesh, p.grid, ls, options, xform.copy(), scale).front());
}

template <typename PointT>
openvdb::MaskGrid::Ptr Voxelizer::meshToSolid(const std::vector<PointT>& points,
                                              const std::vector<openvdb::Vec3I>& triangles,
                                              const openvdb::math::Transform& xform, const VoxelizeOptions& options,
                                              const SignOptions& sign)
{
    const IndexSpaceMesh p = prepareMesh(points, triangles, {}, xform);
    return solidChecked(p.mesh, p.grid, options, sign, xform.copy());
}

} // namespace svo
