#include "svo/core/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <fmt/format.h>

#include "off_reader.h"
#include "svo/core/atomic_file.h"
#include "svo/core/error.h"

namespace svo {
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

std::string lowerExtension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

/// A binary STL is an 80-byte header, a uint32 count and 50 bytes a triangle;
/// a size that disagrees means truncation, which OpenMesh would not report.
void checkBinaryStl(const std::string& path, const std::string& bytes)
{
    const bool ascii = bytes.compare(0, 5, "solid") == 0 && bytes.find("facet") != std::string::npos;
    if (ascii) return;
    if (bytes.size() < 84) throw Error(fmt::format("{}: truncated binary STL ({} bytes, header needs 84)", path, bytes.size()));
    uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);
    const uint64_t want = 84 + 50ull * n;
    if (bytes.size() < want)
        throw Error(fmt::format("{}: truncated binary STL: {} triangles need {} bytes, the file has {}", path, n,
                                want, bytes.size()));
    // OpenMesh welds STL vertices through an ordered map, where a NaN compares
    // equal to anything and silently vanishes; screen the corners here.
    for (uint32_t t = 0; t < n; ++t)
        for (int c = 0; c < 9; ++c) {
            float f;
            std::memcpy(&f, bytes.data() + 84 + 50ull * t + 12 + 4 * c, 4);
            if (!std::isfinite(f))
                throw Error(fmt::format("{}: triangle {} has a non-finite coordinate ({})", path, t, f));
        }
}

/// A PLY header declares its vertex and face counts; we hold the reader to them.
struct PlyCounts {
    long vertices = -1, faces = -1;
    bool binary = false;
};
PlyCounts readPlyHeader(const std::string& path, const std::string& bytes)
{
    PlyCounts c;
    std::istringstream in(bytes);
    std::string line;
    if (!std::getline(in, line) || line.rfind("ply", 0) != 0)
        throw Error(fmt::format("{}: not a PLY file (no 'ply' magic line)", path));
    bool ended = false;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string word, what;
        ls >> word;
        if (word == "format") { ls >> what; c.binary = what != "ascii"; }
        else if (word == "element") {
            long n = -1;
            ls >> what >> n;
            if (what == "vertex") c.vertices = n;
            if (what == "face") c.faces = n;
        } else if (word == "end_header") { ended = true; break; }
    }
    if (!ended) throw Error(fmt::format("{}: truncated PLY header (no end_header)", path));
    // Each vertex takes at least 3 bytes and each face at least 1: a count the
    // file cannot hold is refused before the reader allocates for it.
    if (c.vertices > long(UINT32_MAX) || c.faces > long(UINT32_MAX) ||
        double(std::max(c.vertices, 0L)) * 3 + double(std::max(c.faces, 0L)) > double(bytes.size()))
        throw Error(fmt::format("{}: the header declares {} vertices and {} faces, more than its {} bytes can hold "
                                "(truncated or corrupt file)",
                                path, c.vertices, c.faces, bytes.size()));
    return c;
}

/// OpenMesh's text readers turn "nan"/"inf" into undefined values (or lose
/// their place in the file), so ASCII OBJ, PLY and STL coordinates are
/// screened first (ASCII OFF is read by off_reader.h).
/// Returns the number of face records for formats that list one per line (OBJ).
size_t screenAsciiNumbers(const std::string& path, const std::string& ext, const std::string& bytes)
{
    std::istringstream in(bytes);
    std::string line;
    size_t lineNo = 0, faces = 0;
    bool body = ext == "obj" || ext == "stl";
    while (std::getline(in, line)) {
        ++lineNo;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        if (ext == "ply" && !body) {
            if (line.rfind("format", first) == first && line.find("ascii") == std::string::npos) return 0;
            body = line.rfind("end_header", first) == first;
            continue;
        }
        bool coordinates = true;
        if (ext == "obj") {
            coordinates = line.compare(first, 2, "v ") == 0 || line.compare(first, 2, "v\t") == 0;
            faces += line.compare(first, 2, "f ") == 0 || line.compare(first, 2, "f\t") == 0;
        }
        if (ext == "stl") coordinates = line.compare(first, 6, "vertex") == 0;
        if (!coordinates) continue;
        std::istringstream tokens(line);
        std::string tok;
        while (tokens >> tok) {
            std::string lower = tok;
            std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
            if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
                throw Error(fmt::format("{}: line {}: non-finite coordinate '{}'", path, lineNo, tok));
        }
    }
    return faces;
}

} // namespace

void writeMesh(const std::string& path, const TriangleMesh& mesh)
{
    const std::string ext = lowerExtension(path);
    if (ext != "off" && ext != "obj") throw Error(fmt::format("{}: meshes are written as .off or .obj", path));
    const bool obj = ext == "obj", colors = !obj && !mesh.colors.empty();
    std::string text = obj ? std::string("# ") + mesh.source + "\n"
                           : fmt::format("{}\n{} {} 0\n", colors ? "COFF" : "OFF", mesh.positions.size(),
                                         mesh.triangles.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3d& p = mesh.positions[i];
        text += fmt::format("{}{} {} {}", obj ? "v " : "", p.x, p.y, p.z); // shortest round-trip form
        if (colors) text += fmt::format(" {} {} {} 1.0", mesh.colors[i].x, mesh.colors[i].y, mesh.colors[i].z);
        text += '\n';
    }
    for (const auto& t : mesh.triangles)
        text += obj ? fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1)
                    : fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
    writeFileAtomically(path, text);
}

const char* supportedMeshExtensions() { return ".obj, .ply, .stl, .off"; }

TriangleMesh loadMesh(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    if (ext != "obj" && ext != "ply" && ext != "stl" && ext != "off")
        throw Error(fmt::format("{}: unknown mesh extension '.{}' (supported: {})", path, ext,
                                supportedMeshExtensions()));
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(fmt::format("{}: no such file", path));
    if (std::filesystem::is_directory(path, ec)) throw Error(fmt::format("{}: is a directory, not a mesh file", path));
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw Error(fmt::format("{}: cannot read the file size: {}", path, ec.message()));
    std::string bytes(size, '\0');
    file.read(bytes.data(), std::streamsize(bytes.size()));
    if (!file) throw Error(fmt::format("{}: read error", path));
    if (bytes.empty()) throw Error(fmt::format("{}: the file is empty", path));

    if (ext == "off")
        if (auto off = detail::readAsciiOff(path, bytes)) {
            validateMesh(*off);
            return std::move(*off);
        }
    // Binary OFF is left to OpenMesh; validateMesh checks what it delivers.
    PlyCounts declared; // counts the header promises (PLY)
    if (ext == "stl") checkBinaryStl(path, bytes);
    if (ext == "ply") declared = readPlyHeader(path, bytes);
    const size_t objFaces = ext == "off" ? 0 : screenAsciiNumbers(path, ext, bytes);

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
    if (!ok) throw Error(fmt::format("{}: OpenMesh could not read the file{}{}", path, why.empty() ? "" : ": ", why));
    if (!importer.indexError.empty()) throw Error(fmt::format("{}: {}", path, importer.indexError));
    if (declared.faces >= 0 && long(importer.facesSeen) != declared.faces)
        throw Error(fmt::format("{}: the header declares {} faces but {} could be read (truncated file?)", path,
                                declared.faces, importer.facesSeen));
    if (declared.vertices >= 0 && long(mesh.positions.size()) != declared.vertices)
        throw Error(fmt::format("{}: the header declares {} vertices but {} could be read (truncated file?)", path,
                                declared.vertices, mesh.positions.size()));
    if (ext == "obj" && importer.facesSeen < objFaces)
        mesh.warnings.push_back(fmt::format("{}: OpenMesh's OBJ reader skipped {} of {} faces (faces that repeat a "
                                            "vertex); they are not voxelized",
                                            path, objFaces - importer.facesSeen, objFaces));
    validateMesh(mesh);
    return mesh;
}

} // namespace svo
