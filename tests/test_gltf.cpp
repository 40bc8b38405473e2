// glTF input: public glTF files voxelize exactly as the same meshes written as
// PLY do (by their source, or by Debian's Assimp, an independent reader);
// node transforms, instancing, mirroring, Draco, strips and fans, colours;
// bad files are one-line errors.
#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "run_shell.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/error.h"
#include "svo/core/grid.h"
#include "svo/core/mesh_io.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace svo;

namespace {

const std::string kData = SVO_TEST_DATA "/gltf/";
const std::string kAssimpModels = "/usr/share/assimp/models/glTF2/";

/// The voxels of two mesh files on the grid the first one gets at a
/// resolution: the same keys. With `sameGrid`, the second gets the same grid
/// by itself (its bounds are bit for bit the first's); a reference written
/// by a tool that transforms in float may differ there in the last bit.
void expectSameVoxels(const std::string& a, const std::string& b, bool sameGrid = true, int64_t resolution = 256)
{
    SCOPED_TRACE(a + " against " + b);
    const TriangleMesh ma = loadMesh(a), mb = loadMesh(b);
    GridRequest request;
    request.resolution = resolution;
    const GridSpec ga = makeGrid(ma, request), gb = makeGrid(mb, request);
    if (sameGrid) {
        ASSERT_EQ(ga.voxelSize, gb.voxelSize);
        ASSERT_EQ(ga.shift, gb.shift);
        ASSERT_EQ(ga.anchor, gb.anchor);
        ASSERT_EQ(ga.dims, gb.dims);
    }
    const std::vector<uint64_t> va = voxelizeCpu(ma, ga).keys, vb = voxelizeCpu(mb, ga).keys;
    EXPECT_GT(va.size(), 0u);
    EXPECT_TRUE(va == vb) << va.size() << " voxels against " << vb.size();
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b)
{
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t i = 0; i < a.positions.size(); ++i)
        for (int k = 0; k < 3; ++k)
            ASSERT_EQ(a.positions[i][k], b.positions[i][k]) << fmt::format("vertex {} axis {}: {} {}", i, k, a.positions[i][k], b.positions[i][k]); // bit for bit
    EXPECT_EQ(a.triangles, b.triangles);
}

template <typename T> void put(std::string& s, T v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }

/// A binary glTF: the JSON and the binary chunk, each padded to 4 bytes.
std::string glb(std::string json, std::string bin)
{
    json.resize((json.size() + 3) / 4 * 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    std::string s = "glTF";
    put<uint32_t>(s, 2);
    put<uint32_t>(s, uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
    put<uint32_t>(s, uint32_t(json.size()));
    put<uint32_t>(s, 0x4E4F534A);
    s += json;
    if (!bin.empty()) {
        put<uint32_t>(s, uint32_t(bin.size()));
        put<uint32_t>(s, 0x004E4942);
        s += bin;
    }
    return s;
}

class Gltf : public ::testing::Test {
protected:
    void expectError(const std::string& path, const std::string& what)
    {
        try {
            loadMesh(path);
            FAIL() << path << " loaded without error";
        } catch (const IoError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(path), std::string::npos) << msg;
            EXPECT_NE(msg.find(what), std::string::npos) << msg << " (wanted: " << what << ")";
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg; // one line
        }
    }
    test::TempDir tmp_{"gltf"};
};

} // namespace

// google/draco's testdata gives one mesh as glTF (with COLOR_0) and as PLY.
TEST_F(Gltf, DracoTestdataGltfVoxelizesAsItsPly)
{
    expectSameVoxels(kData + "test_pos_color.gltf", kData + "test_pos_color.ply");
    expectSameMesh(loadMesh(kData + "test_pos_color.gltf"), loadMesh(kData + "test_pos_color.ply"));
    // Colours: COLOR_0 (normalized bytes) times the material's baseColorFactor
    // (0.75), against the PLY's own bytes (x y z float, r g b a uchar).
    std::ifstream in(kData + "test_pos_color.ply", std::ios::binary);
    const std::string ply((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t body = ply.find("end_header\n") + 11;
    const TriangleMesh mesh = loadMesh(kData + "test_pos_color.gltf");
    ASSERT_EQ(mesh.colors.size(), 114u);
    for (size_t v = 0; v < mesh.colors.size(); ++v)
        for (int k = 0; k < 3; ++k) {
            const uint8_t byte = uint8_t(ply[body + 16 * v + 12 + size_t(k)]);
            ASSERT_EQ(mesh.colors[v][k], float(byte / 255.0) * 0.75f) << v << " " << k;
        }
}

// The same sample (Khronos's Box) as plain and as Draco-compressed .glb.
TEST_F(Gltf, DracoBoxIsThePlainBox)
{
    const TriangleMesh plain = loadMesh(kData + "Box.glb"), draco = loadMesh(kData + "Box_Draco.glb");
    EXPECT_EQ(plain.triangles.size(), 12u);
    expectSameMesh(draco, plain);
    expectSameVoxels(kData + "Box_Draco.glb", kData + "Box.glb");
}

// Debian's assimp-testmodels (Khronos samples, glTF-Asset-Generator files,
// Draco), each written as PLY by Debian's assimp tool with the node
// transforms applied (-ptv): the voxels are the same.
TEST_F(Gltf, PublicFilesVoxelizeAsAssimpWritesThemAsPly)
{
    if (test::runShell("command -v assimp").code != 0 || !fs::exists(kAssimpModels))
        GTEST_SKIP() << "needs assimp-utils and assimp-testmodels (scripts/setup.sh installs them)";
    const std::vector<std::string> files = {
        kAssimpModels + "draco/2CylinderEngine.gltf", // Draco, 30 nodes of rotations and translations
        kAssimpModels + "BoxTextured-glTF-Binary/BoxTextured.glb",
        kAssimpModels + "BoxTextured-glTF-Embedded/BoxTextured.gltf", // data URIs
        kAssimpModels + "cameras/Cameras.gltf",
        kAssimpModels + "ClearCoat-glTF/ClearCoatTest.gltf",
        kAssimpModels + "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
        kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_04.gltf", // strip
        kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf", // fan
        kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf", // triangles
        kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_11.gltf", // strip, uint indices
        kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_12.gltf", // fan, uint indices
        kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_14.gltf", // byte indices
        kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_15.gltf", // short indices
        kAssimpModels + "textureTransform/TextureTransformTest.gltf",
        kData + "Box_Draco.glb",
    };
    for (size_t i = 0; i < files.size(); ++i) {
        const std::string ply = tmp_.path(fmt::format("{}.ply", i));
        const auto run = test::runShell(fmt::format("assimp export '{}' '{}' -ptv", files[i], ply));
        ASSERT_EQ(run.code, 0) << run.out;
        expectSameVoxels(files[i], ply, false);
    }
}

// Points and lines are not voxelized: a file of only those says so.
TEST_F(Gltf, PointAndLinePrimitivesAreSkippedAndSaid)
{
    if (!fs::exists(kAssimpModels)) GTEST_SKIP() << "needs assimp-testmodels (scripts/setup.sh installs it)";
    expectError(kAssimpModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf",
                "no triangles, only 1 point or line primitives");
}

namespace {

/// A mesh's corners as packed floats, its triangles as uint32 indices and,
/// for a copy without indices, the corners of each triangle in order.
struct Buffers {
    std::string bin;
    size_t add(const std::string& bytes)
    {
        const size_t at = bin.size();
        bin += bytes;
        bin.resize((bin.size() + 3) / 4 * 4, '\0');
        return at;
    }
};

} // namespace

#ifdef SVO_CGAL_MESHES
// A CGAL demo mesh in a .glb written here: a node tree with a matrix, a
// rotation quaternion, scales and translations, a mirror, one mesh placed
// twice, a copy without indices and with byte colours, and a second scene
// that is not the default. Every transform is exact in binary, so the
// reference (the float corners moved by hand, written as .off) is exact too.
TEST_F(Gltf, CgalMeshWithNodeTransformsVoxelizesAsTheMovedMesh)
{
    const TriangleMesh cow = loadMesh(std::string(SVO_CGAL_MESHES) + "/cow.off");
    Buffers b;
    std::string pos, idx, soup, colors;
    for (const Vec3d& p : cow.positions) put(pos, float(p.x)), put(pos, float(p.y)), put(pos, float(p.z));
    for (const auto& t : cow.triangles)
        for (uint32_t v : t) {
            put(idx, v);
            const Vec3d& p = cow.positions[v];
            put(soup, float(p.x)), put(soup, float(p.y)), put(soup, float(p.z));
            colors += char(v % 256), colors += char(51), colors += char(255), colors += char(0);
        }
    const size_t nv = cow.positions.size(), nc = 3 * cow.triangles.size();
    const size_t oPos = b.add(pos), oIdx = b.add(idx), oSoup = b.add(soup), oCol = b.add(colors);
    const std::string json = fmt::format(R"({{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 3]}}, {{"nodes": [4]}}],
  "nodes": [
    {{"matrix": [2,0,0,0, 0,2,0,0, 0,0,2,0, 10,-4,0.5,1], "children": [1, 2]}},
    {{"rotation": [0,0,1,0], "translation": [0,0,3], "mesh": 0}},
    {{"scale": [-1,1,1], "mesh": 0}},
    {{"matrix": [0,1,0,0, 0,0,1,0, 1,0,0,0, 0,0,0,1], "mesh": 1}},
    {{"translation": [100,0,0], "mesh": 0}}
  ],
  "meshes": [
    {{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}},
    {{"primitives": [{{"attributes": {{"POSITION": 2, "COLOR_0": 3}}, "mode": 4}}]}}
  ],
  "buffers": [{{"byteLength": {}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": {}, "byteLength": {}}},
    {{"buffer": 0, "byteOffset": {}, "byteLength": {}}},
    {{"buffer": 0, "byteOffset": {}, "byteLength": {}}},
    {{"buffer": 0, "byteOffset": {}, "byteLength": {}}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": {}, "type": "VEC3"}},
    {{"bufferView": 1, "componentType": 5125, "count": {}, "type": "SCALAR"}},
    {{"bufferView": 2, "componentType": 5126, "count": {}, "type": "VEC3"}},
    {{"bufferView": 3, "componentType": 5121, "normalized": true, "count": {}, "type": "VEC4"}}
  ]
}})",
                                         b.bin.size(), oPos, pos.size(), oIdx, idx.size(), oSoup, soup.size(), oCol,
                                         colors.size(), nv, nc, nc, nc);
    const std::string path = tmp_.write("cow.glb", glb(json, b.bin));

    // The reference, by hand: node 1 (rotate 180 degrees about z, lift by 3,
    // then node 0's scale 2 and move), node 2 (mirror x, then node 0's), and
    // node 3 (x to y, y to z, z to x) over the copy without indices.
    TriangleMesh ref;
    // The corners as the file stores them, read back from its bytes: GCC 12's
    // SLP vectorizer (-O2 and up) drops a double(float(x)) round trip in a
    // loop such as this one.
    std::vector<Vec3d> floats(nv);
    for (size_t v = 0; v < nv; ++v)
        for (int k = 0; k < 3; ++k) {
            float f;
            std::memcpy(&f, pos.data() + 4 * (3 * v + size_t(k)), 4);
            floats[v][k] = f;
        }
    auto place = [&](Vec3d (*moved)(const Vec3d&), bool mirrored) {
        const uint32_t base = uint32_t(ref.positions.size());
        for (const Vec3d& p : floats) ref.positions.push_back(moved(p));
        for (const auto& t : cow.triangles)
            ref.triangles.push_back(mirrored ? std::array<uint32_t, 3>{t[0] + base, t[2] + base, t[1] + base}
                                             : std::array<uint32_t, 3>{t[0] + base, t[1] + base, t[2] + base});
    };
    place([](const Vec3d& p) { return Vec3d{2 * -p.x + 10, 2 * -p.y - 4, 2 * p.z + 6.5}; }, false); // each correctly rounded
    place([](const Vec3d& p) { return Vec3d{2 * -p.x + 10, 2 * p.y - 4, 2 * p.z + 0.5}; }, true);
    const uint32_t base = uint32_t(ref.positions.size());
    for (size_t c = 0; c < nc; ++c) {
        const Vec3d p = floats[cow.triangles[c / 3][c % 3]];
        ref.positions.push_back({p.z, p.x, p.y});
    }
    for (uint32_t t = 0; t < cow.triangles.size(); ++t)
        ref.triangles.push_back({base + 3 * t, base + 3 * t + 1, base + 3 * t + 2});

    const TriangleMesh mesh = loadMesh(path);
    expectSameMesh(mesh, ref);
    // Colours only on the copy's vertices; the rest are white (no COLOR_0, no material).
    ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
    EXPECT_EQ(mesh.colors[0].x, 1.0f);
    for (size_t c = 0; c < nc; ++c) {
        const uint32_t v = cow.triangles[c / 3][c % 3];
        ASSERT_EQ(mesh.colors[base + c].x, float((v % 256) / 255.0)) << c;
        ASSERT_EQ(mesh.colors[base + c].y, float(51 / 255.0)) << c;
    }
    ref.source = "reference";
    writeMesh(tmp_.path("ref.off"), ref);
    expectSameVoxels(path, tmp_.path("ref.off"));
}
#endif

TEST_F(Gltf, BadFilesAreOneLineErrors)
{
    const std::string tri = [] {
        std::string s;
        for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(s, f);
        return s;
    }();
    auto scene = [](const std::string& extra, const std::string& nodes = R"([{"mesh": 0}])",
                    const std::string& prim = R"({"attributes": {"POSITION": 0}})") {
        return fmt::format(R"({{"asset": {{"version": "2.0"}}, {} "scenes": [{{"nodes": [0]}}], "nodes": {},
          "meshes": [{{"primitives": [{}]}}], "buffers": [{{"byteLength": 36}}],
          "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
          "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}}]}})",
                           extra, nodes, prim);
    };
    // The well-formed file reads, so each error below is the change's.
    EXPECT_EQ(loadMesh(tmp_.write("good.glb", glb(scene(""), tri))).triangles.size(), 1u);
    expectError(tmp_.write("meshopt.glb", glb(scene(R"("extensionsRequired": ["EXT_meshopt_compression"],)"), tri)),
                "requires EXT_meshopt_compression (meshopt-compressed buffers), which svo does not decode");
    expectError(tmp_.write("cycle.glb", glb(scene("", R"([{"mesh": 0, "children": [1]}, {"children": [0]}])"), tri)),
                "node 0 is reached twice");
    expectError(tmp_.write("short.glb", glb(scene(""), tri).substr(0, 100)), "truncated");
    expectError(tmp_.write("json.gltf", "{\"asset\": "), "not a valid glTF 2.0 file");
    expectError(tmp_.write("v1.gltf", R"({"asset": {"version": "1.0"}, "meshes": []})"), "glTF version '1.0'; svo reads glTF 2.0");
    expectError(tmp_.write("deep.gltf", std::string(10000, '[')), "nested more than");
    expectError(tmp_.write("missing.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "gone.bin", "byteLength": 4}]})"),
                "gone.bin");
    expectError(tmp_.write("index.glb", glb(scene("", R"([{"mesh": 0}])",
                                                   R"({"attributes": {"POSITION": 0}, "indices": 0})"), tri)),
                "indices of component type 5126 (glTF's are unsigned integers)");
    // Float VEC3 colours (here the positions themselves) are glTF's too.
    const TriangleMesh colored = loadMesh(tmp_.write(
        "color.glb", glb(scene("", R"([{"mesh": 0}])", R"({"attributes": {"POSITION": 0, "COLOR_0": 0}})"), tri)));
    ASSERT_EQ(colored.colors.size(), 3u);
    EXPECT_TRUE(colored.colors[1] == (Vec3f{1, 0, 0}));
    expectError(tmp_.write("count.glb", glb(fmt::format(R"({{"asset": {{"version": "2.0"}}, "scenes": [{{"nodes": [0]}}],
          "nodes": [{{"mesh": 0}}], "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
          "buffers": [{{"byteLength": 36}}], "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
          "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4000000000, "type": "VEC3"}}]}})"),
                                             tri)),
                "run past buffer view 0");
    expectError(tmp_.write("mode.glb", glb(scene("", R"([{"mesh": 0}])", R"({"attributes": {"POSITION": 0}, "mode": 9})"), tri)),
                "unknown mode 9");
}
