#include "off_reader.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <string_view>
#include <tbb/parallel_for.h>
#include <vector>

#include "svo/core/error.h"
#include "text_chunks.h"
#include "text_scan.h"

namespace svo::detail {
namespace {

/// Lines with comments stripped and blank lines skipped, numbered for errors;
/// views into the bytes, so that a large file costs no string per line.
class Lines {
public:
    explicit Lines(std::string_view bytes, size_t before = 0)
        : p_(bytes.data()), end_(p_ + bytes.size()), number_(before)
    {
    }
    bool next(std::string_view& line)
    {
        while (p_ < end_) {
            const char* nl = static_cast<const char*>(std::memchr(p_, '\n', size_t(end_ - p_)));
            line = std::string_view(p_, size_t((nl ? nl : end_) - p_));
            p_ = nl ? nl + 1 : end_;
            ++number_;
            if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
            if (line.find_first_not_of(" \t\r\v\f") != std::string_view::npos) return true;
        }
        return false;
    }
    size_t number() const { return number_; }
    const char* position() const { return p_; }

private:
    const char* p_;
    const char* end_;
    size_t number_ = 0;
};

/// The whitespace-separated words of a line, into w.
void words(std::string_view line, std::vector<std::string_view>& w)
{
    w.clear();
    TextScanner s(line);
    for (std::string_view t = s.next(); !t.empty(); t = s.next()) w.push_back(t);
}

/// The body's records (vertex and face lines) as the header declares them.
struct OffLayout {
    int64_t nv = 0, nf = 0;
    bool hasColors = false;
    size_t colorAt = 3;
};

/// Vertex `v` from its words into mesh (and its colour); throws fail(...).
template <typename Fail>
void parseVertex(const std::vector<std::string_view>& w, int64_t v, const OffLayout& l, Vec3d& position, Vec3f* color,
                 Fail&& fail)
{
    if (w.size() < 3) throw fail(fmt::format("vertex {} has {} coordinates", v, w.size()));
    double c[3];
    for (int k = 0; k < 3; ++k) {
        if (!parseDouble(w[size_t(k)], c[k]) || !std::isfinite(c[k]))
            throw fail(fmt::format("vertex {} has a non-finite or malformed coordinate {}", v, quoted(w[size_t(k)])));
    }
    position = {c[0], c[1], c[2]};
    if (l.hasColors) {
        if (w.size() < l.colorAt + 3) throw fail(fmt::format("vertex {} has no colour", v));
        // Integers are 0..255; numbers with a point are 0..1.
        float rgb[3];
        bool integers = true;
        for (int k = 0; k < 3; ++k) {
            const std::string_view t = w[l.colorAt + size_t(k)];
            double x = 0;
            rgb[k] = parseDouble(t, x) ? float(x) : NAN;
            if (!std::isfinite(rgb[k])) throw fail(fmt::format("vertex {} has a malformed colour {}", v, quoted(t)));
            integers &= t.find_first_of(".eE") == std::string_view::npos;
        }
        const float scale = integers ? 1.0f / 255.0f : 1.0f;
        *color = {rgb[0] * scale, rgb[1] * scale, rgb[2] * scale};
    }
}

/// Fan triangulation of a face's corners (one or more); a face with fewer
/// than 3 corners still covers its points.
void addFan(const std::vector<uint32_t>& idx, std::vector<std::array<uint32_t, 3>>& triangles)
{
    auto u = [&](size_t i) { return idx[std::min(i, idx.size() - 1)]; };
    const size_t fans = idx.size() < 3 ? 1 : idx.size() - 2;
    for (size_t i = 0; i < fans; ++i) triangles.push_back({u(0), u(i + 1), u(i + 2)});
}

/// Face `f` from its words, fan-triangulated onto `triangles`; throws fail(...).
template <typename Fail>
void parseFace(const std::vector<std::string_view>& w, int64_t f, const OffLayout& l, std::vector<uint32_t>& idx,
               std::vector<std::array<uint32_t, 3>>& triangles, Fail&& fail)
{
    int64_t n = -1;
    if (w.empty() || !parseInt(w[0], n) || n < 1 || uint64_t(n) >= w.size())
        throw fail(fmt::format("face {} is malformed", f));
    idx.clear();
    for (int64_t i = 1; i <= n; ++i) {
        int64_t k = -1;
        if (!parseInt(w[size_t(i)], k) || k < 0 || k >= l.nv)
            throw fail(fmt::format("face {} uses vertex index {}, but the file has {} vertices", f,
                                   quoted(w[size_t(i)]), l.nv));
        idx.push_back(uint32_t(k));
    }
    addFan(idx, triangles);
}

/// The body parsed in pieces at once: records counted per piece, then each
/// piece parses its records knowing their place; returns how many pieces. 0 (and nothing kept)
/// where a piece finds anything the one-piece reader would name: it reads the
/// file again to say it in the same words.
size_t readBodyInParallel(std::string_view body, const OffLayout& l, size_t chunkBytes, TriangleMesh& mesh)
{
    const std::vector<std::string_view> pieces = cutAtLines(body, chunkBytes, [](size_t) { return true; });
    if (pieces.size() < 2) return 0;
    std::vector<int64_t> records(pieces.size() + 1, 0);
    tbb::parallel_for(size_t(0), pieces.size(), [&](size_t i) {
        Lines lines(pieces[i]);
        std::string_view line;
        int64_t n = 0;
        while (lines.next(line)) ++n;
        records[i + 1] = n;
    });
    for (size_t i = 0; i < pieces.size(); ++i) records[i + 1] += records[i];
    // Truncated (named by the one-piece reader). nf is checked alone first, so
    // that nv + nf cannot overflow: nv is below 2^32 and nf below the line count.
    if (l.nf > records.back() || records.back() < l.nv + l.nf) return 0;
    const int64_t want = l.nv + l.nf;
    mesh.positions.resize(size_t(l.nv));
    if (l.hasColors) mesh.colors.resize(size_t(l.nv));
    std::vector<std::vector<std::array<uint32_t, 3>>> triangles(pieces.size());
    std::atomic<bool> failed{false};
    struct Failed {};
    tbb::parallel_for(size_t(0), pieces.size(), [&](size_t i) {
        if (records[i] >= want) return;
        Lines lines(pieces[i]);
        std::string_view line;
        std::vector<std::string_view> w;
        std::vector<uint32_t> idx;
        auto fail = [](const std::string&) { return Failed{}; };
        try {
            for (int64_t r = records[i]; r < want && lines.next(line); ++r) {
                words(line, w);
                if (r < l.nv)
                    parseVertex(w, r, l, mesh.positions[size_t(r)], l.hasColors ? &mesh.colors[size_t(r)] : nullptr,
                                fail);
                else
                    parseFace(w, r - l.nv, l, idx, triangles[i], fail);
            }
        } catch (const Failed&) {
            failed = true;
        }
    });
    if (failed) {
        mesh.positions.clear();
        mesh.colors.clear();
        return 0;
    }
    size_t total = 0;
    for (const auto& t : triangles) total += t.size();
    mesh.triangles.reserve(total);
    for (const auto& t : triangles) mesh.triangles.insert(mesh.triangles.end(), t.begin(), t.end());
    return pieces.size();
}

/// Big-endian 32-bit words, the OFF spec's binary encoding whatever the
/// machine's; bounds-checked: false at the end of the data.
class BigEndianWords {
public:
    explicit BigEndianWords(std::string_view body) : p_(body.data()), end_(p_ + body.size()) {}
    bool int32(int32_t& out) { return next(out); }
    bool float32(float& out) { return next(out); }
    /// Whole words left.
    uint64_t remaining() const { return uint64_t(end_ - p_) / 4; }

private:
    template <typename T> bool next(T& out)
    {
        static_assert(sizeof(T) == 4);
        if (end_ - p_ < 4) return false;
        const auto* b = reinterpret_cast<const unsigned char*>(p_);
        const uint32_t u = uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | uint32_t(b[3]);
        std::memcpy(&out, &u, 4);
        p_ += 4;
        return true;
    }
    const char* p_;
    const char* end_;
};

/// The word read in the other byte order (to recognise a little-endian file).
uint32_t byteSwapped(uint32_t u) { return u >> 24 | (u >> 8 & 0xFF00u) | (u << 8 & 0xFF0000u) | u << 24; }

/// What a binary vertex holds after x y z, from the keyword's prefix, in this
/// order: a normal (3 floats), an RGBA colour (4), a texture coordinate (2).
struct BinaryLayout {
    bool normals = false, colors = false, texture = false;
    size_t floatsPerVertex() const { return 3 + (normals ? 3 : 0) + (colors ? 4 : 0) + (texture ? 2 : 0); }
};

/// The layout a keyword's prefix gives (ST, C and N, each once at most);
/// false for any other letter: text can skip what it does not know, but in
/// binary an unknown field leaves every later byte unplaced.
bool binaryLayout(std::string_view prefix, BinaryLayout& l)
{
    for (size_t i = 0; i < prefix.size();) {
        if (prefix.substr(i, 2) == "ST" && !l.texture) l.texture = true, i += 2;
        else if (prefix[i] == 'C' && !l.colors) l.colors = true, ++i;
        else if (prefix[i] == 'N' && !l.normals) l.normals = true, ++i;
        else return false;
    }
    return true;
}

/// Vertex `v` into mesh: its position, and its colour's RGB if the layout has
/// one (alpha is not kept, as from text). The caller has checked that its
/// floats are there.
void readBinaryVertex(const std::string& path, BigEndianWords& in, int64_t v, const BinaryLayout& l,
                      TriangleMesh& mesh)
{
    float f[12] = {}; // 3 + 3 + 4 + 2 at most
    for (size_t k = 0; k < l.floatsPerVertex(); ++k)
        if (!in.float32(f[k])) throw IoError(fmt::format("{}: the file ends in vertex {} (truncated file?)", path, v));
    if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2]))
        throw IoError(fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {})", path, v, f[0], f[1], f[2]));
    mesh.positions.push_back({f[0], f[1], f[2]});
    if (!l.colors) return;
    const float* c = f + (l.normals ? 6 : 3);
    if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
        throw IoError(fmt::format("{}: vertex {} has a non-finite colour ({}, {}, {})", path, v, c[0], c[1], c[2]));
    mesh.colors.push_back({c[0], c[1], c[2]});
}

/// Face `f` of `nf`, fan-triangulated onto mesh. Its polygon size is checked
/// against the words left before anything is read or kept for it, so that no
/// count in the file sets how much is allocated or how long the loop runs.
void readBinaryFace(const std::string& path, BigEndianWords& in, int64_t f, int64_t nf, std::vector<uint32_t>& idx,
                    TriangleMesh& mesh)
{
    auto truncated = [&] { return IoError(fmt::format("{}: the file ends in face {} of {} (truncated file?)", path, f, nf)); };
    int32_t n = 0;
    if (!in.int32(n)) throw truncated();
    if (n < 1) throw IoError(fmt::format("{}: face {} has {} vertices", path, f, n));
    if (uint64_t(n) >= in.remaining()) // its indices and its colour count
        throw IoError(fmt::format("{}: face {} has {} vertices, more than the rest of the file holds (truncated file?)",
                                  path, f, n));
    idx.clear();
    for (int32_t i = 0; i < n; ++i) {
        int32_t k = -1;
        if (!in.int32(k)) throw truncated();
        if (k < 0 || size_t(k) >= mesh.positions.size())
            throw IoError(fmt::format("{}: face {} uses vertex index {}, but the file has {} vertices", path, f, k,
                                      mesh.positions.size()));
        idx.push_back(uint32_t(k));
    }
    // The face's colour: a count, then that many floats (a colour-map index or
    // RGB[A]); not kept, since svo's colours are per vertex.
    int32_t components = -1;
    if (!in.int32(components)) throw truncated();
    if (components < 0 || components > 4)
        throw IoError(fmt::format("{}: face {} has {} colour components (OFF allows 0 to 4)", path, f, components));
    for (int32_t c = 0; c < components; ++c) {
        float unused;
        if (!in.float32(unused)) throw truncated();
    }
    addFan(idx, mesh.triangles);
}

/// A binary body, the bytes after the `OFF BINARY` line (at `bodyAt` in the
/// file): int32 vertex, face and edge counts, the vertices, the faces.
TriangleMesh readBinaryBody(const std::string& path, std::string_view body, size_t bodyAt, const BinaryLayout& l)
{
    BigEndianWords in(body);
    int32_t nv = 0, nf = 0, ne = 0; // edges: not used (nor checked, as the spec says)
    if (!in.int32(nv) || !in.int32(nf) || !in.int32(ne))
        throw IoError(fmt::format("{}: truncated binary OFF: the counts need 12 bytes after the header line, the file "
                                  "has {}",
                                  path, body.size()));
    // A vertex takes its floats, a face at least its size, one index and its
    // colour count: counts that the rest of the file cannot hold are refused
    // before anything is allocated for them.
    auto fits = [&](int64_t v, int64_t f) {
        return v >= 0 && f >= 0 && uint64_t(v) * l.floatsPerVertex() + uint64_t(f) * 3 <= in.remaining();
    };
    if (!fits(nv, nf)) {
        // OpenMesh writes binary OFF in the machine's byte order: say so where
        // the counts read little-endian would fit.
        const bool little = fits(int32_t(byteSwapped(uint32_t(nv))), int32_t(byteSwapped(uint32_t(nf))));
        const std::string hint =
            little ? " (a little-endian file? svo reads binary OFF big-endian, as the format says)" : "";
        if (nv < 0 || nf < 0)
            throw IoError(fmt::format("{}: the binary header declares {} vertices and {} faces{}", path, nv, nf, hint));
        throw IoError(fmt::format("{}: the header declares {} vertices and {} faces, more than the file's {} bytes can "
                                  "hold{}",
                                  path, nv, nf, bodyAt + body.size(),
                                  little ? hint : std::string(" (truncated or corrupt file)")));
    }
    TriangleMesh mesh;
    mesh.source = path;
    mesh.positions.reserve(size_t(nv));
    if (l.colors) mesh.colors.reserve(size_t(nv));
    for (int32_t v = 0; v < nv; ++v) readBinaryVertex(path, in, v, l, mesh);
    mesh.triangles.reserve(size_t(nf));
    std::vector<uint32_t> idx;
    for (int32_t f = 0; f < nf; ++f) readBinaryFace(path, in, f, nf, idx, mesh);
    return mesh;
}

} // namespace

TriangleMesh readOff(const std::string& path, const std::string& bytes, size_t chunkBytes, size_t* inPieces)
{
    if (inPieces) *inPieces = 0;
    Lines lines(bytes);
    std::string_view line;
    std::vector<std::string_view> w;
    auto fail = [&](const std::string& what) { return IoError(fmt::format("{}: line {}: {}", path, lines.number(), what)); };
    if (!lines.next(line)) throw IoError(fmt::format("{}: no OFF header", path));
    words(line, w);
    if (w.empty()) throw fail("expected an OFF keyword");
    const std::string_view keyword = w[0];
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
        throw fail(fmt::format("expected an OFF keyword, found {}", quoted(keyword)));
    if (keyword.find('4') != std::string_view::npos || keyword.find('n') != std::string_view::npos)
        throw fail(fmt::format("{} files are not 3D; svo reads 3D OFF", quoted(keyword)));
    const size_t prefix = keyword.size() - 3;
    if (w.size() > 1 && w[1] == "BINARY") {
        BinaryLayout layout;
        if (!binaryLayout(keyword.substr(0, prefix), layout))
            throw fail(fmt::format("{} has fields svo cannot place in a binary file (it reads the prefixes ST, C, N)",
                                   quoted(keyword)));
        if (w.size() > 2)
            throw fail(fmt::format("unexpected {} after BINARY (the binary data starts on the next line)",
                                   quoted(w[2])));
        const size_t at = size_t(lines.position() - bytes.data());
        return readBinaryBody(path, std::string_view(bytes).substr(at), at, layout);
    }
    w.erase(w.begin());
    if (w.empty()) {
        if (!lines.next(line)) throw IoError(fmt::format("{}: truncated OFF header (no counts)", path));
        words(line, w);
    }
    int64_t nv = -1, nf = -1;
    if (w.size() < 2 || !parseInt(w[0], nv) || !parseInt(w[1], nf) || nv < 0 || nf < 0)
        throw fail("expected the vertex and face counts");
    if (nv > int64_t(UINT32_MAX)) throw fail(fmt::format("{} vertices are more than 32-bit indices address", nv));

    // Per vertex: x y z [nx ny nz if N] [r g b [a] if C] [s t if ST].
    const bool hasNormals = keyword.find('N') < prefix, hasColors = keyword.find('C') < prefix;
    const size_t colorAt = hasNormals ? 6 : 3;
    OffLayout layout;
    layout.nv = nv;
    layout.nf = nf;
    layout.hasColors = hasColors;
    layout.colorAt = colorAt;
    TriangleMesh mesh;
    mesh.source = path;
    const std::string_view body(lines.position(), size_t(bytes.data() + bytes.size() - lines.position()));
    if (const size_t pieces = readBodyInParallel(body, layout, chunkBytes, mesh)) {
        if (inPieces) *inPieces = pieces;
        return mesh;
    }

    mesh.positions.reserve(std::min<size_t>(size_t(nv), bytes.size() / 6)); // a vertex takes 6 bytes or more
    for (int64_t v = 0; v < nv; ++v) {
        if (!lines.next(line))
            throw IoError(fmt::format("{}: the header declares {} vertices but the file ends after {} (truncated file?)",
                                      path, nv, v));
        words(line, w);
        Vec3d position;
        Vec3f color;
        parseVertex(w, v, layout, position, &color, fail);
        mesh.positions.push_back(position);
        if (hasColors) mesh.colors.push_back(color);
    }
    std::vector<uint32_t> idx;
    for (int64_t f = 0; f < nf; ++f) {
        if (!lines.next(line))
            throw IoError(fmt::format("{}: the header declares {} faces but the file ends after {} (truncated file?)",
                                      path, nf, f));
        words(line, w);
        parseFace(w, f, layout, idx, mesh.triangles, fail);
    }
    return mesh;
}

} // namespace svo::detail
