#include "closed_surface.h"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/boost/graph/helpers.h>
#include <fmt/format.h>

namespace svo::validate::detail {

namespace PMP = CGAL::Polygon_mesh_processing;

ClosedSurface closedSurface(const TriangleMesh& mesh, const std::vector<K::Point_3>& points)
{
    ClosedSurface out;
    std::vector<std::vector<std::size_t>> faces;
    faces.reserve(mesh.triangles.size());
    for (const auto& f : mesh.triangles) faces.push_back({f[0], f[1], f[2]});
    for (bool repair : {false, true}) {
        auto pts = points;
        auto polys = faces;
        if (repair) PMP::repair_polygon_soup(pts, polys);
        if (polys.empty()) {
            out.reason = "the mesh has no proper triangles, so it has no inside";
            continue;
        }
        if (!PMP::orient_polygon_soup(pts, polys)) {
            out.reason = "the mesh is not a 2-manifold (non-manifold edges or vertices), so it has no well-defined inside";
            continue;
        }
        SurfaceMesh candidate;
        PMP::polygon_soup_to_polygon_mesh(pts, polys, candidate);
        if (!CGAL::is_closed(candidate)) {
            size_t border = 0;
            for (auto e : candidate.halfedges()) border += candidate.is_border(e);
            out.reason = fmt::format("the mesh is open ({} border edges), so it has no inside", border);
            continue;
        }
        out.surface = std::move(candidate);
        out.closed = true;
        out.reason.clear();
        break;
    }
    return out;
}

} // namespace svo::validate::detail
