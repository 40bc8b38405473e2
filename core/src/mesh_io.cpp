#include "svo/core/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <tbb/parallel_for.h>
#include <unistd.h>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "gltf_reader.h"
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

/// A text output written in order from pieces formatted on all cores, so
/// that a 10^8-triangle mesh's several gigabytes of text are never in memory
/// whole. POSIX calls rather than a stream, so that a full disk is named.
class TextFile {
public:
    TextFile(const std::string& tmp, const std::string& path) : path_(path)
    {
        fd_ = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd_ < 0) fail(errno);
    }
    ~TextFile()
    {
        if (fd_ >= 0) ::close(fd_);
    }
    TextFile(const TextFile&) = delete;
    TextFile& operator=(const TextFile&) = delete;

    void write(const char* bytes, size_t size)
    {
        for (size_t done = 0; done < size;) {
            const ssize_t n = ::write(fd_, bytes + done, size - done);
            if (n > 0) done += size_t(n);
            else if (n == 0) fail(EIO);
            else if (errno != EINTR) fail(errno);
        }
    }
    /// Lines 0 to @a count - 1, line(buffer, i) appending line i: formatted
    /// a batch of pieces at a time in parallel, written in order.
    template <typename Line>
    void lines(size_t count, const Line& line)
    {
        constexpr size_t kPiece = 1 << 15, kBatch = 32; // lines; pieces (some 64 MB of text a batch)
        std::vector<fmt::memory_buffer> pieces(kBatch);
        for (size_t start = 0; start < count; start += kPiece * kBatch) {
            const size_t n = std::min(kBatch, (count - start + kPiece - 1) / kPiece);
            tbb::parallel_for(size_t(0), n, [&](size_t k) {
                pieces[k].clear();
                const size_t first = start + k * kPiece, last = std::min(count, first + kPiece);
                for (size_t i = first; i < last; ++i) line(pieces[k], i);
            });
            for (size_t k = 0; k < n; ++k) write(pieces[k].data(), pieces[k].size());
        }
    }
    void close()
    {
        const int fd = std::exchange(fd_, -1);
        if (::close(fd) != 0) fail(errno);
    }

private:
    [[noreturn]] void fail(int error) const
    {
        throw IoError(fmt::format("{}: cannot write the file: {}", path_, std::strerror(error)));
    }
    std::string path_;
    int fd_ = -1;
};

} // namespace

void writeMesh(const std::string& path, const TriangleMesh& mesh)
{
    const std::string ext = lowerExtension(path);
    if (ext != "off" && ext != "obj") throw IoError(fmt::format("{}: meshes are written as .off or .obj", path));
    const bool obj = ext == "obj", colors = !obj && !mesh.colors.empty();
    const std::string header = obj ? std::string("# ") + mesh.source + "\n"
                                   : fmt::format("{}\n{} {} 0\n", colors ? "COFF" : "OFF", mesh.positions.size(),
                                                 mesh.triangles.size());
    writeAtomically(path, [&](const std::string& tmp) {
        TextFile file(tmp, path);
        file.write(header.data(), header.size());
        file.lines(mesh.positions.size(), [&](fmt::memory_buffer& out, size_t i) {
            const Vec3d& p = mesh.positions[i];
            fmt::format_to(std::back_inserter(out), "{}{} {} {}", obj ? "v " : "", p.x, p.y, p.z); // shortest round-trip form
            if (colors)
                fmt::format_to(std::back_inserter(out), " {} {} {} 1.0", mesh.colors[i].x, mesh.colors[i].y, mesh.colors[i].z);
            out.push_back('\n');
        });
        file.lines(mesh.triangles.size(), [&](fmt::memory_buffer& out, size_t i) {
            const auto& t = mesh.triangles[i];
            if (obj) fmt::format_to(std::back_inserter(out), "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
            else fmt::format_to(std::back_inserter(out), "3 {} {} {}\n", t[0], t[1], t[2]);
        });
        file.close();
    });
}

const char* supportedMeshExtensions() { return ".obj, .ply, .stl, .off, .gltf, .glb"; }

TriangleMesh loadMesh(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    if (ext.empty())
        throw IoError(fmt::format("{}: the name has no extension, which svo needs to know the format ({})", path,
                                  supportedMeshExtensions()));
    if (ext != "obj" && ext != "ply" && ext != "stl" && ext != "off" && ext != "gltf" && ext != "glb")
        throw IoError(fmt::format("{}: unknown mesh extension '.{}' (supported: {})", path, ext,
                                  supportedMeshExtensions()));
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw IoError(fmt::format("{}: no such file", path));
    if (std::filesystem::is_directory(path, ec)) throw IoError(fmt::format("{}: is a directory, not a mesh file", path));
    std::ifstream file(path, std::ios::binary);
    if (!file) throw IoError(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw IoError(fmt::format("{}: cannot read the file size: {}", path, ec.message()));
    if (size == 0) throw IoError(fmt::format("{}: the file is empty", path));

    TriangleMesh mesh;
    std::string bytes;
    if (ext != "obj") { // OBJ text is read a block at a time
        bytes.resize(size);
        file.read(bytes.data(), std::streamsize(bytes.size()));
        if (!file) throw IoError(fmt::format("{}: read error", path));
    }
    if (ext == "obj") mesh = detail::readObjFile(path);
    else if (ext == "ply") mesh = detail::readPly(path, bytes);
    else if (ext == "stl") mesh = detail::readStl(path, bytes);
    else if (ext == "gltf" || ext == "glb") mesh = detail::readGltf(path, bytes);
    else mesh = detail::readOff(path, bytes);
    try {
        validateMesh(mesh);
    } catch (const InvalidInput& e) {
        throw IoError(e.what()); // a file that holds a bad mesh is a damaged file
    }
    return mesh;
}

} // namespace svo
