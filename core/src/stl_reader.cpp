#include "stl_reader.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <string_view>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <vector>

#include "svo/core/error.h"
#include "text_scan.h"

namespace svo::detail {
namespace {

/// A corner's coordinates as their bits: corners are shared when these are
/// equal (so -0 and +0 stay apart, which the voxelizer does not mind).
using CornerKey = std::array<uint64_t, 3>;

CornerKey keyOf(const Vec3d& p)
{
    CornerKey k;
    std::memcpy(&k[0], &p.x, 8);
    std::memcpy(&k[1], &p.y, 8);
    std::memcpy(&k[2], &p.z, 8);
    return k;
}

struct CornerHash {
    size_t operator()(const CornerKey& k) const
    {
        uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
        h = (h ^ (h >> 29) ^ k[1]) * 0xBF58476D1CE4E5B9ull;
        h = (h ^ (h >> 31) ^ k[2]) * 0x94D049BB133111EBull;
        return size_t(h ^ (h >> 32));
    }
};

/// The mesh of `corners` (three a triangle, in file order): corners with the
/// same bits become one vertex, numbered in the order of first appearance.
/// STL repeats each corner in every facet around it; welding keeps the
/// vertex list about six times shorter. In parallel: corners are split into
/// buckets by hash, each bucket finds every corner's first appearance on its
/// own, and a running count over the first appearances numbers them, which
/// gives the numbering of one pass in file order.
void weld(const std::vector<Vec3d>& corners, TriangleMesh& mesh)
{
    const size_t n = corners.size();
    if (n >= UINT32_MAX) // corners are numbered in 32 bits below
        throw IoError(fmt::format("{}: {} triangles are more than svo reads from one STL file", mesh.source, n / 3));
    constexpr size_t kBuckets = 256;
    std::vector<uint64_t> hashes(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const auto& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) hashes[i] = CornerHash{}(keyOf(corners[i]));
    });
    // Each bucket's corners in file order (a counting sort by bucket).
    const size_t parts = std::max<size_t>(1, std::min<size_t>(64, n >> 14));
    std::vector<std::array<uint32_t, kBuckets>> counts(parts);
    auto partRange = [&](size_t p) { return std::pair<size_t, size_t>{n * p / parts, n * (p + 1) / parts}; };
    tbb::parallel_for(size_t(0), parts, [&](size_t p) {
        counts[p].fill(0);
        const auto [lo, hi] = partRange(p);
        for (size_t i = lo; i < hi; ++i) ++counts[p][hashes[i] >> 56];
    });
    std::vector<size_t> bucketStart(kBuckets + 1, 0);
    std::vector<std::array<size_t, kBuckets>> offsets(parts);
    for (size_t b = 0, at = 0; b < kBuckets; ++b) {
        bucketStart[b] = at;
        for (size_t p = 0; p < parts; ++p) offsets[p][b] = at, at += counts[p][b];
        bucketStart[b + 1] = at;
    }
    std::vector<uint32_t> order(n);
    tbb::parallel_for(size_t(0), parts, [&](size_t p) {
        const auto [lo, hi] = partRange(p);
        for (size_t i = lo; i < hi; ++i) order[offsets[p][hashes[i] >> 56]++] = uint32_t(i);
    });
    // Each corner's first appearance.
    std::vector<uint32_t> first(n);
    tbb::parallel_for(size_t(0), kBuckets, [&](size_t b) {
        // Open addressing over the bucket's corners: a slot holds a first appearance + 1.
        size_t size = 16;
        while (size < 2 * (bucketStart[b + 1] - bucketStart[b])) size *= 2;
        std::vector<uint32_t> slots(size, 0);
        for (size_t j = bucketStart[b]; j < bucketStart[b + 1]; ++j) {
            const uint32_t i = order[j];
            const CornerKey k = keyOf(corners[i]);
            for (size_t s = size_t(hashes[i]) & (size - 1);; s = (s + 1) & (size - 1)) {
                if (!slots[s]) {
                    slots[s] = i + 1;
                    first[i] = i;
                    break;
                }
                if (keyOf(corners[slots[s] - 1]) == k) {
                    first[i] = slots[s] - 1;
                    break;
                }
            }
        }
    });
    // Vertex numbers: first appearances counted in file order.
    std::vector<uint32_t> number(n);
    uint64_t vertices = 0;
    for (size_t i = 0; i < n; ++i)
        if (first[i] == i) number[i] = uint32_t(vertices++);
    if (vertices >= UINT32_MAX) throw IoError(fmt::format("{}: more vertices than 32-bit indices address", mesh.source));
    mesh.positions.resize(size_t(vertices));
    mesh.triangles.resize(n / 3);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const auto& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const uint32_t v = number[first[i]];
            if (first[i] == i) mesh.positions[v] = corners[i];
            mesh.triangles[i / 3][i % 3] = v;
        }
    });
}

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
        throw IoError(fmt::format("{}: truncated binary STL ({} bytes, header needs 84)", path, bytes.size()));
    const uint32_t n = littleEndian32(bytes.data() + 80);
    const uint64_t want = 84 + 50ull * n;
    if (bytes.size() < want)
        throw IoError(fmt::format("{}: truncated binary STL: {} triangles need {} bytes, the file has {}", path, n, want,
                                  bytes.size()));
    // Corners decoded in parallel; the first non-finite coordinate in file order is named.
    std::vector<Vec3d> corners(3 * size_t(n));
    std::atomic<uint64_t> firstBad{UINT64_MAX};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 12), [&](const auto& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const char* corner = bytes.data() + 84 + 50ull * t + 12; // after the facet normal
            for (size_t c = 0; c < 3; ++c) {
                float f[3];
                for (size_t a = 0; a < 3; ++a) {
                    const uint32_t bits = littleEndian32(corner + 12 * c + 4 * a);
                    std::memcpy(&f[a], &bits, 4);
                    if (!std::isfinite(f[a])) {
                        const uint64_t at = 9 * t + 3 * c + a;
                        for (uint64_t now = firstBad; at < now && !firstBad.compare_exchange_weak(now, at);) {
                        }
                    }
                }
                corners[3 * t + c] = {f[0], f[1], f[2]};
            }
        }
    });
    if (const uint64_t at = firstBad; at != UINT64_MAX) {
        const uint32_t bits = littleEndian32(bytes.data() + 84 + 50 * (at / 9) + 12 + 4 * (at % 9));
        float f;
        std::memcpy(&f, &bits, 4);
        throw IoError(fmt::format("{}: triangle {} has a non-finite coordinate ({})", path, at / 9, f));
    }
    TriangleMesh mesh;
    mesh.source = path;
    weld(corners, mesh);
    return mesh;
}

TriangleMesh readAscii(const std::string& path, const std::string& bytes)
{
    TextScanner s(bytes);
    auto fail = [&](const std::string& what) { return IoError(fmt::format("{}: line {}: {}", path, s.line(), what)); };
    auto expect = [&](const char* keyword) {
        const std::string_view t = s.next();
        if (t.empty())
            throw IoError(fmt::format("{}: the file ends where '{}' should follow (truncated file?)", path, keyword));
        if (!equalsNoCase(t, keyword)) throw fail(fmt::format("expected '{}', found {}", keyword, quoted(t)));
    };
    expect("solid");
    s.skipLine(); // the solid's name

    TriangleMesh mesh;
    mesh.source = path;
    std::vector<Vec3d> corners; // three a triangle, welded at the end
    corners.reserve(bytes.size() / 60); // a facet takes 200 bytes or so
    std::vector<Vec3d> loop;
    for (;;) {
        std::string_view t = s.next();
        if (t.empty()) throw IoError(fmt::format("{}: the file ends without 'endsolid' (truncated file?)", path));
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
            if (s.next().empty()) throw IoError(fmt::format("{}: the file ends in a facet normal (truncated file?)", path));
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
            loop.push_back({c[0], c[1], c[2]});
        }
        if (t.empty()) throw IoError(fmt::format("{}: the file ends in a facet (truncated file?)", path));
        if (!equalsNoCase(t, "endloop")) throw fail(fmt::format("expected 'vertex' or 'endloop', found {}", quoted(t)));
        expect("endfacet");
        if (loop.size() < 3) throw fail(fmt::format("a facet with {} vertices", loop.size()));
        for (size_t i = 1; i + 1 < loop.size(); ++i) corners.insert(corners.end(), {loop[0], loop[i], loop[i + 1]});
    }
    weld(corners, mesh);
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
