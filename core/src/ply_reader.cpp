#include "ply_reader.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
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

enum class Type : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool typeNamed(std::string_view name, Type& t)
{
    struct Name {
        const char* a;
        const char* b;
        Type t;
    };
    static const Name names[] = {{"char", "int8", Type::Int8},       {"uchar", "uint8", Type::UInt8},
                                 {"short", "int16", Type::Int16},    {"ushort", "uint16", Type::UInt16},
                                 {"int", "int32", Type::Int32},      {"uint", "uint32", Type::UInt32},
                                 {"float", "float32", Type::Float32}, {"double", "float64", Type::Float64}};
    for (const Name& n : names)
        if (name == n.a || name == n.b) return t = n.t, true;
    return false;
}
size_t sizeOf(Type t)
{
    static const size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    return sizes[int(t)];
}
bool isInteger(Type t) { return t < Type::Float32; }

struct Property {
    std::string name;
    Type type = Type::Float32; // of the items, for a list
    bool list = false;
    Type countType = Type::UInt8;
};
struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

/// Binary values of either byte order, bounds-checked; false at the end of the data.
class BinarySource {
public:
    BinarySource(std::string_view body, bool bigEndian) : p_(body.data()), end_(p_ + body.size())
    {
        const uint16_t one = 1;
        unsigned char first;
        std::memcpy(&first, &one, 1);
        swap_ = bigEndian == (first == 1);
    }
    bool value(Type t, double& out)
    {
        const size_t n = sizeOf(t);
        if (size_t(end_ - p_) < n) return false;
        unsigned char b[8];
        std::memcpy(b, p_, n);
        p_ += n;
        if (swap_) std::reverse(b, b + n);
        switch (t) {
        case Type::Int8: out = get<int8_t>(b); break;
        case Type::UInt8: out = get<uint8_t>(b); break;
        case Type::Int16: out = get<int16_t>(b); break;
        case Type::UInt16: out = get<uint16_t>(b); break;
        case Type::Int32: out = get<int32_t>(b); break;
        case Type::UInt32: out = get<uint32_t>(b); break;
        case Type::Float32: out = get<float>(b); break;
        case Type::Float64: out = get<double>(b); break;
        }
        return true;
    }
    /// Integer types only (the header is checked for that), so exact.
    bool integer(Type t, int64_t& out)
    {
        double d = 0;
        if (!value(t, d)) return false;
        out = int64_t(d);
        return true;
    }
    bool skip(Type t)
    {
        if (size_t(end_ - p_) < sizeOf(t)) return false;
        p_ += sizeOf(t);
        return true;
    }
    size_t remaining() const { return size_t(end_ - p_); }
    std::string where() const { return ""; }

private:
    template <typename T> static T get(const unsigned char* b)
    {
        T v;
        std::memcpy(&v, b, sizeof v);
        return v;
    }
    const char* p_;
    const char* end_;
    bool swap_ = false;
};

/// ASCII values as whitespace-separated tokens; false at the end of the text,
/// svo::Error naming the line for a malformed number.
class AsciiSource {
public:
    AsciiSource(const std::string& path, std::string_view body, size_t firstLine) : path_(path), s_(body, firstLine) {}
    bool value(Type, double& out)
    {
        const std::string_view t = s_.next();
        if (t.empty()) return false;
        if (!parseDouble(t, out)) throw IoError(fmt::format("{}: line {}: malformed number {}", path_, s_.line(), quoted(t)));
        return true;
    }
    bool integer(Type, int64_t& out)
    {
        const std::string_view t = s_.next();
        if (t.empty()) return false;
        if (!parseInt(t, out))
            throw IoError(fmt::format("{}: line {}: expected an integer, found {}", path_, s_.line(), quoted(t)));
        return true;
    }
    bool skip(Type) { return !s_.next().empty(); }
    size_t remaining() const { return s_.remaining(); }
    std::string where() const { return fmt::format(" (line {})", s_.line()); }

private:
    const std::string& path_;
    TextScanner s_;
};

struct Header {
    std::vector<Element> elements;
    enum Format { Ascii, Little, Big } format = Ascii;
    size_t bodyOffset = 0, bodyLine = 0;
};

Header readHeader(const std::string& path, const std::string& bytes)
{
    Header h;
    size_t pos = 0, lineNo = 0;
    bool haveFormat = false;
    auto fail = [&](const std::string& what) { return IoError(fmt::format("{}: line {}: {}", path, lineNo, what)); };
    while (pos < bytes.size()) {
        const size_t nl = bytes.find('\n', pos);
        if (nl == std::string::npos) break;
        const std::string_view line(bytes.data() + pos, nl - pos);
        pos = nl + 1;
        ++lineNo;
        TextScanner words(line);
        const std::string_view word = words.next();
        if (lineNo == 1) {
            if (word != "ply" || !words.next().empty())
                throw IoError(fmt::format("{}: not a PLY file (no 'ply' magic line)", path));
            continue;
        }
        if (word == "end_header") {
            if (!haveFormat) throw fail("the header has no format line");
            h.bodyOffset = pos;
            h.bodyLine = lineNo + 1;
            return h;
        }
        if (word == "comment" || word == "obj_info" || word.empty()) continue;
        if (word == "format") {
            const std::string_view f = words.next();
            if (f == "ascii") h.format = Header::Ascii;
            else if (f == "binary_little_endian") h.format = Header::Little;
            else if (f == "binary_big_endian") h.format = Header::Big;
            else throw fail(fmt::format("unknown PLY format {}", quoted(f)));
            haveFormat = true;
        } else if (word == "element") {
            Element e;
            e.name = std::string(words.next());
            int64_t n = -1;
            if (e.name.empty() || !parseInt(words.next(), n) || n < 0)
                throw fail("expected 'element <name> <count>'");
            e.count = uint64_t(n);
            h.elements.push_back(std::move(e));
        } else if (word == "property") {
            if (h.elements.empty()) throw fail("a property before any element");
            Property p;
            std::string_view t = words.next();
            if (t == "list") {
                p.list = true;
                const std::string_view c = words.next();
                if (!typeNamed(c, p.countType) || !isInteger(p.countType))
                    throw fail(fmt::format("list count type {} is not an integer type", quoted(c)));
                t = words.next();
            }
            if (!typeNamed(t, p.type)) throw fail(fmt::format("unknown property type {}", quoted(t)));
            p.name = std::string(words.next());
            if (p.name.empty()) throw fail("a property without a name");
            h.elements.back().properties.push_back(std::move(p));
        } else {
            throw fail(fmt::format("unexpected header line starting with {}", quoted(word)));
        }
    }
    if (lineNo == 0 && bytes.compare(0, 3, "ply") != 0)
        throw IoError(fmt::format("{}: not a PLY file (no 'ply' magic line)", path));
    throw IoError(fmt::format("{}: truncated PLY header (no end_header)", path));
}

/// What the body reader needs of an element: which properties are the
/// vertex coordinates and the face indices. Throws for a header that lacks them.
struct Layout {
    bool vertex = false, face = false;
    int axisOf[3] = {-1, -1, -1};
    int indices = -1;
};

Layout layoutOf(const std::string& path, const Element& e)
{
    Layout l;
    l.vertex = e.name == "vertex";
    l.face = e.name == "face";
    for (size_t j = 0; j < e.properties.size(); ++j) {
        const Property& p = e.properties[j];
        const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
        if (l.vertex && axis >= 0 && !p.list && l.axisOf[axis] < 0) l.axisOf[axis] = int(j);
        if (l.face && p.list && l.indices < 0 && (p.name == "vertex_indices" || p.name == "vertex_index")) {
            if (!isInteger(p.type))
                throw IoError(fmt::format("{}: the face element's '{}' list is not of an integer type", path, p.name));
            l.indices = int(j);
        }
    }
    return l;
}

/// Record i of element e from src: the vertex's coordinates into c, the
/// face's indices into face (the largest seen into maxIndex/maxIndexFace).
template <typename Source>
void readRecord(const std::string& path, const Element& e, const Layout& l, uint64_t i, Source& src, double (&c)[3],
                std::vector<uint32_t>& face, uint64_t& maxIndex, uint64_t& maxIndexFace)
{
    auto truncated = [&]() {
        return IoError(fmt::format("{}: the file ends in {} {} of {}{} (truncated file?)", path, escaped(e.name), i,
                                   e.count, src.where()));
    };
    c[0] = c[1] = c[2] = 0;
    face.clear();
    for (size_t j = 0; j < e.properties.size(); ++j) {
        const Property& p = e.properties[j];
        if (!p.list) {
            int axis = -1;
            for (int a = 0; a < 3 && l.vertex; ++a)
                if (int(j) == l.axisOf[a]) axis = a;
            if (!(axis >= 0 ? src.value(p.type, c[axis]) : src.skip(p.type))) throw truncated();
            continue;
        }
        int64_t n = 0;
        if (!src.integer(p.countType, n)) throw truncated();
        if (n < 0) throw IoError(fmt::format("{}: {} {} has a list of {} items{}", path, escaped(e.name), i, n, src.where()));
        if (uint64_t(n) > src.remaining()) // an item takes a byte or more
            throw IoError(fmt::format("{}: {} {} has a list of {} items, more than the rest of the file holds{} "
                                      "(truncated file?)",
                                      path, escaped(e.name), i, n, src.where()));
        if (int(j) != l.indices) {
            for (int64_t k = 0; k < n; ++k)
                if (!src.skip(p.type)) throw truncated();
            continue;
        }
        face.clear();
        for (int64_t k = 0; k < n; ++k) {
            int64_t v = 0;
            if (!src.integer(p.type, v)) throw truncated();
            if (v < 0 || v > int64_t(UINT32_MAX))
                throw IoError(fmt::format("{}: face {} uses vertex index {}{}", path, i, v, src.where()));
            if (uint64_t(v) >= maxIndex) maxIndex = uint64_t(v) + 1, maxIndexFace = i;
            face.push_back(uint32_t(v));
        }
    }
    if (l.vertex)
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(c[a]))
                throw IoError(fmt::format("{}: vertex {} has a non-finite coordinate ({}, {}, {}){}", path, i, c[0], c[1],
                                          c[2], src.where()));
}

/// Fan triangulation; a face with fewer than 3 corners still covers its points.
void addFace(const std::vector<uint32_t>& face, std::vector<std::array<uint32_t, 3>>& triangles)
{
    if (face.empty()) return;
    auto u = [&](size_t k) { return face[std::min(k, face.size() - 1)]; };
    const size_t fans = face.size() < 3 ? 1 : face.size() - 2;
    for (size_t k = 0; k < fans; ++k) triangles.push_back({u(0), u(k + 1), u(k + 2)});
}

/// Checks, before any allocation, that the declared counts fit the body.
template <typename Source>
void checkCounts(const std::string& path, const Header& h, const Source& src)
{
    // Each value takes a byte or more (with its separator, in ASCII): counts
    // that the rest of the file cannot hold are refused before any allocation.
    double least = 0;
    for (const Element& e : h.elements) {
        double bytesEach = 0;
        for (const Property& p : e.properties)
            bytesEach += h.format == Header::Ascii ? 2.0 : double(sizeOf(p.list ? p.countType : p.type));
        least += double(e.count) * bytesEach;
        if (least > double(src.remaining()) + 1)
            throw IoError(fmt::format("{}: the header declares {} '{}' elements, more than the file's {} bytes can hold "
                                      "(truncated or corrupt file)",
                                      path, e.count, escaped(e.name), h.bodyOffset + src.remaining()));
    }
}

/// Reads every element's values into the mesh: vertex x, y, z and face index lists.
template <typename Source>
void readBody(const std::string& path, const Header& h, Source& src, TriangleMesh& mesh)
{
    checkCounts(path, h, src);
    bool haveVertices = false;
    uint64_t maxIndex = 0, maxIndexFace = 0; // faces may precede vertices: indices are checked at the end
    std::vector<uint32_t> face;
    for (const Element& e : h.elements) {
        const Layout l = layoutOf(path, e);
        if (l.vertex) {
            if (haveVertices) throw IoError(fmt::format("{}: more than one vertex element", path));
            haveVertices = true;
            for (int a = 0; a < 3; ++a)
                if (l.axisOf[a] < 0)
                    throw IoError(fmt::format("{}: the vertex element has no scalar '{}' property", path, "xyz"[a]));
            if (e.count > UINT32_MAX)
                throw IoError(fmt::format("{}: {} vertices are more than 32-bit indices address", path, e.count));
            mesh.positions.reserve(size_t(e.count));
        }
        if (l.face && l.indices < 0) throw IoError(fmt::format("{}: the face element has no 'vertex_indices' list", path));
        if (e.properties.empty()) continue; // nothing of it is stored, however many there are
        for (uint64_t i = 0; i < e.count; ++i) {
            double c[3];
            readRecord(path, e, l, i, src, c, face, maxIndex, maxIndexFace);
            if (l.vertex) mesh.positions.push_back({c[0], c[1], c[2]});
            if (l.face) addFace(face, mesh.triangles);
        }
    }
    if (maxIndex > mesh.positions.size())
        throw IoError(fmt::format("{}: face {} uses vertex index {}, but the file has {} vertices", path, maxIndexFace,
                                  maxIndex - 1, mesh.positions.size()));
}

/// Where each record of an ASCII body starts, one a line (and where the last
/// line ends). Empty when the body has fewer lines than records (the
/// one-piece reader then names what is wrong).
std::vector<size_t> recordStarts(const Header& h, std::string_view body)
{
    uint64_t records = 0;
    for (const Element& e : h.elements)
        if (!e.properties.empty()) records += e.count;
    if (records > body.size()) return {};
    std::vector<size_t> starts;
    starts.reserve(size_t(records) + 1);
    size_t at = 0;
    while (starts.size() <= records && at < body.size()) {
        starts.push_back(at);
        const void* nl = std::memchr(body.data() + at, '\n', body.size() - at);
        at = nl ? size_t(static_cast<const char*>(nl) - body.data()) + 1 : body.size();
    }
    if (starts.size() < records) return {};
    if (starts.size() == records) starts.push_back(body.size()); // the last line runs to the end
    starts.resize(size_t(records) + 1);
    starts.back() = std::min(starts.back(), body.size());
    return starts;
}

/// An ASCII body read in parallel, records cut out by recordStarts: the same
/// mesh as readBody, or false (nothing kept) for anything readBody would
/// refuse or a record that is not exactly one line, which readBody then names.
bool readBodyInParallel(const std::string& path, const Header& h, std::string_view body, TriangleMesh& mesh)
{
    const std::vector<size_t> starts = recordStarts(h, body);
    if (starts.empty()) return false;
    int vertexElements = 0;
    try {
        for (const Element& e : h.elements) {
            const Layout l = layoutOf(path, e);
            vertexElements += l.vertex;
            if (l.vertex && (l.axisOf[0] < 0 || l.axisOf[1] < 0 || l.axisOf[2] < 0 || e.count > UINT32_MAX))
                return false;
            if (l.face && l.indices < 0) return false;
        }
    } catch (const Error&) {
        return false; // named by the one-piece reader, in its order
    }
    if (vertexElements > 1) return false;
    std::atomic<bool> failed{false};
    std::atomic<uint64_t> maxIndex{0};
    size_t record = 0; // the element's first record among starts
    for (const Element& e : h.elements) {
        if (e.properties.empty()) continue;
        const Layout l = layoutOf(path, e);
        const size_t first = record;
        record += size_t(e.count);
        // Other elements are read too (and dropped): the one-piece reader refuses their malformed values.
        if (l.vertex) mesh.positions.resize(size_t(e.count));
        constexpr size_t kRecords = 1 << 14;
        const size_t tasks = (size_t(e.count) + kRecords - 1) / kRecords;
        std::vector<std::vector<std::array<uint32_t, 3>>> triangles(l.face ? tasks : 0);
        tbb::parallel_for(size_t(0), tasks, [&](size_t t) {
            std::vector<uint32_t> face;
            uint64_t localMax = 0, maxFace = 0;
            try {
                for (size_t i = t * kRecords; i < std::min<size_t>(size_t(e.count), (t + 1) * kRecords); ++i) {
                    const std::string_view bytes = body.substr(starts[first + i], starts[first + i + 1] - starts[first + i]);
                    double c[3];
                    AsciiSource src(path, bytes, 0);
                    readRecord(path, e, l, i, src, c, face, localMax, maxFace);
                    double extra = 0;
                    if (src.value(Type::Float64, extra)) throw IoError("more values on the line than the record");
                    if (l.vertex) mesh.positions[i] = {c[0], c[1], c[2]};
                    if (l.face) addFace(face, triangles[t]);
                }
            } catch (const Error&) {
                failed = true;
            }
            for (uint64_t now = maxIndex; localMax > now && !maxIndex.compare_exchange_weak(now, localMax);) {
            }
        });
        if (failed) break;
        size_t total = 0;
        for (const auto& part : triangles) total += part.size();
        mesh.triangles.reserve(mesh.triangles.size() + total);
        for (const auto& part : triangles) mesh.triangles.insert(mesh.triangles.end(), part.begin(), part.end());
    }
    if (failed || maxIndex > mesh.positions.size()) {
        mesh.positions.clear();
        mesh.triangles.clear();
        return false;
    }
    return true;
}

} // namespace

TriangleMesh readPly(const std::string& path, const std::string& bytes, size_t parallelFrom, bool* inParallel)
{
    if (inParallel) *inParallel = false;
    const Header h = readHeader(path, bytes);
    const std::string_view body(bytes.data() + h.bodyOffset, bytes.size() - h.bodyOffset);
    TriangleMesh mesh;
    mesh.source = path;
    // Large ASCII bodies are cut into records (lines) and read in parallel;
    // anything that reader does not take is read again in one piece, which
    // names it. Binary bodies stay one piece: they decode at memory speed
    // (80 ms for 25 MB on 2 cores), and cutting them needs a walk over every
    // list first, which cost as much as it saved there.
    if (h.format == Header::Ascii && body.size() >= parallelFrom) {
        const AsciiSource all(path, body, h.bodyLine);
        checkCounts(path, h, all);
        if (readBodyInParallel(path, h, body, mesh)) {
            if (inParallel) *inParallel = true;
            return mesh;
        }
    }
    if (h.format == Header::Ascii) {
        AsciiSource src(path, body, h.bodyLine);
        readBody(path, h, src, mesh);
    } else {
        BinarySource src(body, h.format == Header::Big);
        readBody(path, h, src, mesh);
    }
    return mesh;
}

} // namespace svo::detail
