// Mesh input: each format reads what was written; each bad input is a clear error.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace svo;

namespace {

class MeshIo : public ::testing::Test {
protected:
    std::string write(const std::string& name, const std::string& bytes) { return tmp_.write(name, bytes); }
    /// Loading must fail with svo::Error whose message names the file and contains `what`.
    void expectError(const std::string& path, const std::string& what)
    {
        try {
            loadMesh(path);
            FAIL() << path << " loaded without error";
        } catch (const Error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(path), std::string::npos) << msg;
            EXPECT_NE(msg.find(what), std::string::npos) << msg;
        }
    }
    test::TempDir tmp_{"mesh_io"};
};

template <typename T> void put(std::string& s, T v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }

std::string binaryStl(int triangles)
{
    std::string s(80, ' ');
    put<uint32_t>(s, uint32_t(triangles));
    for (int t = 0; t < triangles; ++t) {
        const float f[12] = {0, 0, 1, float(t), 0, 0, float(t) + 1, 0, 0, float(t), 1, 0};
        for (float x : f) put(s, x);
        put<uint16_t>(s, 0);
    }
    return s;
}

std::string binaryPly(int quads)
{
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(4 * quads) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(quads) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int q = 0; q < quads; ++q)
        for (int c = 0; c < 4; ++c) {
            put<float>(s, float(q) + float(c & 1));
            put<float>(s, float(c >> 1));
            put<float>(s, 0.5f);
        }
    for (int q = 0; q < quads; ++q) {
        put<uint8_t>(s, 4);
        for (int c : {0, 1, 3, 2}) put<int32_t>(s, 4 * q + c);
    }
    return s;
}

} // namespace

TEST_F(MeshIo, ObjTriangulatesPolygons)
{
    const auto m = loadMesh(write("a.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.25 0.5 2\nf 1 2 3 4\nf 1 2 5\n"));
    ASSERT_EQ(m.triangles.size(), 3u);
    EXPECT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.positions[4].x, 0.25);
    EXPECT_EQ(m.positions[4].z, 2.0);
    const auto b = m.bounds();
    EXPECT_EQ(b.max.y, 1.0);
    EXPECT_EQ(b.max.z, 2.0);
}

TEST_F(MeshIo, OffAsciiPlyBinaryPlyAsciiStlBinaryStl)
{
    auto off = loadMesh(write("a.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 3\n3 0 1 2\n3 0 2 3\n"));
    EXPECT_EQ(off.triangles.size(), 2u);
    EXPECT_EQ(off.bounds().max.z, 3.0);

    auto plyA = loadMesh(write("a.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                        "end_header\n0 0 0\n2 0 0\n2 2 0\n0 2 1\n4 0 1 2 3\n"));
    EXPECT_EQ(plyA.triangles.size(), 2u);
    EXPECT_EQ(plyA.bounds().max.x, 2.0);

    auto plyB = loadMesh(write("b.ply", binaryPly(3)));
    EXPECT_EQ(plyB.triangles.size(), 6u);
    EXPECT_EQ(plyB.bounds().max.x, 3.0);
    EXPECT_EQ(plyB.bounds().min.z, 0.5);

    auto stlA = loadMesh(write("a.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                        "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"));
    EXPECT_EQ(stlA.triangles.size(), 1u);

    auto stlB = loadMesh(write("b.stl", binaryStl(5)));
    EXPECT_EQ(stlB.triangles.size(), 5u);
    EXPECT_EQ(stlB.bounds().max.x, 5.0);
}

TEST_F(MeshIo, DegenerateAndDuplicateFacesAreKept)
{
    // A repeated-vertex face, a duplicate face and a non-manifold fan: a
    // halfedge mesh would refuse some of these; a voxelizer must not.
    const auto m = loadMesh(write("d.off", "OFF\n5 5 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 -1 0\n"
                                           "3 0 1 2\n3 0 1 2\n3 0 0 1\n3 0 1 3\n3 0 1 4\n"));
    EXPECT_EQ(m.triangles.size(), 5u);
    EXPECT_TRUE(m.warnings.empty());
    // OpenMesh's OBJ reader drops a face that repeats a vertex; that is reported.
    const auto o = loadMesh(write("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n"));
    EXPECT_EQ(o.triangles.size(), 1u);
    ASSERT_EQ(o.warnings.size(), 1u);
    EXPECT_NE(o.warnings[0].find("skipped 1 of 2 faces"), std::string::npos) << o.warnings[0];
}

TEST_F(MeshIo, BadInputsAreClearErrors)
{
    expectError(tmp_.path("missing.obj"), "no such file");
    expectError(write("a.xyz", "v 0 0 0\n"), "unknown mesh extension");
    expectError(write("empty.obj", ""), "empty");
    expectError(write("noface.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), "no triangles");
    expectError(write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"), "non-finite");
    expectError(write("inf.off", "OFF\n3 1 0\n0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n"), "non-finite");
    expectError(write("inf.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex -INF 0 0\n"
                                 "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"),
                "non-finite");
    std::string nanStl = binaryStl(2);
    const float nan = std::nanf("");
    std::memcpy(&nanStl[84 + 12 + 4], &nan, 4);
    expectError(write("nan.stl", nanStl), "non-finite");
    expectError(write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), "vertex index");
    expectError(write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), "");
    const std::string stl = binaryStl(10);
    expectError(write("trunc.stl", stl.substr(0, stl.size() - 30)), "truncated");
    const std::string ply = binaryPly(10);
    expectError(write("trunc.ply", ply.substr(0, ply.size() - 40)), "");
    expectError(write("header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), "truncated");
}

TEST_F(MeshIo, OffWithCommentsColoursAndPolygons)
{
    // As CGAL's tools write them: comments before the keyword and in the body,
    // colours after face indices, quads.
    const auto m = loadMesh(write("c.off", "# made by a tool\n#CBP\nCOFF\n# counts\n4 2 0\n\n# vertices\n"
                                           "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 2 1 1 1 255\n"
                                           "# faces\n4  0 1 2 3  0.5 0.5 0.5\n1 2\n"));
    ASSERT_EQ(m.triangles.size(), 3u); // a quad as 2 triangles, and a point face
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
    EXPECT_EQ(m.triangles[2], (std::array<uint32_t, 3>{2, 2, 2}));
    EXPECT_EQ(m.bounds().max.z, 2.0);
    expectError(write("t.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"), "truncated");
    expectError(write("n.off", "4OFF\n1 0 0\n0 0 0 0\n"), "not 3D");
}
