#include "openmesh_reader.h"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <sstream>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <fmt/format.h>

#include "svo/core/error.h"
#include "text_scan.h"

namespace svo::detail {
namespace {

namespace om = OpenMesh;
using om::FaceHandle;
using om::HalfedgeHandle;
using om::VertexHandle;

/// Receives OpenMesh's reader callbacks straight into a TriangleMesh, without a
/// halfedge structure, so that no face is refused or altered on the way.
class RawImporter final : public om::IO::BaseImporter {
public:
    explicit RawImporter(TriangleMesh& mesh) : mesh_(mesh) {}

    size_t facesSeen = 0;
    std::string indexError;

    VertexHandle add_vertex(const om::Vec3f& p) override { return add({p[0], p[1], p[2]}); }
    VertexHandle add_vertex(const om::Vec3d& p) override { return add({p[0], p[1], p[2]}); }
    VertexHandle add_vertex() override { return add({0, 0, 0}); }

    FaceHandle add_face(const VHandles& idx) override
    {
        const int face = static_cast<int>(facesSeen++);
        const int n = static_cast<int>(mesh_.positions.size());
        for (const VertexHandle& v : idx)
            if (v.idx() < 0 || v.idx() >= n) {
                if (indexError.empty())
                    indexError = fmt::format("face {} uses vertex index {}, but the file has {} vertices",
                                             face, v.idx(), n);
                return FaceHandle(face);
            }
        // Fan triangulation; a face with fewer than 3 corners still covers its points.
        if (idx.empty()) return FaceHandle(face);
        auto u = [&](size_t i) { return static_cast<uint32_t>(idx[std::min(i, idx.size() - 1)].idx()); };
        const size_t fans = idx.size() < 3 ? 1 : idx.size() - 2;
        for (size_t i = 0; i < fans; ++i) mesh_.triangles.push_back({u(0), u(i + 1), u(i + 2)});
        return FaceHandle(face);
    }

    // Everything else a reader can report is not used by the voxelizer.
    HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
    FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<om::Vec2f>&) override {}
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<om::Vec3f>&) override {}
    void set_face_texindex(FaceHandle, int) override {}
    void set_point(VertexHandle v, const om::Vec3f& p) override
    {
        if (v.idx() >= 0 && size_t(v.idx()) < mesh_.positions.size()) mesh_.positions[v.idx()] = {p[0], p[1], p[2]};
    }
    void set_halfedge(VertexHandle, HalfedgeHandle) override {}
    void set_normal(VertexHandle, const om::Vec3f&) override {}
    void set_normal(VertexHandle, const om::Vec3d&) override {}
    void set_color(VertexHandle, const om::Vec3uc&) override {}
    void set_color(VertexHandle, const om::Vec4uc&) override {}
    void set_color(VertexHandle, const om::Vec3f&) override {}
    void set_color(VertexHandle, const om::Vec4f&) override {}
    void set_texcoord(VertexHandle, const om::Vec2f&) override {}
    void set_status(VertexHandle, const om::Attributes::StatusInfo&) override {}
    void set_next(HalfedgeHandle, HalfedgeHandle) override {}
    void set_face(HalfedgeHandle, FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(HalfedgeHandle, const om::Vec2f&) override {}
    void set_texcoord(VertexHandle, const om::Vec3f&) override {}
    void set_texcoord(HalfedgeHandle, const om::Vec3f&) override {}
    void set_status(HalfedgeHandle, const om::Attributes::StatusInfo&) override {}
    void set_color(om::EdgeHandle, const om::Vec3uc&) override {}
    void set_color(om::EdgeHandle, const om::Vec4uc&) override {}
    void set_color(om::EdgeHandle, const om::Vec3f&) override {}
    void set_color(om::EdgeHandle, const om::Vec4f&) override {}
    void set_status(om::EdgeHandle, const om::Attributes::StatusInfo&) override {}
    void set_normal(FaceHandle, const om::Vec3f&) override {}
    void set_normal(FaceHandle, const om::Vec3d&) override {}
    void set_color(FaceHandle, const om::Vec3uc&) override {}
    void set_color(FaceHandle, const om::Vec4uc&) override {}
    void set_color(FaceHandle, const om::Vec3f&) override {}
    void set_color(FaceHandle, const om::Vec4f&) override {}
    void set_status(FaceHandle, const om::Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}
    size_t n_vertices() const override { return mesh_.positions.size(); }
    size_t n_faces() const override { return facesSeen; }
    size_t n_edges() const override { return 0; }

private:
    VertexHandle add(Vec3d p)
    {
        mesh_.positions.push_back(p);
        return VertexHandle(static_cast<int>(mesh_.positions.size() - 1));
    }
    TriangleMesh& mesh_;
};

} // namespace

TriangleMesh readWithOpenMesh(const std::string& path)
{
    TriangleMesh mesh;
    mesh.source = path;
    RawImporter importer(mesh);
    // Collect OpenMesh's diagnostics instead of letting them reach the terminal.
    std::ostringstream diag;
    omerr().disconnect(std::cerr);
    omerr().connect(diag);
    omlog().disable();
    OpenMesh::IO::Options opt;
    const bool ok = OpenMesh::IO::IOManager().read(path, importer, opt);
    omerr().disconnect(diag);
    omerr().connect(std::cerr);
    omlog().enable();

    std::string why = diag.str();
    while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.pop_back();
    std::replace(why.begin(), why.end(), '\n', ' ');
    why = escaped(why); // OpenMesh may quote bytes of the file
    if (!ok) throw Error(fmt::format("{}: OpenMesh could not read the file{}{}", path, why.empty() ? "" : ": ", why));
    if (!importer.indexError.empty()) throw Error(fmt::format("{}: {}", path, importer.indexError));
    return mesh;
}

} // namespace svo::detail
