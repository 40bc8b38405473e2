#include "stl_reader.h"

#include <array>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "svo/core/error.h"
#include "text_scan.h"

namespace svo::detail {
namespace {

/// Shares corners whose coordinates have the same bits (so -0 and +0 stay
/// apart, which the voxelizer does not mind). STL repeats each corner in every
/// facet around it; welding keeps the vertex list about six times shorter.
class Welder {
public:
    Welder(TriangleMesh& mesh, size_t corners) : mesh_(mesh) { map_.reserve(corners / 4); }
    uint32_t add(const Vec3d& p)
    {
        Key k;
        std::memcpy(&k[0], &p.x, 8);
        std::memcpy(&k[1], &p.y, 8);
        std::memcpy(&k[2], &p.z, 8);
        const auto [it, added] = map_.try_emplace(k, uint32_t(mesh_.positions.size()));
        if (added) {
            if (mesh_.positions.size() == UINT32_MAX)
                throw Error(fmt::format("{}: more vertices than 32-bit indices address", mesh_.source));
            mesh_.positions.push_back(p);
        }
        return it->second;
    }

private:
    using Key = std::array<uint64_t, 3>;
    struct Hash {
        size_t operator()(const Key& k) const
        {
            uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
            h = (h ^ (h >> 29) ^ k[1]) * 0xBF58476D1CE4E5B9ull;
            h = (h ^ (h >> 31) ^ k[2]) * 0x94D049BB133111EBull;
            return size_t(h ^ (h >> 32));
        }
    };
    TriangleMesh& mesh_;
    std::unordered_map<Key, uint32_t, Hash> map_;
};

uint32_t littleEndian32(const char* b)
{
    const auto* u = reinterpret_cast<const unsigned char*>(b);
    return uint32_t(u[0]) | uint32_t(u[1]) << 8 | uint32_t(u[2]) << 16 | uint32_t(u[3]) << 24;
}

TriangleMesh readBinary(const std::string& path, const std::string& bytes)
{
    // An 80-byte header, a uint32 count and 50 bytes a triangle: a size that
    // disagrees means truncation.
    if (bytes.size() < 84)
        throw Error(fmt::format("{}: truncated binary STL ({} bytes, header needs 84)", path, bytes.size()));
    const uint32_t n = littleEndian32(bytes.data() + 80);
    const uint64_t want = 84 + 50ull * n;
    if (bytes.size() < want)
        throw Error(fmt::format("{}: truncated binary STL: {} triangles need {} bytes, the file has {}", path, n, want,
                                bytes.size()));
    TriangleMesh mesh;
    mesh.source = path;
    mesh.triangles.reserve(n);
    Welder weld(mesh, 3 * size_t(n));
    for (uint32_t t = 0; t < n; ++t) {
        const char* corner = bytes.data() + 84 + 50ull * t + 12; // after the facet normal
        std::array<uint32_t, 3> tri;
        for (int c = 0; c < 3; ++c) {
            float f[3];
            for (int a = 0; a < 3; ++a) {
                const uint32_t bits = littleEndian32(corner + 12 * c + 4 * a);
                std::memcpy(&f[a], &bits, 4);
                if (!std::isfinite(f[a]))
                    throw Error(fmt::format("{}: triangle {} has a non-finite coordinate ({})", path, t, f[a]));
            }
            tri[size_t(c)] = weld.add({f[0], f[1], f[2]});
        }
        mesh.triangles.push_back(tri);
    }
    return mesh;
}

TriangleMesh readAscii(const std::string& path, const std::string& bytes)
{
    TextScanner s(bytes);
    auto fail = [&](const std::string& what) { return Error(fmt::format("{}: line {}: {}", path, s.line(), what)); };
    auto expect = [&](const char* keyword) {
        const std::string_view t = s.next();
        if (t.empty())
            throw Error(fmt::format("{}: the file ends where '{}' should follow (truncated file?)", path, keyword));
        if (!equalsNoCase(t, keyword)) throw fail(fmt::format("expected '{}', found {}", keyword, quoted(t)));
    };
    expect("solid");
    s.skipLine(); // the solid's name

    TriangleMesh mesh;
    mesh.source = path;
    Welder weld(mesh, bytes.size() / 40); // a facet takes 200 bytes or so
    std::vector<uint32_t> loop;
    for (;;) {
        std::string_view t = s.next();
        if (t.empty()) throw Error(fmt::format("{}: the file ends without 'endsolid' (truncated file?)", path));
        if (equalsNoCase(t, "endsolid")) {
            s.skipLine();
            t = s.next();
            if (t.empty()) break; // another solid may follow
            if (!equalsNoCase(t, "solid")) throw fail(fmt::format("expected 'solid' after 'endsolid', found {}", quoted(t)));
            s.skipLine();
            continue;
        }
        if (!equalsNoCase(t, "facet")) throw fail(fmt::format("expected 'facet' or 'endsolid', found {}", quoted(t)));
        expect("normal");
        for (int a = 0; a < 3; ++a) // the normal is not used
            if (s.next().empty()) throw Error(fmt::format("{}: the file ends in a facet normal (truncated file?)", path));
        expect("outer");
        expect("loop");
        loop.clear();
        for (t = s.next(); equalsNoCase(t, "vertex"); t = s.next()) {
            double c[3];
            for (double& x : c) {
                const std::string_view v = s.next();
                if (!parseDouble(v, x)) throw fail(fmt::format("malformed coordinate {}", quoted(v)));
                if (!std::isfinite(x)) throw fail(fmt::format("non-finite coordinate {}", quoted(v)));
            }
            loop.push_back(weld.add({c[0], c[1], c[2]}));
        }
        if (t.empty()) throw Error(fmt::format("{}: the file ends in a facet (truncated file?)", path));
        if (!equalsNoCase(t, "endloop")) throw fail(fmt::format("expected 'vertex' or 'endloop', found {}", quoted(t)));
        expect("endfacet");
        if (loop.size() < 3) throw fail(fmt::format("a facet with {} vertices", loop.size()));
        for (size_t i = 1; i + 1 < loop.size(); ++i) mesh.triangles.push_back({loop[0], loop[i], loop[i + 1]});
    }
    return mesh;
}

} // namespace

TriangleMesh readStl(const std::string& path, const std::string& bytes)
{
    // A binary header may begin with "solid" too (some exporters write that);
    // a size that matches the binary layout exactly decides for binary.
    size_t start = 0;
    while (start < bytes.size() && isSpace(bytes[start])) ++start;
    const bool solid = bytes.size() - start >= 5 && equalsNoCase(std::string_view(bytes).substr(start, 5), "solid");
    const bool binarySize = bytes.size() >= 84 && bytes.size() == 84 + 50ull * littleEndian32(bytes.data() + 80);
    const bool ascii = solid && !binarySize &&
                       (bytes.size() < 84 || bytes.find("facet") != std::string::npos ||
                        bytes.find("FACET") != std::string::npos || bytes.find("endsolid") != std::string::npos);
    return ascii ? readAscii(path, bytes) : readBinary(path, bytes);
}

} // namespace svo::detail
