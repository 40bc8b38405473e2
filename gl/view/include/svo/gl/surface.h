#pragma once
/// @file surface.h
/// @brief The surface the octree view's voxel layer shades (ViewLayers::surface), and its names.
#include "svo/core/enum_names.h"

namespace svo::gl {

/// @brief The surface the voxel layer shades (ViewLayers::surface):
///   - Voxels: the voxels camera rays hit in the octree, each shaded at its
///     centre along its normal channel (or the face the ray hit): what the
///     octree holds, blocky at its resolution;
///   - Mesh: the mesh's triangles (OctreeView needs the mesh), rasterized
///     into the triangle each pixel sees, met there by the pixel's ray, and
///     shaded at that point along the triangle's normal by the same light,
///     AO and cones through the octree's volume (deferred shading, as in
///     Crassin et al. 2011): silhouettes and edges are the triangles', and
///     the octree only lights them. `svo view` picks it for lit and AO
///     pictures of a mesh input (`--surface auto`). Direct light marches its
///     shadow ray from the pixel's point (the Voxels surface reads each
///     voxel's from the injection). Colours by attribute, and the albedo,
///     are the channel's value at the voxel holding the point.
enum class Surface { Voxels, Mesh };
inline constexpr EnumName<Surface> kSurfaceNames[] = {{Surface::Voxels, "voxels"}, {Surface::Mesh, "mesh"}};
constexpr const auto& enumNames(Surface) { return kSurfaceNames; }

} // namespace svo::gl
