#pragma once
/// @file field_grids.h
/// @brief Distance fields and solids on bricks (svo/core/field_bricks.h) as
/// OpenVDB grids.
#include <openvdb/openvdb.h>

#include "svo/core/field_bricks.h"

namespace svo::vdb {

/// @brief The grids of a distance field: the distances (world units), then
/// "closest_triangle" (Int32Grid, -1 off the band) when it was computed.
/// @details Voxels nearer than the band on their side are active; others hold
/// +/- the background, the exterior band times the voxel size, signed as
/// OpenVDB's signedFloodFill signs them (parity) or as the winding number
/// says. A signed field has class GRID_LEVEL_SET and is named "surface"; an
/// unsigned one GRID_UNKNOWN, named "distance".
/// @param field         the distances (and closest triangles) on bricks
/// @param exteriorBand, interiorBand  the band on each side, in voxels
/// @param worldPerVoxel the transform's uniform scale
/// @param xform         the grids' transform
/// @return the distance grid, then the closest-triangle grid when present
openvdb::GridPtrVec levelSetGrids(const DistanceBricks& field, double exteriorBand, double interiorBand,
                                  double worldPerVoxel, openvdb::math::Transform::Ptr xform);

/// @brief The MaskGrid "band": the voxels of an unsigned field nearer than
/// @a band, the active voxels of levelSetGrids' "distance" grid.
/// @param field an unsigned field (its distances, not necessarily the
///        least where only the band was asked: gl::FieldRequest::bandOnly)
/// @param band  the band in voxels
/// @param xform the grid's transform
openvdb::MaskGrid::Ptr bandGrid(const DistanceBricks& field, double band, openvdb::math::Transform::Ptr xform);

/// @brief The MaskGrid "solid": the band's inside voxels, and whole regions
/// inside as active tiles at the largest tree level they fill (memory follows
/// the surface).
/// @param xform the grid's transform
openvdb::MaskGrid::Ptr solidGrid(const SolidBricks& solid, openvdb::math::Transform::Ptr xform);

} // namespace svo::vdb
