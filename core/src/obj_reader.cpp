#include "obj_reader.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <tbb/parallel_for.h>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <map>
#include <string_view>
#include <vector>

#include "mtl_reader.h"
#include "svo/core/error.h"
#include "text_chunks.h"
#include "text_scan.h"

namespace svo::detail {
namespace {

bool continued(std::string_view line) { return !line.empty() && line.back() == '\\'; }

/// One physical line without its '\n' and a trailing '\r'; advances p.
std::string_view takeLine(const char*& p, const char* end)
{
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    const char* stop = nl ? nl : end;
    std::string_view line(p, size_t(stop - p));
    p = nl ? nl + 1 : end;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
}

} // namespace

namespace {

/// What one piece of the file holds: its vertices (and colours), its faces
/// as triangles, and what the checks at the end need.
struct ObjPart {
    std::vector<Vec3d> positions;
    std::vector<Vec3f> colors; ///< one per vertex when any has one; (-1, -1, -1) for none
    size_t colored = 0;
    std::vector<std::array<uint32_t, 3>> triangles;
    uint64_t maxIndex = 0;
    size_t maxIndexLine = 0; ///< counted from the piece's first line
    size_t lines = 0;
    bool relative = false; ///< a relative index, which needs the vertices before the piece
    /// `usemtl`: the first triangle (of the piece) of each material and its name.
    std::vector<std::pair<size_t, std::string>> materialRuns;
    /// `mtllib`: the line (counted from the piece's first) and the file names.
    std::vector<std::pair<size_t, std::string>> libraries;
};

/// Parses `text`, whose first line is line `firstLine` of the file, into
/// `out`. With `vertexBase` (the vertices before the piece: known only when
/// the piece is the whole file) relative indices are resolved; without, the
/// first one stops the piece with out.relative set.
void parseObjPart(const std::string& path, std::string_view text, size_t firstLine, const uint64_t* vertexBase,
                  ObjPart& out)
{
    const Vec3f uncoloured{-1, -1, -1};
    std::string joined; // a statement continued over several lines
    std::vector<uint32_t> face;
    size_t lineNo = firstLine - 1, statementLine = 0;
    auto fail = [&](const std::string& what) {
        return IoError(fmt::format("{}: line {}: {}", path, statementLine, what));
    };
    const char* p = text.data();
    const char* const end = p + text.size();
    while (p < end) {
        statementLine = ++lineNo;
        std::string_view line = takeLine(p, end);
        if (continued(line)) {
            joined.assign(line.data(), line.size() - 1);
            for (std::string_view more = line; continued(more) && p < end;) {
                more = takeLine(p, end);
                ++lineNo;
                joined += ' ';
                joined.append(more.data(), more.size() - (continued(more) ? 1 : 0));
            }
            line = joined;
        }
        if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        TextScanner words(line);
        const std::string_view keyword = words.next();
        if (keyword == "v") {
            double c[6];
            int n = 0;
            for (std::string_view t = words.next(); !t.empty(); t = words.next(), ++n) {
                double x = 0;
                if (!parseDouble(t, x)) throw fail(fmt::format("malformed number {} in a vertex", quoted(t)));
                if (!std::isfinite(x)) throw fail(fmt::format("non-finite coordinate {}", quoted(t)));
                if (n < 6) c[n] = x;
            }
            if (n < 3) throw fail(fmt::format("a vertex needs 3 coordinates, this one has {}", n));
            if ((vertexBase ? *vertexBase : 0) + out.positions.size() >= UINT32_MAX)
                throw fail("more vertices than 32-bit indices address");
            out.positions.push_back({c[0], c[1], c[2]});
            // `v x y z r g b` (6 numbers) carries a colour; 4 is `v x y z w`.
            if (n == 6) {
                out.colors.resize(out.positions.size() - 1, uncoloured);
                out.colors.push_back({float(c[3]), float(c[4]), float(c[5])});
                ++out.colored;
            }
            continue;
        }
        if (keyword == "usemtl") {
            out.materialRuns.push_back({out.triangles.size(), std::string(statementArgument(line, keyword))});
            continue;
        }
        if (keyword == "mtllib") {
            out.libraries.push_back({statementLine - firstLine + 1, std::string(statementArgument(line, keyword))});
            continue;
        }
        if (keyword != "f") continue; // vt, vn, o, g, s, l, p, ...: not needed to voxelize
        face.clear();
        for (std::string_view t = words.next(); !t.empty(); t = words.next()) {
            // v, v/vt, v//vn or v/vt/vn: only v is used.
            const size_t slash = t.find('/');
            const std::string_view v = t.substr(0, slash);
            const std::string_view rest = slash == std::string_view::npos ? std::string_view() : t.substr(slash);
            int64_t k = 0;
            if (!parseInt(v, k) || rest.find_first_not_of("/0123456789-+") != std::string_view::npos)
                throw fail(fmt::format("malformed face corner {}", quoted(t)));
            if (k == 0) throw fail("vertex index 0 in a face (OBJ counts vertices from 1)");
            if (k < 0) {
                if (!vertexBase) {
                    out.relative = true;
                    return;
                }
                // Relative: -1 is the vertex listed last before this face.
                const uint64_t known = *vertexBase + out.positions.size();
                if (uint64_t(-(k + 1)) >= known)
                    throw fail(fmt::format("face uses relative vertex index {}, but only {} vertices precede it", k,
                                           known));
                face.push_back(uint32_t(known - uint64_t(-(k + 1)) - 1));
                continue;
            }
            if (uint64_t(k) > UINT32_MAX)
                throw fail(fmt::format("face uses vertex index {}, more than 32-bit indices address", k));
            if (uint64_t(k) > out.maxIndex) out.maxIndex = uint64_t(k), out.maxIndexLine = statementLine;
            face.push_back(uint32_t(k - 1));
        }
        if (face.empty()) throw fail("a face with no vertices");
        // Fan triangulation; a face with fewer than 3 corners still covers its points.
        auto u = [&](size_t i) { return face[std::min(i, face.size() - 1)]; };
        const size_t fans = face.size() < 3 ? 1 : face.size() - 2;
        for (size_t i = 0; i < fans; ++i) out.triangles.push_back({u(0), u(i + 1), u(i + 2)});
    }
    out.lines = lineNo - (firstLine - 1);
}

/// What the pieces say of materials, for the whole file: the first triangle
/// of each `usemtl` and the absolute line of each `mtllib`.
struct Materials {
    std::vector<std::pair<size_t, std::string>> runs, libraries;
};

/// The checks and the assembly of the whole file from its pieces, in order.
TriangleMesh assemble(const std::string& path, std::vector<ObjPart>& parts, Materials& materials)
{
    TriangleMesh mesh;
    mesh.source = path;
    size_t vertices = 0, triangles = 0, colored = 0, lines = 0;
    uint64_t maxIndex = 0;
    size_t maxIndexLine = 0;
    for (const ObjPart& part : parts) {
        if (part.maxIndex > maxIndex) maxIndex = part.maxIndex, maxIndexLine = lines + part.maxIndexLine;
        vertices += part.positions.size();
        triangles += part.triangles.size();
        colored += part.colored;
        lines += part.lines;
    }
    // Positive indices may name vertices listed later, so they are checked at
    // the end; the largest one and its line are enough for the message.
    if (maxIndex > vertices)
        throw IoError(fmt::format("{}: line {}: face uses vertex index {}, but the file has {} vertices", path,
                                  maxIndexLine, maxIndex, vertices));
    if (vertices >= UINT32_MAX) throw IoError(fmt::format("{}: more vertices than 32-bit indices address", path));
    mesh.positions.reserve(vertices);
    mesh.triangles.reserve(triangles);
    if (colored == vertices && colored) mesh.colors.reserve(vertices);
    size_t lineBase = 0;
    for (ObjPart& part : parts) {
        for (auto& run : part.materialRuns) materials.runs.push_back({mesh.triangles.size() + run.first, std::move(run.second)});
        for (auto& lib : part.libraries) materials.libraries.push_back({lineBase + lib.first, std::move(lib.second)});
        lineBase += part.lines;
        mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
        mesh.triangles.insert(mesh.triangles.end(), part.triangles.begin(), part.triangles.end());
        if (colored == vertices && colored) {
            part.colors.resize(part.positions.size(), Vec3f{-1, -1, -1});
            mesh.colors.insert(mesh.colors.end(), part.colors.begin(), part.colors.end());
        }
        part = ObjPart(); // freed as joined: the pieces and the mesh are not all held at once
    }
    if (colored && colored != vertices)
        mesh.warnings.push_back(fmt::format("{}: only {} of {} vertices have a colour; colours are not used", path,
                                            colored, vertices));
    return mesh;
}

} // namespace

namespace {

/// Where `text` may be cut after its newline at `nl`: not inside a `\`
/// continued statement.
bool mayCutAfter(std::string_view text, size_t nl)
{
    size_t i = nl;
    if (i > 0 && text[i - 1] == '\r') --i;
    return i == 0 || text[i - 1] != '\\';
}

/// `text` (whole lines) cut into pieces of about `chunkBytes` that end at
/// line ends outside `\` continued statements.
std::vector<std::string_view> piecesOf(std::string_view text, size_t chunkBytes)
{
    return cutAtLines(text, chunkBytes, [&](size_t nl) { return mayCutAfter(text, nl); });
}

/// The pieces parsed in parallel, appended to `parts`; false when a piece
/// needs the file read in order (a relative index or an error: the serial
/// reader names the line).
bool parseInPieces(const std::string& path, const std::vector<std::string_view>& pieces, std::vector<ObjPart>& parts)
{
    const size_t first = parts.size();
    parts.resize(first + pieces.size());
    std::atomic<bool> serial{false};
    tbb::parallel_for(size_t(0), pieces.size(), [&](size_t i) {
        try {
            parseObjPart(path, pieces[i], 1, nullptr, parts[first + i]);
            if (parts[first + i].relative) serial = true;
        } catch (const Error&) {
            serial = true;
        }
    });
    return !serial;
}

/// The file in one piece, in order.
TriangleMesh readSerially(const std::string& path, std::string_view text, Materials& materials)
{
    const uint64_t none = 0;
    std::vector<ObjPart> whole(1);
    parseObjPart(path, text, 1, &none, whole[0]);
    return assemble(path, whole, materials);
}

TriangleMesh readObjGeometry(const std::string& path, std::string_view bytes, size_t chunkBytes, size_t* inPieces,
                             Materials& materials)
{
    if (inPieces) *inPieces = 0;
    const std::vector<std::string_view> pieces = piecesOf(bytes, chunkBytes);
    std::vector<ObjPart> parts;
    if (pieces.size() > 1 && parseInPieces(path, pieces, parts)) {
        if (inPieces) *inPieces = parts.size();
        return assemble(path, parts, materials);
    }
    return readSerially(path, bytes, materials);
}

/// Material libraries read from the OBJ's folder.
MaterialFiles besideTheFile(const std::string& objPath)
{
    const std::filesystem::path folder = std::filesystem::path(objPath).parent_path();
    return [folder](const std::string& name) -> std::optional<std::string> {
        const std::filesystem::path file = folder / name;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
        std::ifstream in(file, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!in && !in.eof()) return std::nullopt;
        return bytes;
    };
}

/// The diffuse colours (Kd) of the materials the `mtllib` statements name;
/// a library that cannot be found is a warning.
std::map<std::string, std::optional<Vec3f>> loadLibraries(const std::string& path, const Materials& materials,
                                                          const MaterialFiles& files, TriangleMesh& mesh)
{
    std::map<std::string, std::optional<Vec3f>> kd;
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    auto load = [&](const std::string& name, const std::string& bytes) {
        for (auto& [material, colour] : readMtl((folder / name).string(), bytes)) kd[material] = colour;
    };
    for (const auto& [line, names] : materials.libraries) {
        // One name with blanks when a file has it; blank-separated names otherwise.
        if (const auto whole = files(names)) {
            load(names, *whole);
            continue;
        }
        TextScanner words(names);
        for (std::string_view name = words.next(); !name.empty(); name = words.next()) {
            if (const auto bytes = files(std::string(name))) load(std::string(name), *bytes);
            else
                mesh.warnings.push_back(fmt::format("{}: line {}: material library {} not found; its colours are not used",
                                                    path, line, quoted(name)));
        }
    }
    return kd;
}

/// Colours from the materials' Kd where the file has no vertex colours and
/// every face has one: a vertex shared by faces of different colours is
/// split into one per colour (the same position, so the same voxels).
void colorByMaterial(const std::string& path, TriangleMesh& mesh, const Materials& materials, const MaterialFiles& files)
{
    if (materials.runs.empty() || !mesh.colors.empty() || mesh.triangles.empty()) return;
    const auto kd = loadLibraries(path, materials, files, mesh);
    std::vector<Vec3f> faceColor(mesh.triangles.size());
    size_t missing = 0, run = 0;
    std::optional<Vec3f> color;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (; run < materials.runs.size() && materials.runs[run].first <= t; ++run) {
            const auto it = kd.find(materials.runs[run].second);
            color = it == kd.end() ? std::nullopt : it->second;
        }
        if (color) faceColor[t] = *color;
        else ++missing;
    }
    if (missing == mesh.triangles.size()) return; // no colour to keep (a missing library was said above)
    if (missing) {
        mesh.warnings.push_back(fmt::format("{}: {} of {} faces have no material colour (Kd); colours are not used", path,
                                            missing, mesh.triangles.size()));
        return;
    }
    const Vec3f unused{1, 1, 1}; // vertices no face uses: any colour
    mesh.colors.assign(mesh.positions.size(), unused);
    std::vector<char> set(mesh.positions.size(), 0);
    std::map<std::pair<uint32_t, std::array<float, 3>>, uint32_t> copies;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Vec3f c = faceColor[t];
        for (uint32_t& v : mesh.triangles[t]) {
            if (!set[v]) {
                set[v] = 1;
                mesh.colors[v] = c;
                continue;
            }
            if (mesh.colors[v] == c) continue;
            const auto [it, added] = copies.insert({{v, {c.x, c.y, c.z}}, uint32_t(mesh.positions.size())});
            if (added) {
                if (mesh.positions.size() >= UINT32_MAX - 1)
                    throw IoError(fmt::format("{}: more vertices than 32-bit indices address once split by material",
                                              path));
                const Vec3d p = mesh.positions[v];
                mesh.positions.push_back(p);
                mesh.colors.push_back(c);
            }
            v = it->second;
        }
    }
}

} // namespace

TriangleMesh readObj(const std::string& path, std::string_view bytes, size_t chunkBytes, size_t* inPieces,
                     const MaterialFiles& materialFiles)
{
    Materials materials;
    TriangleMesh mesh = readObjGeometry(path, bytes, chunkBytes, inPieces, materials);
    colorByMaterial(path, mesh, materials, materialFiles ? materialFiles : besideTheFile(path));
    return mesh;
}

TriangleMesh readObjFile(const std::string& path, size_t blockBytes, size_t chunkBytes,
                         const MaterialFiles& materialFiles)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
    Materials materials;
    std::vector<ObjPart> parts;
    std::string block; // whole lines not parsed yet, then the next block
    bool inOrder = true;
    for (bool end = false; !end && inOrder;) {
        const size_t carried = block.size();
        block.resize(carried + blockBytes);
        in.read(block.data() + carried, std::streamsize(blockBytes));
        if (in.bad()) throw IoError(fmt::format("{}: read error", path));
        block.resize(carried + size_t(in.gcount()));
        end = in.eof();
        // Up to the last line end where a cut is allowed; all of it at the end.
        size_t cut = block.size();
        if (!end) {
            size_t nl = block.rfind('\n');
            while (nl != std::string::npos && !mayCutAfter(block, nl))
                nl = nl ? block.rfind('\n', nl - 1) : std::string::npos;
            cut = nl == std::string::npos ? 0 : nl + 1;
        }
        if (cut) inOrder = parseInPieces(path, piecesOf(std::string_view(block).substr(0, cut), chunkBytes), parts);
        block.erase(0, cut);
    }
    std::string().swap(block);
    TriangleMesh mesh;
    if (inOrder && !parts.empty()) {
        mesh = assemble(path, parts, materials);
    } else { // a relative index or an error: the whole file, in order
        parts.clear();
        in.clear();
        in.seekg(0);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (in.bad()) throw IoError(fmt::format("{}: read error", path));
        mesh = readSerially(path, bytes, materials);
    }
    colorByMaterial(path, mesh, materials, materialFiles ? materialFiles : besideTheFile(path));
    return mesh;
}

} // namespace svo::detail
