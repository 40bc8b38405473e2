#include "off_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fmt/format.h>
#include <sstream>
#include <vector>

#include "svo/core/error.h"
#include "text_scan.h"

namespace svo::detail {
namespace {

/// Lines with comments stripped and blank lines skipped, numbered for errors.
class Lines {
public:
    explicit Lines(const std::string& bytes) : in_(bytes) {}
    bool next(std::string& line)
    {
        while (std::getline(in_, line)) {
            ++number_;
            if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
            if (line.find_first_not_of(" \t\r\v\f") != std::string::npos) return true; // as istream skips
        }
        return false;
    }
    size_t number() const { return number_; }

private:
    std::istringstream in_;
    size_t number_ = 0;
};

/// The whitespace-separated words of a line.
std::vector<std::string> words(const std::string& line)
{
    std::istringstream s(line);
    std::vector<std::string> w;
    for (std::string t; s >> t;) w.push_back(t);
    return w;
}

} // namespace

std::optional<TriangleMesh> readAsciiOff(const std::string& path, const std::string& bytes)
{
    Lines lines(bytes);
    std::string line;
    auto fail = [&](const std::string& what) { return Error(fmt::format("{}: line {}: {}", path, lines.number(), what)); };
    if (!lines.next(line)) throw Error(fmt::format("{}: no OFF header", path));
    std::vector<std::string> w = words(line);
    if (w.empty()) throw fail("expected an OFF keyword");
    const std::string keyword = w[0];
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
        throw fail(fmt::format("expected an OFF keyword, found {}", quoted(keyword)));
    if (keyword.find('4') != std::string::npos || keyword.find('n') != std::string::npos)
        throw fail(fmt::format("{} files are not 3D; svo reads 3D OFF", quoted(keyword)));
    if (w.size() > 1 && w[1] == "BINARY") return std::nullopt;
    w.erase(w.begin());
    if (w.empty()) {
        if (!lines.next(line)) throw Error(fmt::format("{}: truncated OFF header (no counts)", path));
        w = words(line);
    }
    char* end = nullptr;
    const long nv = w.size() >= 2 ? std::strtol(w[0].c_str(), &end, 10) : -1;
    const long nf = w.size() >= 2 ? std::strtol(w[1].c_str(), &end, 10) : -1;
    if (nv < 0 || nf < 0) throw fail("expected the vertex and face counts");
    if (nv > long(UINT32_MAX)) throw fail(fmt::format("{} vertices are more than 32-bit indices address", nv));

    // Per vertex: x y z [nx ny nz if N] [r g b [a] if C] [s t if ST].
    const size_t prefix = keyword.size() - 3;
    const bool hasNormals = keyword.find('N') < prefix, hasColors = keyword.find('C') < prefix;
    const size_t colorAt = hasNormals ? 6 : 3;
    TriangleMesh mesh;
    mesh.source = path;
    mesh.positions.reserve(std::min<size_t>(size_t(nv), bytes.size() / 6)); // a vertex takes 6 bytes or more
    for (long v = 0; v < nv; ++v) {
        if (!lines.next(line))
            throw Error(fmt::format("{}: the header declares {} vertices but the file ends after {} (truncated file?)",
                                    path, nv, v));
        w = words(line);
        if (w.size() < 3) throw fail(fmt::format("vertex {} has {} coordinates", v, w.size()));
        double c[3];
        for (int k = 0; k < 3; ++k) {
            c[k] = std::strtod(w[size_t(k)].c_str(), &end);
            if (*end || !std::isfinite(c[k]))
                throw fail(fmt::format("vertex {} has a non-finite or malformed coordinate {}", v, quoted(w[size_t(k)])));
        }
        mesh.positions.push_back({c[0], c[1], c[2]});
        if (hasColors) {
            if (w.size() < colorAt + 3) throw fail(fmt::format("vertex {} has no colour", v));
            // Integers are 0..255; numbers with a point are 0..1.
            float rgb[3];
            bool integers = true;
            for (int k = 0; k < 3; ++k) {
                const std::string& t = w[colorAt + size_t(k)];
                rgb[k] = std::strtof(t.c_str(), &end);
                if (*end || !std::isfinite(rgb[k])) throw fail(fmt::format("vertex {} has a malformed colour {}", v, quoted(t)));
                integers &= t.find_first_of(".eE") == std::string::npos;
            }
            const float scale = integers ? 1.0f / 255.0f : 1.0f;
            mesh.colors.push_back({rgb[0] * scale, rgb[1] * scale, rgb[2] * scale});
        }
    }
    for (long f = 0; f < nf; ++f) {
        if (!lines.next(line))
            throw Error(fmt::format("{}: the header declares {} faces but the file ends after {} (truncated file?)",
                                    path, nf, f));
        w = words(line);
        const long n = w.empty() ? -1 : std::strtol(w[0].c_str(), &end, 10);
        if (n < 1 || size_t(n) >= w.size()) throw fail(fmt::format("face {} is malformed", f));
        std::vector<uint32_t> idx;
        for (long i = 1; i <= n; ++i) {
            const long k = std::strtol(w[size_t(i)].c_str(), &end, 10);
            if (*end || k < 0 || k >= nv)
                throw fail(fmt::format("face {} uses vertex index {}, but the file has {} vertices", f,
                                       quoted(w[size_t(i)]), nv));
            idx.push_back(uint32_t(k));
        }
        // Fan triangulation; a face with fewer than 3 corners still covers its points.
        auto u = [&](size_t i) { return idx[std::min(i, idx.size() - 1)]; };
        const size_t fans = idx.size() < 3 ? 1 : idx.size() - 2;
        for (size_t i = 0; i < fans; ++i) mesh.triangles.push_back({u(0), u(i + 1), u(i + 2)});
    }
    return mesh;
}

} // namespace svo::detail
