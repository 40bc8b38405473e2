#pragma once
/// @file closed_surface.h (internal)
/// The mesh as a closed CGAL surface, when it is one: what
/// Side_of_triangle_mesh needs to tell inside from outside.
///
/// Method: the triangles as given; failing that, with coincident vertices
/// welded and degenerate faces dropped (CGAL's repair_polygon_soup), which
/// changes no point's side and closes split seams, common in real meshes.
/// Either must orient into a 2-manifold (orient_polygon_soup) without border
/// edges.
#include <CGAL/Surface_mesh.h>
#include <string>
#include <vector>

#include "local_points.h"

namespace svo::validate::detail {

using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;

struct ClosedSurface {
    bool closed = false;
    SurfaceMesh surface; ///< the closed surface, when `closed`
    std::string reason;  ///< why there is none ("the mesh is open (12 border edges), so it has no inside")
};

/// @param points the mesh's vertices in local coordinates (localPoints)
ClosedSurface closedSurface(const TriangleMesh& mesh, const std::vector<K::Point_3>& points);

} // namespace svo::validate::detail
