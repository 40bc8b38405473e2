#include "obj_reader.h"

#include <array>
#include <atomic>
#include <cmath>
#include <tbb/parallel_for.h>
#include <cstring>
#include <fmt/format.h>
#include <string_view>
#include <vector>

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
        if (keyword != "f") continue; // vt, vn, o, g, s, usemtl, mtllib, l, p, ...: not needed to voxelize
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

/// The checks and the assembly of the whole file from its pieces, in order.
TriangleMesh assemble(const std::string& path, std::vector<ObjPart>& parts)
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
    for (ObjPart& part : parts) {
        mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
        mesh.triangles.insert(mesh.triangles.end(), part.triangles.begin(), part.triangles.end());
        if (colored == vertices && colored) {
            part.colors.resize(part.positions.size(), Vec3f{-1, -1, -1});
            mesh.colors.insert(mesh.colors.end(), part.colors.begin(), part.colors.end());
        }
    }
    if (colored && colored != vertices)
        mesh.warnings.push_back(fmt::format("{}: only {} of {} vertices have a colour; colours are not used", path,
                                            colored, vertices));
    return mesh;
}

} // namespace

TriangleMesh readObj(const std::string& path, const std::string& bytes, size_t chunkBytes, size_t* inPieces)
{
    if (inPieces) *inPieces = 0;
    // Pieces end at line ends outside `\` continued statements.
    const std::vector<std::string_view> pieces = cutAtLines(bytes, chunkBytes, [&](size_t nl) {
        size_t i = nl;
        if (i > 0 && bytes[i - 1] == '\r') --i;
        return i == 0 || bytes[i - 1] != '\\';
    });
    if (pieces.size() > 1) {
        std::vector<ObjPart> parts(pieces.size());
        std::atomic<bool> serial{false};
        tbb::parallel_for(size_t(0), pieces.size(), [&](size_t i) {
            try {
                parseObjPart(path, pieces[i], 1, nullptr, parts[i]);
                if (parts[i].relative) serial = true;
            } catch (const Error&) {
                serial = true; // the whole file read in order names the line as the serial reader does
            }
        });
        if (!serial) {
            if (inPieces) *inPieces = parts.size();
            return assemble(path, parts);
        }
    }
    // One piece, a relative index or an error: the file in one piece, in order.
    const uint64_t none = 0;
    std::vector<ObjPart> whole(1);
    parseObjPart(path, bytes, 1, &none, whole[0]);
    return assemble(path, whole);
}

} // namespace svo::detail
