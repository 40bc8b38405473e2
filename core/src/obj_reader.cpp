#include "obj_reader.h"

#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <string_view>
#include <vector>

#include "svo/core/error.h"
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

TriangleMesh readObj(const std::string& path, const std::string& bytes)
{
    TriangleMesh mesh;
    mesh.source = path;
    std::vector<Vec3f> colors; // kept only if every vertex has one
    const Vec3f uncoloured{-1, -1, -1};
    size_t colored = 0;
    std::string joined;        // a statement continued over several lines
    std::vector<uint32_t> face;
    // Positive indices may name vertices listed later, so they are checked at
    // the end; the largest one and its line are enough for the message.
    uint64_t maxIndex = 0;
    size_t maxIndexLine = 0;
    size_t lineNo = 0, statementLine = 0;
    auto fail = [&](const std::string& what) {
        return Error(fmt::format("{}: line {}: {}", path, statementLine, what));
    };

    const char* p = bytes.data();
    const char* const end = p + bytes.size();
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
            if (mesh.positions.size() == UINT32_MAX)
                throw fail("more vertices than 32-bit indices address");
            mesh.positions.push_back({c[0], c[1], c[2]});
            // `v x y z r g b` (6 numbers) carries a colour; 4 is `v x y z w`.
            if (n == 6) {
                colors.resize(mesh.positions.size() - 1, uncoloured);
                colors.push_back({float(c[3]), float(c[4]), float(c[5])});
                ++colored;
            }
            continue;
        }
        if (keyword != "f") continue; // vt, vn, o, g, s, usemtl, mtllib, l, p, ...: not needed to voxelize

        face.clear();
        const uint64_t known = mesh.positions.size();
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
                // Relative: -1 is the vertex listed last before this face.
                if (uint64_t(-(k + 1)) >= known)
                    throw fail(fmt::format("face uses relative vertex index {}, but only {} vertices precede it", k,
                                           known));
                face.push_back(uint32_t(known - uint64_t(-(k + 1)) - 1));
                continue;
            }
            if (uint64_t(k) > UINT32_MAX)
                throw fail(fmt::format("face uses vertex index {}, more than 32-bit indices address", k));
            if (uint64_t(k) > maxIndex) maxIndex = uint64_t(k), maxIndexLine = statementLine;
            face.push_back(uint32_t(k - 1));
        }
        if (face.empty()) throw fail("a face with no vertices");
        // Fan triangulation; a face with fewer than 3 corners still covers its points.
        auto u = [&](size_t i) { return face[std::min(i, face.size() - 1)]; };
        const size_t fans = face.size() < 3 ? 1 : face.size() - 2;
        for (size_t i = 0; i < fans; ++i) mesh.triangles.push_back({u(0), u(i + 1), u(i + 2)});
    }

    if (maxIndex > mesh.positions.size())
        throw Error(fmt::format("{}: line {}: face uses vertex index {}, but the file has {} vertices", path,
                                maxIndexLine, maxIndex, mesh.positions.size()));
    if (colored) {
        if (colored == mesh.positions.size()) mesh.colors = std::move(colors);
        else
            mesh.warnings.push_back(fmt::format("{}: only {} of {} vertices have a colour; colours are not used", path,
                                                colored, mesh.positions.size()));
    }
    return mesh;
}

} // namespace svo::detail
