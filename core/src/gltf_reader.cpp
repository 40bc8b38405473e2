#include "gltf_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <string_view>
#include <vector>

// tinygltf's implementation lives in this file only. Images are not decoded
// (svo needs geometry): no stb, no external image files.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <draco/compression/decode.h>

#include "svo/core/error.h"

namespace svo::detail {
namespace {

constexpr int kComponentByte = 5120, kComponentUByte = 5121, kComponentShort = 5122, kComponentUShort = 5123,
              kComponentUInt = 5125, kComponentFloat = 5126;

/// A 4x4 matrix, column-major as glTF stores it: m[4 * column + row].
using Mat4 = std::array<double, 16>;

constexpr Mat4 kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Mat4 multiply(const Mat4& a, const Mat4& b)
{
    Mat4 c{};
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[size_t(4 * k + row)] * b[size_t(4 * col + k)];
            c[size_t(4 * col + row)] = s;
        }
    return c;
}

Vec3d transformPoint(const Mat4& m, const Vec3d& p)
{
    return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
            m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

/// The determinant of the upper 3x3: negative for a transform that mirrors.
double linearDeterminant(const Mat4& m)
{
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

/// One line from tinygltf's messages, which end each problem with '\n'.
std::string oneLine(std::string text)
{
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
    std::replace(text.begin(), text.end(), '\n', ';');
    return text;
}

/// The deepest nesting of arrays and objects in JSON text, strings skipped:
/// tinygltf turns extras and extensions into values recursively, so a file
/// nested deeper than any real one is refused before it can exhaust the stack.
size_t jsonDepth(const char* p, size_t size)
{
    size_t depth = 0, deepest = 0;
    bool inString = false;
    for (const char* end = p + size; p < end; ++p) {
        if (inString) {
            if (*p == '\\') ++p;
            else if (*p == '"') inString = false;
        } else if (*p == '"') inString = true;
        else if (*p == '[' || *p == '{') deepest = std::max(deepest, ++depth);
        else if ((*p == ']' || *p == '}') && depth) --depth;
    }
    return deepest;
}

uint32_t littleU32(const std::string& bytes, size_t at)
{
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | uint8_t(bytes[at + size_t(i)]);
    return v;
}

/// The filesystem tinygltf reads external buffers through: plain paths (no
/// shell expansion), no writes, and none at all when the options say so.
struct FileAccess {
    static bool exists(const std::string& path, void* self)
    {
        if (!static_cast<const GltfReadOptions*>(self)->externalFiles) return false;
        std::error_code ec;
        return std::filesystem::is_regular_file(path, ec);
    }
    static std::string expand(const std::string& path, void*) { return path; }
    static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self)
    {
        if (!exists(path, self)) {
            if (err) *err += path + ": no such file\n";
            return false;
        }
        std::ifstream in(path, std::ios::binary);
        std::error_code ec;
        const auto size = std::filesystem::file_size(path, ec);
        if (!in || ec) {
            if (err) *err += path + ": cannot be read\n";
            return false;
        }
        out->resize(size_t(size));
        in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size));
        if (!in) {
            if (err) *err += path + ": read error\n";
            return false;
        }
        return true;
    }
    static bool write(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }
};

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*)
{
    return true; // textures do not change which voxels a mesh covers
}

/// One primitive in the file's own coordinates.
struct Primitive {
    std::vector<Vec3d> positions;
    std::vector<Vec3f> colors; ///< COLOR_0's rgb, one per position; empty without COLOR_0
    Vec3f baseColor{1, 1, 1};  ///< the material's baseColorFactor
    std::vector<std::array<uint32_t, 3>> triangles;
};

/// Reads a parsed model's scene into one mesh; every index and byte range
/// the file gives is checked before it is used.
class SceneReader {
public:
    SceneReader(const std::string& path, const tinygltf::Model& model, const GltfReadOptions& options)
        : path_(path), model_(model), options_(options)
    {
    }

    TriangleMesh read()
    {
        if (model_.asset.version.rfind("2.", 0) != 0)
            fail(fmt::format("glTF version '{}'; svo reads glTF 2.0", model_.asset.version));
        checkExtensions();
        mesh_.source = path_;
        std::vector<int> roots;
        if (model_.scenes.empty()) {
            roots = rootNodes();
        } else {
            const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
            if (size_t(scene) >= model_.scenes.size())
                fail(fmt::format("the default scene is {}, but the file has {} scenes", scene, model_.scenes.size()));
            roots = model_.scenes[size_t(scene)].nodes;
        }
        placeNodes(roots);
        finishColors();
        if (mesh_.triangles.empty() && skipped_)
            fail(fmt::format("the scene has no triangles, only {} point or line primitives", skipped_));
        if (skipped_)
            mesh_.warnings.push_back(
                fmt::format("{}: {} point or line primitives are skipped (svo voxelizes triangles)", path_, skipped_));
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw IoError(fmt::format("{}: {}", path_, what)); }

    void checkExtensions() const
    {
        for (const std::string& e : model_.extensionsRequired) {
            if (e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression")
                fail(fmt::format("the file requires {} (meshopt-compressed buffers), which svo does not decode; "
                                 "decompress it first (e.g. gltfpack -noq, or gltf-transform copy)",
                                 e));
            if (e == "EXT_mesh_gpu_instancing")
                fail(fmt::format("the file requires {}, which svo does not read", e));
        }
    }

    /// Nodes no other node lists as a child, for a file without scenes.
    std::vector<int> rootNodes() const
    {
        std::vector<char> child(model_.nodes.size(), 0);
        for (const tinygltf::Node& n : model_.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = 1;
        std::vector<int> roots;
        for (size_t i = 0; i < child.size(); ++i)
            if (!child[i]) roots.push_back(int(i));
        return roots;
    }

    Mat4 localMatrix(const tinygltf::Node& node, size_t index) const
    {
        auto finite = [&](const std::vector<double>& v, size_t n, const char* what) {
            if (!v.empty() && v.size() != n)
                fail(fmt::format("node {}: {} has {} numbers, not {}", index, what, v.size(), n));
            for (double x : v)
                if (!std::isfinite(x)) fail(fmt::format("node {}: {} holds a non-finite number", index, what));
            return !v.empty();
        };
        if (finite(node.matrix, 16, "matrix")) {
            Mat4 m;
            std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
            return m;
        }
        Mat4 m = kIdentity;
        if (finite(node.rotation, 4, "rotation")) {
            // A unit quaternion (x, y, z, w) as a rotation matrix.
            const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
            m = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
                 2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
                 2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
                 0,                       0,                       0,                       1};
        }
        if (finite(node.scale, 3, "scale"))
            for (int col = 0; col < 3; ++col)
                for (int row = 0; row < 3; ++row) m[size_t(4 * col + row)] *= node.scale[size_t(col)];
        if (finite(node.translation, 3, "translation"))
            for (int row = 0; row < 3; ++row) m[size_t(12 + row)] = node.translation[size_t(row)];
        return m;
    }

    /// Walks the node trees below `roots` (without recursion: a chain of
    /// nodes is as deep as the file is long) and places each mesh it meets.
    void placeNodes(const std::vector<int>& roots)
    {
        std::vector<char> seen(model_.nodes.size(), 0);
        std::vector<std::pair<int, Mat4>> stack;
        for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, kIdentity});
        while (!stack.empty()) {
            const auto [index, parent] = stack.back();
            stack.pop_back();
            if (index < 0 || size_t(index) >= model_.nodes.size())
                fail(fmt::format("node {} is named, but the file has {} nodes", index, model_.nodes.size()));
            if (seen[size_t(index)])
                fail(fmt::format("node {} is reached twice (glTF's nodes form trees)", index));
            seen[size_t(index)] = 1;
            const tinygltf::Node& node = model_.nodes[size_t(index)];
            const Mat4 world = multiply(parent, localMatrix(node, size_t(index)));
            if (node.mesh >= 0) placeMesh(node.mesh, world);
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
        }
    }

    void placeMesh(int meshIndex, const Mat4& world)
    {
        if (size_t(meshIndex) >= model_.meshes.size())
            fail(fmt::format("mesh {} is named, but the file has {} meshes", meshIndex, model_.meshes.size()));
        const bool mirrored = linearDeterminant(world) < 0;
        const auto& prims = model_.meshes[size_t(meshIndex)].primitives;
        for (size_t p = 0; p < prims.size(); ++p) {
            const Primitive* prim = primitive(meshIndex, p);
            if (!prim) continue;
            const uint64_t base = mesh_.positions.size();
            if (base + prim->positions.size() > options_.maxVertices)
                fail(fmt::format("the scene places more than {} vertices, more than svo reads into one mesh",
                                 options_.maxVertices));
            for (const Vec3d& v : prim->positions) mesh_.positions.push_back(transformPoint(world, v));
            for (const auto& t : prim->triangles) {
                const uint32_t b = uint32_t(base);
                mesh_.triangles.push_back(mirrored ? std::array<uint32_t, 3>{t[0] + b, t[2] + b, t[1] + b}
                                                   : std::array<uint32_t, 3>{t[0] + b, t[1] + b, t[2] + b});
            }
            placed_.push_back({prim, prim->positions.size()});
        }
    }

    /// Colours once every vertex is placed: glTF's base colour where any
    /// primitive has one other than white, none otherwise.
    void finishColors()
    {
        const Vec3f white{1, 1, 1};
        const bool any = std::any_of(placed_.begin(), placed_.end(), [&](const auto& p) {
            const Vec3f& c = p.first->baseColor;
            return !p.first->colors.empty() || c.x != white.x || c.y != white.y || c.z != white.z;
        });
        if (!any) return;
        mesh_.colors.reserve(mesh_.positions.size());
        for (const auto& [prim, n] : placed_)
            for (size_t v = 0; v < n; ++v) {
                const Vec3f c = prim->colors.empty() ? white : prim->colors[v];
                mesh_.colors.push_back({c.x * prim->baseColor.x, c.y * prim->baseColor.y, c.z * prim->baseColor.z});
            }
    }

    /// Primitive p of mesh m, decoded once however many nodes place it;
    /// null for points and lines.
    const Primitive* primitive(int m, size_t p)
    {
        auto& slot = cache_[{m, p}];
        if (slot.first) return slot.second.get();
        slot.first = true;
        const tinygltf::Primitive& prim = model_.meshes[size_t(m)].primitives[p];
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode < TINYGLTF_MODE_TRIANGLES) {
            ++skipped_;
            return nullptr;
        }
        if (mode > TINYGLTF_MODE_TRIANGLE_FAN) fail(fmt::format("mesh {} primitive {}: unknown mode {}", m, p, mode));
        const std::string where = fmt::format("mesh {} primitive {}", m, p);
        auto out = std::make_unique<Primitive>();
        std::vector<uint32_t> corners;
        const auto draco = prim.extensions.find("KHR_draco_mesh_compression");
        if (draco != prim.extensions.end()) {
            decodeDraco(where, draco->second, *out, corners);
        } else {
            const auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) fail(where + " has no POSITION");
            const std::vector<double> xyz = accessorValues(pos->second, TINYGLTF_TYPE_VEC3, false, where + " POSITION");
            out->positions.resize(xyz.size() / 3);
            for (size_t v = 0; v < out->positions.size(); ++v)
                out->positions[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
            const auto col = prim.attributes.find("COLOR_0");
            if (col != prim.attributes.end()) {
                const std::vector<double> rgb = colorValues(col->second, out->positions.size(), where);
                const size_t n = model_.accessors[size_t(col->second)].type; // 3 or 4 numbers a colour
                out->colors.resize(out->positions.size());
                for (size_t v = 0; v < out->colors.size(); ++v)
                    out->colors[v] = {float(rgb[n * v]), float(rgb[n * v + 1]), float(rgb[n * v + 2])};
            }
            if (prim.indices >= 0) {
                const int type = size_t(prim.indices) < model_.accessors.size()
                                     ? model_.accessors[size_t(prim.indices)].componentType
                                     : kComponentUInt; // accessorValues names the missing accessor
                if (type != kComponentUByte && type != kComponentUShort && type != kComponentUInt)
                    fail(fmt::format("{}: indices of component type {} (glTF's are unsigned integers)", where, type));
                const std::vector<double> idx = accessorValues(prim.indices, TINYGLTF_TYPE_SCALAR, false, where + " indices");
                corners.resize(idx.size());
                for (size_t i = 0; i < idx.size(); ++i) {
                    if (!(idx[i] >= 0 && idx[i] < double(out->positions.size())))
                        fail(fmt::format("{}: index {} is {}, but the primitive has {} vertices", where, i, idx[i],
                                         out->positions.size()));
                    corners[i] = uint32_t(idx[i]);
                }
            } else {
                corners.resize(out->positions.size());
                for (size_t i = 0; i < corners.size(); ++i) corners[i] = uint32_t(i);
            }
        }
        // Every primitive decoded is placed at least once: the vertices
        // decoded so far count against the same limit as those placed.
        decoded_ += out->positions.size();
        if (decoded_ > options_.maxVertices)
            fail(fmt::format("the scene's meshes hold more than {} vertices, more than svo reads into one mesh",
                             options_.maxVertices));
        out->baseColor = baseColor(prim.material, where);
        assemble(mode, corners, where, *out);
        slot.second = std::move(out);
        return slot.second.get();
    }

    /// Triangles from the corner list as `mode` orders it (glTF 2.0, 3.7.2.1).
    void assemble(int mode, const std::vector<uint32_t>& c, const std::string& where, Primitive& out) const
    {
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (c.size() % 3)
                fail(fmt::format("{}: {} corners do not make whole triangles", where, c.size()));
            out.triangles.reserve(c.size() / 3);
            for (size_t i = 0; i + 2 < c.size(); i += 3) out.triangles.push_back({c[i], c[i + 1], c[i + 2]});
        } else if (c.size() >= 3) {
            out.triangles.reserve(c.size() - 2);
            for (size_t i = 0; i + 2 < c.size(); ++i)
                if (mode == TINYGLTF_MODE_TRIANGLE_FAN) out.triangles.push_back({c[i + 1], c[i + 2], c[0]});
                else out.triangles.push_back({c[i + i % 2], c[i + 1 - i % 2], c[i + 2]}); // every other one turned
        }
    }

    Vec3f baseColor(int material, const std::string& where) const
    {
        if (material < 0) return {1, 1, 1};
        if (size_t(material) >= model_.materials.size())
            fail(fmt::format("{}: material {} is named, but the file has {}", where, material, model_.materials.size()));
        const std::vector<double>& f = model_.materials[size_t(material)].pbrMetallicRoughness.baseColorFactor;
        if (f.size() != 4 || !std::all_of(f.begin(), f.end(), [](double x) { return std::isfinite(x); }))
            fail(fmt::format("{}: material {} has a malformed baseColorFactor", where, material));
        return {float(f[0]), float(f[1]), float(f[2])};
    }

    std::vector<double> colorValues(int accessor, size_t vertices, const std::string& where)
    {
        if (accessor < 0 || size_t(accessor) >= model_.accessors.size())
            fail(fmt::format("{} COLOR_0: accessor {} is named, but the file has {}", where, accessor,
                             model_.accessors.size()));
        const int type = model_.accessors[size_t(accessor)].type;
        if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
            fail(fmt::format("{} COLOR_0: accessor {} is {}, not VEC3 or VEC4", where, accessor, typeName(type)));
        // Integer colours are normalized in glTF, flagged or not.
        std::vector<double> rgb = accessorValues(accessor, type, true, where + " COLOR_0");
        if (rgb.size() / size_t(type) != vertices)
            fail(fmt::format("{}: COLOR_0 has {} values for {} vertices", where, rgb.size() / size_t(type), vertices));
        return rgb;
    }

    static std::string typeName(int type)
    {
        switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return fmt::format("of unknown type {}", type);
        }
    }

    static size_t componentSize(int componentType)
    {
        switch (componentType) {
        case kComponentByte:
        case kComponentUByte: return 1;
        case kComponentShort:
        case kComponentUShort: return 2;
        case kComponentUInt:
        case kComponentFloat: return 4;
        default: return 0;
        }
    }

    /// One component at `p`, normalized to [0, 1] or [-1, 1] when asked.
    static double component(const unsigned char* p, int type, bool normalized)
    {
        auto get = [p](auto v) {
            std::memcpy(&v, p, sizeof v);
            return v;
        };
        switch (type) {
        case kComponentByte: return normalized ? std::max(get(int8_t()) / 127.0, -1.0) : get(int8_t());
        case kComponentUByte: return normalized ? get(uint8_t()) / 255.0 : get(uint8_t());
        case kComponentShort: return normalized ? std::max(get(int16_t()) / 32767.0, -1.0) : get(int16_t());
        case kComponentUShort: return normalized ? get(uint16_t()) / 65535.0 : get(uint16_t());
        case kComponentUInt: return normalized ? get(uint32_t()) / 4294967295.0 : get(uint32_t());
        default: return double(get(float()));
        }
    }

    /// The bytes of buffer view `view`, checked against its buffer.
    std::pair<const unsigned char*, size_t> viewBytes(int view, const std::string& what) const
    {
        if (view < 0 || size_t(view) >= model_.bufferViews.size())
            fail(fmt::format("{}: buffer view {} is named, but the file has {}", what, view, model_.bufferViews.size()));
        const tinygltf::BufferView& bv = model_.bufferViews[size_t(view)];
        if (bv.extensions.count("EXT_meshopt_compression") || bv.extensions.count("KHR_meshopt_compression")) {
            const bool fallback = bv.buffer >= 0 && size_t(bv.buffer) < model_.buffers.size() &&
                                  model_.buffers[size_t(bv.buffer)].data.size() >= bv.byteOffset + bv.byteLength;
            if (!fallback)
                fail(fmt::format("{}: buffer view {} is meshopt-compressed, which svo does not decode; decompress "
                                 "the file first (e.g. gltfpack -noq, or gltf-transform copy)",
                                 what, view));
        }
        if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
            fail(fmt::format("{}: buffer {} is named, but the file has {}", what, bv.buffer, model_.buffers.size()));
        const std::vector<unsigned char>& data = model_.buffers[size_t(bv.buffer)].data;
        if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
            fail(fmt::format("{}: buffer view {} ({} bytes from byte {}) runs past its buffer's {} bytes", what, view,
                             bv.byteLength, bv.byteOffset, data.size()));
        return {data.data() + bv.byteOffset, bv.byteLength};
    }

    /// `count` elements of `components` numbers each from a view at
    /// `offset`, `stride` bytes apart (0: packed), appended to `out`.
    void readElements(int view, size_t offset, size_t stride, size_t count, size_t components, int componentType,
                      bool normalized, const std::string& what, std::vector<double>& out) const
    {
        const size_t size = componentSize(componentType);
        if (!size) fail(fmt::format("{}: unknown component type {}", what, componentType));
        const size_t element = size * components;
        if (stride == 0) stride = element;
        if (stride < element) fail(fmt::format("{}: byte stride {} is less than an element's {} bytes", what, stride, element));
        const auto [bytes, length] = viewBytes(view, what);
        if (count && (offset > length || count - 1 > (length - offset) / stride ||
                      (count - 1) * stride + element > length - offset))
            fail(fmt::format("{}: {} elements from byte {} run past buffer view {}'s {} bytes", what, count, offset, view,
                             length));
        out.reserve(out.size() + count * components);
        for (size_t i = 0; i < count; ++i)
            for (size_t k = 0; k < components; ++k)
                out.push_back(component(bytes + offset + i * stride + k * size, componentType, normalized));
    }

    /// An accessor's values, sparse substitutions applied, checked to be of
    /// type `type` (TINYGLTF_TYPE_*) and finite.
    std::vector<double> accessorValues(int index, int type, bool normalize, const std::string& what) const
    {
        if (index < 0 || size_t(index) >= model_.accessors.size())
            fail(fmt::format("{}: accessor {} is named, but the file has {}", what, index, model_.accessors.size()));
        const tinygltf::Accessor& a = model_.accessors[size_t(index)];
        if (a.type != type)
            fail(fmt::format("{}: accessor {} is {}, not {}", what, index, typeName(a.type), typeName(type)));
        const size_t n = type == TINYGLTF_TYPE_SCALAR ? 1 : size_t(type);
        const bool normalized = normalize || a.normalized;
        std::vector<double> values;
        if (a.bufferView >= 0) {
            const int stride = model_.bufferViews.size() > size_t(a.bufferView)
                                   ? model_.bufferViews[size_t(a.bufferView)].byteStride
                                   : 0;
            readElements(a.bufferView, a.byteOffset, size_t(std::max(stride, 0)), a.count, n, a.componentType,
                         normalized, what, values);
        } else {
            // No data: zeros (then the sparse values), as glTF defines.
            if (a.count > options_.maxVertices)
                fail(fmt::format("{}: accessor {} has {} elements and no data", what, index, a.count));
            if (!componentSize(a.componentType)) fail(fmt::format("{}: unknown component type {}", what, a.componentType));
            values.assign(a.count * n, 0.0);
        }
        if (a.sparse.isSparse) applySparse(a, n, normalized, what, values);
        for (size_t i = 0; i < values.size(); ++i)
            if (!std::isfinite(values[i])) fail(fmt::format("{}: element {} is not finite", what, i / n));
        return values;
    }

    void applySparse(const tinygltf::Accessor& a, size_t n, bool normalized, const std::string& what,
                     std::vector<double>& values) const
    {
        const auto& s = a.sparse;
        if (s.count < 0 || size_t(s.count) > a.count || s.indices.byteOffset < 0 || s.values.byteOffset < 0)
            fail(fmt::format("{}: malformed sparse accessor ({} substitutions for {} elements)", what, s.count, a.count));
        if (s.indices.componentType != kComponentUByte && s.indices.componentType != kComponentUShort &&
            s.indices.componentType != kComponentUInt)
            fail(fmt::format("{}: sparse indices of component type {}", what, s.indices.componentType));
        std::vector<double> at, sub;
        readElements(s.indices.bufferView, size_t(s.indices.byteOffset), 0, size_t(s.count), 1, s.indices.componentType,
                     false, what + " sparse indices", at);
        readElements(s.values.bufferView, size_t(s.values.byteOffset), 0, size_t(s.count), n, a.componentType, normalized,
                     what + " sparse values", sub);
        for (size_t i = 0; i < at.size(); ++i) {
            if (!(at[i] < double(a.count)))
                fail(fmt::format("{}: sparse index {} is {}, but the accessor has {} elements", what, i, at[i], a.count));
            std::copy_n(sub.begin() + std::ptrdiff_t(i * n), n, values.begin() + std::ptrdiff_t(size_t(at[i]) * n));
        }
    }

    /// A Draco-compressed primitive (KHR_draco_mesh_compression): positions,
    /// COLOR_0 when compressed with them, and the triangle corners.
    void decodeDraco(const std::string& where, const tinygltf::Value& ext, Primitive& out,
                     std::vector<uint32_t>& corners) const
    {
        auto number = [&](const tinygltf::Value& v, const char* what) {
            const double x = v.IsNumber() ? v.GetNumberAsDouble() : -1;
            if (!(x >= 0 && x <= double(INT32_MAX)) || x != std::floor(x))
                fail(fmt::format("{}: KHR_draco_mesh_compression has no valid {}", where, what));
            return int(x);
        };
        if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
            fail(where + ": KHR_draco_mesh_compression without attributes");
        const auto [bytes, length] = viewBytes(number(ext.Get("bufferView"), "bufferView"), where + " Draco data");
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char*>(bytes), length);
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok()) fail(fmt::format("{}: Draco data cannot be decoded: {}", where, decoded.status().error_msg_string()));
        const draco::Mesh& dm = *decoded.value();
        const tinygltf::Value& attributes = ext.Get("attributes");
        if (!attributes.Has("POSITION")) fail(where + ": KHR_draco_mesh_compression has no POSITION");
        const uint32_t points = dm.num_points();
        if (decoded_ + points > options_.maxVertices)
            fail(fmt::format("{}: Draco data of {} points, more than svo reads into one mesh", where, points));
        out.positions = dracoAttribute(dm, number(attributes.Get("POSITION"), "POSITION"), 3, false, where);
        if (attributes.Has("COLOR_0")) {
            const auto rgb = dracoAttribute(dm, number(attributes.Get("COLOR_0"), "COLOR_0"), 3, true, where);
            out.colors.reserve(rgb.size());
            for (const Vec3d& c : rgb) out.colors.push_back({float(c.x), float(c.y), float(c.z)});
        }
        corners.reserve(size_t(dm.num_faces()) * 3);
        for (uint32_t f = 0; f < dm.num_faces(); ++f)
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = dm.face(draco::FaceIndex(f))[k].value();
                if (v >= points) fail(fmt::format("{}: Draco face {} uses point {} of {}", where, f, v, points));
                corners.push_back(v);
            }
    }

    /// The first three components of Draco attribute `id` at every point;
    /// integers normalized when `color` (glTF's integer colours are).
    std::vector<Vec3d> dracoAttribute(const draco::Mesh& dm, int id, int components, bool color,
                                  const std::string& where) const
    {
        const draco::PointAttribute* att = dm.GetAttributeByUniqueId(uint32_t(id));
        if (!att) fail(fmt::format("{}: Draco data has no attribute {}", where, id));
        if (att->num_components() < components)
            fail(fmt::format("{}: Draco attribute {} has {} components, not {}", where, id, int(att->num_components()),
                             components));
        const bool integer = att->data_type() != draco::DT_FLOAT32 && att->data_type() != draco::DT_FLOAT64;
        double scale = 1;
        if (color && integer && !att->normalized()) {
            switch (att->data_type()) {
            case draco::DT_UINT8: scale = 1 / 255.0; break;
            case draco::DT_UINT16: scale = 1 / 65535.0; break;
            default: fail(fmt::format("{}: Draco colour attribute {} is of a type glTF does not allow", where, id));
            }
        }
        std::vector<Vec3d> values(dm.num_points());
        std::vector<double> c(att->num_components());
        for (uint32_t p = 0; p < dm.num_points(); ++p) {
            const draco::AttributeValueIndex i = att->mapped_index(draco::PointIndex(p));
            if (i.value() >= att->size() || !att->ConvertValue<double>(i, att->num_components(), c.data()))
                fail(fmt::format("{}: Draco attribute {} has no value for point {}", where, id, p));
            for (int k = 0; k < 3; ++k) {
                if (!std::isfinite(c[size_t(k)])) fail(fmt::format("{}: Draco point {} is not finite", where, p));
                values[p][k] = c[size_t(k)] * scale;
            }
        }
        return values;
    }

    const std::string& path_;
    const tinygltf::Model& model_;
    const GltfReadOptions& options_;
    TriangleMesh mesh_;
    std::map<std::pair<int, size_t>, std::pair<bool, std::unique_ptr<Primitive>>> cache_;
    std::vector<std::pair<const Primitive*, size_t>> placed_; ///< each placed primitive and its vertex count
    size_t skipped_ = 0;
    uint64_t decoded_ = 0; ///< vertices of the primitives decoded so far
};

/// The JSON with `indices` removed from KHR_draco_mesh_compression
/// primitives, whose corners come from the Draco data: tinygltf, built
/// without its own Draco support, refuses an index accessor without a buffer
/// view, which such primitives have. Empty when nothing needs removing (or
/// the JSON is malformed, which tinygltf then reports).
std::string withoutDracoIndices(const char* json, size_t size)
{
    if (std::string_view(json, size).find("KHR_draco_mesh_compression") == std::string_view::npos) return {};
    nlohmann::json doc = nlohmann::json::parse(json, json + size, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return {};
    const auto meshes = doc.find("meshes");
    if (meshes == doc.end() || !meshes->is_array()) return {};
    bool changed = false;
    for (auto& mesh : *meshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (auto& prim : mesh["primitives"]) {
            if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
                !prim["extensions"].contains("KHR_draco_mesh_compression"))
                continue;
            changed = prim.erase("indices") > 0 || changed;
        }
    }
    return changed ? doc.dump() : std::string();
}

/// A .glb whose JSON chunk is `json` instead, its other chunks as they were.
std::string replaceGlbJson(const std::string& bytes, size_t oldJsonSize, std::string json)
{
    json.resize((json.size() + 3) / 4 * 4, ' '); // chunks stay 4-byte aligned
    const size_t rest = 20 + oldJsonSize;
    std::string out = bytes.substr(0, 12);
    auto put = [&out](uint32_t v) {
        for (int i = 0; i < 4; ++i) out += char((v >> (8 * i)) & 0xff);
    };
    out.resize(8);
    const size_t length = littleU32(bytes, 8); // glbJson checked it against the file and the JSON chunk
    put(uint32_t(20 + json.size() + (length - rest)));
    put(uint32_t(json.size()));
    put(0x4E4F534A);
    out += json;
    out.append(bytes, rest, length - rest);
    return out;
}

/// The JSON chunk of a .glb, checked so that a damaged container gets a
/// message of its own rather than tinygltf's "Invalid glTF binary".
std::pair<const char*, size_t> glbJson(const std::string& path, const std::string& bytes)
{
    auto fail = [&](const std::string& what) { return IoError(fmt::format("{}: {}", path, what)); };
    if (bytes.size() < 20) throw fail(fmt::format("a binary glTF needs a 20-byte header, the file has {} bytes", bytes.size()));
    if (littleU32(bytes, 4) != 2)
        throw fail(fmt::format("binary glTF version {}; svo reads version 2", littleU32(bytes, 4)));
    const uint64_t length = littleU32(bytes, 8), json = littleU32(bytes, 12);
    if (length > bytes.size())
        throw fail(fmt::format("truncated: the header says {} bytes, the file has {}", length, bytes.size()));
    if (littleU32(bytes, 16) != 0x4E4F534A) throw fail("the first chunk of a binary glTF is not JSON");
    if (json == 0 || 20 + json > length)
        throw fail(fmt::format("the JSON chunk's {} bytes do not fit in the file's {}", json, length));
    return {bytes.data() + 20, size_t(json)};
}

} // namespace

TriangleMesh readGltf(const std::string& path, const std::string& bytes, const GltfReadOptions& options)
{
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    if (bytes.size() > UINT32_MAX) throw IoError(fmt::format("{}: a glTF file over 4 GiB (glTF's limit)", path));
    const auto [json, jsonSize] = binary ? glbJson(path, bytes) : std::pair{bytes.data(), bytes.size()};
    constexpr size_t kMaxDepth = 200;
    if (jsonDepth(json, jsonSize) > kMaxDepth)
        throw IoError(fmt::format("{}: JSON nested more than {} deep", path, kMaxDepth));

    const std::string edited = withoutDracoIndices(json, jsonSize);
    const std::string glb = binary && !edited.empty() ? replaceGlbJson(bytes, jsonSize, edited) : std::string();
    const std::string& text = !binary && !edited.empty() ? edited : bytes;
    const std::string& container = glb.empty() ? bytes : glb;
    if (std::max(text.size(), container.size()) > UINT32_MAX)
        throw IoError(fmt::format("{}: a glTF file over 4 GiB (glTF's limit)", path));

    tinygltf::TinyGLTF loader;
    GltfReadOptions access = options;
    loader.SetFsCallbacks({&FileAccess::exists, &FileAccess::expand, &FileAccess::read, &FileAccess::write, &access});
    loader.SetImageLoader(&skipImage, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const std::string folder = std::filesystem::path(path).parent_path().string();
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                  reinterpret_cast<const unsigned char*>(container.data()),
                                                  unsigned(container.size()), folder)
                    : loader.LoadASCIIFromString(&model, &err, &warn, text.data(), unsigned(text.size()), folder);
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(fmt::format("{}: malformed glTF: {}", path, oneLine(e.what())));
    }
    if (!ok) throw IoError(fmt::format("{}: not a valid glTF 2.0 file: {}", path, err.empty() ? "unreadable" : oneLine(err)));
    return SceneReader(path, model, options).read();
}

} // namespace svo::detail
