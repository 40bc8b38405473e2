#include "svo/core/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "obj_reader.h"
#include "off_reader.h"
#include "ply_reader.h"
#include "stl_reader.h"
#include "svo/core/atomic_file.h"
#include "svo/core/error.h"

namespace svo {
namespace {

std::string lowerExtension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

} // namespace

void writeMesh(const std::string& path, const TriangleMesh& mesh)
{
    const std::string ext = lowerExtension(path);
    if (ext != "off" && ext != "obj") throw IoError(fmt::format("{}: meshes are written as .off or .obj", path));
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
    if (ext.empty())
        throw IoError(fmt::format("{}: the name has no extension, which svo needs to know the format ({})", path,
                                  supportedMeshExtensions()));
    if (ext != "obj" && ext != "ply" && ext != "stl" && ext != "off")
        throw IoError(fmt::format("{}: unknown mesh extension '.{}' (supported: {})", path, ext,
                                  supportedMeshExtensions()));
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw IoError(fmt::format("{}: no such file", path));
    if (std::filesystem::is_directory(path, ec)) throw IoError(fmt::format("{}: is a directory, not a mesh file", path));
    std::ifstream file(path, std::ios::binary);
    if (!file) throw IoError(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw IoError(fmt::format("{}: cannot read the file size: {}", path, ec.message()));
    std::string bytes(size, '\0');
    file.read(bytes.data(), std::streamsize(bytes.size()));
    if (!file) throw IoError(fmt::format("{}: read error", path));
    if (bytes.empty()) throw IoError(fmt::format("{}: the file is empty", path));

    TriangleMesh mesh;
    if (ext == "obj") mesh = detail::readObj(path, bytes);
    else if (ext == "ply") mesh = detail::readPly(path, bytes);
    else if (ext == "stl") mesh = detail::readStl(path, bytes);
    else mesh = detail::readOff(path, bytes);
    try {
        validateMesh(mesh);
    } catch (const InvalidInput& e) {
        throw IoError(e.what()); // a file that holds a bad mesh is a damaged file
    }
    return mesh;
}

} // namespace svo
