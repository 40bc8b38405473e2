// Mesh input: each format reads what was written; each bad input is a clear error.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <map>
#include <optional>

#include "obj_reader.h"
#include "ply_reader.h"
#include "off_reader.h"
#include "openmesh_reader.h"
#include "text_scan.h"
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
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg; // one line
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
    // OpenMesh's OBJ reader dropped a face that repeats a vertex; svo's keeps it.
    const auto o = loadMesh(write("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n"));
    ASSERT_EQ(o.triangles.size(), 2u);
    EXPECT_EQ(o.triangles[1], (std::array<uint32_t, 3>{0, 0, 1}));
    EXPECT_TRUE(o.warnings.empty());
}

TEST_F(MeshIo, BadInputsAreClearErrors)
{
    expectError(tmp_.path("missing.obj"), "no such file");
    expectError(write("a.xyz", "v 0 0 0\n"), "unknown mesh extension '.xyz'");
    expectError(write("noextension", "v 0 0 0\n"), "the name has no extension");
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
    expectError(write("ctl.off", "OFF\n3 1 0\n0 0 0\n1 0 \x07\\\n0 1 0\n3 0 1 2\n"), "coordinate '\\x07\\x5C'");
}

namespace {

/// A PLY body in ASCII or either binary byte order, value by value, so that
/// one sequence of calls gives the same mesh in all three encodings.
class PlyBody {
public:
    enum Kind { Ascii, Little, Big };
    explicit PlyBody(Kind k) : kind_(k) {}
    const char* format() const
    {
        return kind_ == Ascii ? "ascii" : kind_ == Little ? "binary_little_endian" : "binary_big_endian";
    }
    template <typename T> PlyBody& operator()(T v)
    {
        if (kind_ == Ascii) {
            text += fmt::format("{} ", +v); // + prints (u)int8 as a number
        } else {
            char b[sizeof v];
            std::memcpy(b, &v, sizeof v);
            if (kind_ == Big) std::reverse(b, b + sizeof v); // the test machines are little-endian
            text.append(b, sizeof v);
        }
        return *this;
    }
    PlyBody& endl()
    {
        if (kind_ == Ascii) text += '\n';
        return *this;
    }
    std::string text;

private:
    Kind kind_;
};

// A one-unit triangle 1e9 from the origin: float keeps none of its detail.
const char* const farText[3][3] = {{"1000000000.1", "1000000000.2", "1000000000.3"},
                                   {"1000000001.1", "1000000000.2", "1000000000.3"},
                                   {"1000000000.1", "1000000001.2", "1000000000.3"}};
const Vec3d farCorners[3] = {{1000000000.1, 1000000000.2, 1000000000.3},
                             {1000000001.1, 1000000000.2, 1000000000.3},
                             {1000000000.1, 1000000001.2, 1000000000.3}};

std::string farPly(PlyBody::Kind kind)
{
    PlyBody b(kind);
    for (const Vec3d& c : farCorners) {
        if (kind == PlyBody::Ascii) b.text += fmt::format("{} {} {}\n", c.x, c.y, c.z); // shortest round trip
        else b(c.x)(c.y)(c.z);
    }
    b(uint8_t(3))(int32_t(0))(int32_t(1))(int32_t(2)).endl();
    return fmt::format("ply\nformat {} 1.0\nelement vertex 3\nproperty double x\nproperty float64 y\n"
                       "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n",
                       b.format()) +
           b.text;
}

} // namespace

TEST_F(MeshIo, FarTriangleIsBitExactInEveryFormatThatStoresDoubles)
{
    std::string off = "OFF\n3 1 0\n", obj = "# far\n", stl = "solid far\nfacet normal 0 0 1\n outer loop\n";
    for (const auto& c : farText) {
        off += fmt::format("{} {} {}\n", c[0], c[1], c[2]);
        obj += fmt::format("v {} {} {}\n", c[0], c[1], c[2]);
        stl += fmt::format("  vertex {} {} {}\n", c[0], c[1], c[2]);
    }
    off += "3 0 1 2\n";
    obj += "f 1 2 3\n";
    stl += " endloop\nendfacet\nendsolid far\n";
    ASSERT_NE(double(float(farCorners[0].x)), farCorners[0].x);
    const auto reference = loadMesh(write("far.off", off));
    for (const std::string& path :
         {write("far.obj", obj), write("far.stl", stl), write("a.ply", farPly(PlyBody::Ascii)),
          write("l.ply", farPly(PlyBody::Little)), write("b.ply", farPly(PlyBody::Big))}) {
        const auto m = loadMesh(path);
        ASSERT_EQ(m.triangles.size(), 1u) << path;
        for (size_t k = 0; k < 3; ++k) {
            EXPECT_EQ(m.corners(0)[k], farCorners[k]) << path << " corner " << k;
            EXPECT_EQ(m.corners(0)[k], reference.corners(0)[k]) << path << " corner " << k;
        }
        EXPECT_TRUE(m.warnings.empty()) << path;
    }
}

TEST_F(MeshIo, ObjFaceFormsRelativeIndicesAndStatements)
{
    const auto m = loadMesh(write("forms.obj", "# a comment\r\nv 0 0 0\r\nv 1 0 0 1.0\r\nv 1 1 0\nv 0 1 0\n\n"
                                               "vt 0 0\nvn 0 0 1\no thing\ng group\ns off\nusemtl mat\nmtllib x.mtl\n"
                                               "l 1 2\np 3\n"
                                               "f 1/1 2/1 3/1\n"
                                               "f 1//1 3//1 4//1\n"
                                               "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
                                               "f -4 -3 -2 # relative\n"
                                               "f 2 2 3\n"
                                               "f 1 2 \\\n 4\n"
                                               "v +2 -0.5e1 3.\t\n"
                                               "f\t-1 1 2\n"));
    const std::vector<std::array<uint32_t, 3>> want = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 3},
                                                       {0, 1, 2}, {1, 1, 2}, {0, 1, 3}, {4, 0, 1}};
    EXPECT_EQ(m.triangles, want);
    ASSERT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.positions[1], Vec3d(1, 0, 0)); // w is not a coordinate
    EXPECT_EQ(m.positions[4], Vec3d(2, -5, 3));
    EXPECT_TRUE(m.colors.empty());
    // x.mtl is not there: its colours cannot be used, which the user is told.
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_NE(m.warnings[0].find("material library 'x.mtl' not found"), std::string::npos) << m.warnings[0];

    const auto c = loadMesh(write("c.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n"));
    ASSERT_EQ(c.colors.size(), 3u);
    EXPECT_EQ(c.colors[2], Vec3f(0, 0, 0.5f));
    const auto some = loadMesh(write("some.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_TRUE(some.colors.empty());
    ASSERT_EQ(some.warnings.size(), 1u);
    EXPECT_NE(some.warnings[0].find("only 1 of 3 vertices have a colour"), std::string::npos) << some.warnings[0];
}

TEST_F(MeshIo, ObjErrorsNameTheLine)
{
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n# faces\n";
    expectError(write("r1.obj", head + "f 1 2 3\nf 1 2 9\n"), "line 6: face uses vertex index 9, but the file has 3 vertices");
    expectError(write("r2.obj", head + "f -4 1 2\n"), "line 5: face uses relative vertex index -4");
    expectError(write("r3.obj", head + "f 0 1 2\n"), "line 5: vertex index 0");
    expectError(write("r4.obj", head + "f 1 2 x3\n"), "line 5: malformed face corner 'x3'");
    expectError(write("r5.obj", head + "f\n"), "line 5: a face with no vertices");
    expectError(write("r6.obj", "v 0 0\n"), "line 1: a vertex needs 3 coordinates");
    expectError(write("r7.obj", "v 0 1e999 0\n"), "line 1: non-finite coordinate '1e999'");
    expectError(write("r8.obj", "\n\nv 0 -inf 0\n"), "line 3: non-finite coordinate '-inf'");
    // No byte of the file reaches the terminal raw.
    const std::string path = write("ctl.obj", "v 0 0 \x1b[31mred\x01\n");
    try {
        loadMesh(path);
        FAIL();
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("line 1: malformed number '\\x1B[31mred\\x01'"), std::string::npos) << msg;
        EXPECT_EQ(std::count_if(msg.begin(), msg.end(), [](char ch) { return (unsigned char)ch < 0x20; }), 0);
    }
}

namespace {

/// Extra vertex properties (a list among them), elements before and after,
/// and face properties around the index list, in any encoding.
std::string extrasPly(PlyBody::Kind kind)
{
    PlyBody b(kind);
    b(uint8_t(2))(0.5f)(0.25f)(uint8_t(7)).endl()(uint8_t(0))(uint8_t(9)).endl(); // materials
    const double v[3][3] = {{0.5, 0.25, 3}, {1.5, 0.25, 3}, {0.5, 1.25, -2}};
    for (int i = 0; i < 3; ++i) {
        b(0.1f)(v[i][0])(uint16_t(2))(int32_t(1))(int32_t(2))(float(v[i][1]))(uint8_t(255))(int16_t(v[i][2]));
        b.endl();
    }
    b(uint8_t(1))(uint8_t(3))(uint32_t(0))(uint32_t(1))(uint32_t(2))(uint8_t(0)).endl();
    b(uint8_t(0))(uint8_t(4))(uint32_t(2))(uint32_t(1))(uint32_t(0))(uint32_t(1))(uint8_t(1))(int32_t(5)).endl();
    b(int32_t(0))(int32_t(1)).endl(); // the edge
    return fmt::format("ply\nformat {} 1.0\ncomment made by a test\nobj_info none\n"
                       "element material 2\nproperty list uchar float shininess\nproperty uchar id\n"
                       "element vertex 3\nproperty float nx\nproperty double x\nproperty list ushort int neighbours\n"
                       "property float32 y\nproperty uchar red\nproperty int16 z\n"
                       "element face 2\nproperty uchar flags\nproperty list uint8 uint32 vertex_index\n"
                       "property list uchar int texnumber\n"
                       "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n",
                       b.format()) +
           b.text;
}

} // namespace

TEST_F(MeshIo, PlyExtraPropertiesAndElementsInEveryEncoding)
{
    for (auto kind : {PlyBody::Ascii, PlyBody::Little, PlyBody::Big}) {
        const auto m = loadMesh(write("extras.ply", extrasPly(kind)));
        const std::vector<std::array<uint32_t, 3>> want = {{0, 1, 2}, {2, 1, 0}, {2, 0, 1}};
        EXPECT_EQ(m.triangles, want) << kind;
        ASSERT_EQ(m.positions.size(), 3u) << kind;
        EXPECT_EQ(m.positions[0], Vec3d(0.5, 0.25, 3)) << kind;
        EXPECT_EQ(m.positions[2], Vec3d(0.5, 1.25, -2)) << kind;
    }
}

TEST_F(MeshIo, PlyTruncationsCountsAndIndicesAreClearErrors)
{
    // Every cut of a binary body is refused, however it falls.
    const std::string ply = binaryPly(2);
    const size_t body = ply.find("end_header\n") + 11;
    for (size_t cut = body; cut < ply.size(); ++cut) {
        SCOPED_TRACE(cut);
        expectError(write("cut.ply", ply.substr(0, cut)), "truncated");
    }
    const std::string ascii = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    expectError(write("cuta.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"), "the file ends in face 0 of 1");
    expectError(write("idx.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
                "face 0 uses vertex index 7, but the file has 3 vertices");
    expectError(write("neg.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), "face 0 uses vertex index -1");
    expectError(write("num.ply", ascii + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"), "line 11: malformed number 'x'");
    expectError(write("nan.ply", ascii + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "non-finite");
    std::string big = binaryPly(1);
    big.replace(big.find("vertex 4"), 8, "vertex 4000000000");
    expectError(write("count.ply", big), "more than the file's");
    expectError(write("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"),
                "line 2: unknown PLY format 'binary_middle_endian'");
    expectError(write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n"),
                "line 4: unknown property type 'float128'");
    expectError(write("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                 "end_header\n0 0\n"),
                "no scalar 'z' property");
    expectError(write("magic.ply", "plx\n"), "not a PLY file");
}

TEST_F(MeshIo, StlVariants)
{
    // Upper-case keywords, two solids, a four-corner loop, no names.
    const auto a = loadMesh(write("u.stl", "SOLID\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\n"
                                           "VERTEX 1 1 0\nVERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID\n"
                                           "solid b\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                           "vertex 0 0 1\nendloop\nendfacet\nendsolid b\n"));
    EXPECT_EQ(a.triangles.size(), 3u);
    EXPECT_EQ(a.positions.size(), 5u); // corners welded
    // A binary file whose header starts with "solid" is still binary.
    std::string b = binaryStl(3);
    b.replace(0, 11, "solid facet");
    EXPECT_EQ(loadMesh(write("s.stl", b)).triangles.size(), 3u);
    expectError(write("t.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"), "truncated");
    expectError(write("e.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
                               "endfacet\nendsolid t\n"),
                "line 7: a facet with 2 vertices");
    expectError(write("m.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                               "vertex 0 1 zero\nendloop\nendfacet\nendsolid t\n"),
                "line 6: malformed coordinate 'zero'");
}

#ifdef SVO_CGAL_MESHES
TEST_F(MeshIo, RealMeshesReadAsOpenMeshReadsThemWithinFloatRounding)
{
    // svo's readers against OpenMesh's (the readers they replace) on the same
    // files: the same triangles, and corners that round to OpenMesh's floats.
    for (const char* name : {"elephant.off", "cow.off"}) {
        SCOPED_TRACE(name);
        const auto ref = loadMesh(std::string(SVO_CGAL_MESHES) + "/" + name);
        const std::string obj = tmp_.path("m.obj");
        writeMesh(obj, ref);
        std::string plyHeader = fmt::format("element vertex {}\nproperty {{0}} x\nproperty {{0}} y\nproperty {{0}} z\n"
                                            "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                                            ref.positions.size(), ref.triangles.size());
        PlyBody text(PlyBody::Ascii), bin(PlyBody::Little);
        for (const Vec3d& p : ref.positions) {
            text.text += fmt::format("{} {} {}\n", p.x, p.y, p.z);
            bin(float(p.x))(float(p.y))(float(p.z));
        }
        std::string stl = "solid m\n", stlBin(80, ' ');
        put<uint32_t>(stlBin, uint32_t(ref.triangles.size()));
        for (size_t t = 0; t < ref.triangles.size(); ++t) {
            text(uint8_t(3));
            bin(uint8_t(3));
            for (uint32_t v : ref.triangles[t]) text(int32_t(v)), bin(int32_t(v));
            text.endl();
            stl += "facet normal 0 0 0\nouter loop\n";
            for (int a = 0; a < 3; ++a) put<float>(stlBin, 0);
            for (const Vec3d& c : ref.corners(t)) {
                stl += fmt::format("vertex {} {} {}\n", c.x, c.y, c.z);
                for (int a = 0; a < 3; ++a) put<float>(stlBin, float(c[a]));
            }
            stl += "endloop\nendfacet\n";
            put<uint16_t>(stlBin, 0);
        }
        stl += "endsolid m\n";
        const std::string textPly = write("t.ply", "ply\nformat ascii 1.0\n" + fmt::format(plyHeader, "double") + text.text);
        const std::string binPly =
            write("b.ply", "ply\nformat binary_little_endian 1.0\n" + fmt::format(plyHeader, "float") + bin.text);
        for (const std::string& path : {obj, textPly, binPly, write("t.stl", stl), write("b.stl", stlBin)}) {
            SCOPED_TRACE(path);
            const auto ours = loadMesh(path);
            const auto theirs = detail::readWithOpenMesh(path);
            ASSERT_EQ(ours.triangles.size(), ref.triangles.size());
            ASSERT_EQ(theirs.triangles.size(), ref.triangles.size());
            const bool exact = path != binPly && path.find("b.stl") == std::string::npos;
            for (size_t t = 0; t < ref.triangles.size(); ++t)
                for (int k = 0; k < 3; ++k)
                    for (int a = 0; a < 3; ++a) {
                        const double mine = ours.corners(t)[size_t(k)][a];
                        ASSERT_EQ(float(mine), float(theirs.corners(t)[size_t(k)][a])) << t << " " << k << " " << a;
                        // Text is read exactly; binary float is what was stored.
                        ASSERT_EQ(mine, exact ? ref.corners(t)[size_t(k)][a] : double(float(ref.corners(t)[size_t(k)][a])));
                    }
        }
    }
}
#endif

namespace {

/// The mesh (or the error message) a reader gives.
template <typename Read>
std::string outcome(Read&& read, TriangleMesh& mesh)
{
    try {
        mesh = read();
        return "";
    } catch (const Error& e) {
        return e.what();
    }
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b)
{
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t i = 0; i < a.positions.size(); ++i)
        for (int k = 0; k < 3; ++k) ASSERT_EQ(a.positions[i][k], b.positions[i][k]) << "vertex " << i; // bit for bit
    EXPECT_EQ(a.triangles, b.triangles);
    ASSERT_EQ(a.colors.size(), b.colors.size());
    for (size_t i = 0; i < a.colors.size(); ++i)
        for (int k = 0; k < 3; ++k) ASSERT_EQ(a.colors[i][k], b.colors[i][k]) << "colour " << i;
    EXPECT_EQ(a.warnings, b.warnings);
}

/// An OBJ with everything the reader accepts, in `lines` statements: comments,
/// blank lines, CRLF, `\` continuations, polygons, v/vt/vn corners, and
/// colours on every vertex or on some.
std::string variedObj(int lines, bool allColoured, bool relative)
{
    std::string s = "# varied\nmtllib x.mtl\n";
    int vertices = 0;
    for (int i = 0; i < lines; ++i) {
        const double x = 0.1 * i, y = std::sin(i * 0.7), z = 1.0 / (i + 3);
        switch (i % 7) {
        case 0: s += fmt::format(allColoured ? "v {} {} {} 1 0 0\r\n" : "v {} {} {}\r\n", x, y, z); ++vertices; break;
        case 1:
            s += allColoured || i % 3 ? fmt::format("v {} {} {} 0.5 0.25 1\n", x, y, z) : fmt::format("v {} {} {}\n", x, y, z);
            ++vertices;
            break;
        case 2:
            s += fmt::format(allColoured ? "v {} \\\n {} \\\n{} 0 1 0  # continued\n" : "v {} \\\n {} \\\n{}  # continued\n", x, y,
                             z);
            ++vertices;
            break;
        case 3: s += "\n# a comment line\nvt 0.5 0.5\n"; break;
        default:
            if (vertices < 4) break;
            if (relative && i % 5 == 0) s += "f -1 -2 -3\n";
            else if (i % 2) s += fmt::format("f {}/1 {}//2 {}/3/4 {}\n", vertices, vertices - 1, vertices - 2, vertices - 3);
            else s += fmt::format("f {} \\\n{} {}\n", vertices - 3, vertices - 1, vertices);
        }
    }
    return s;
}

} // namespace

// The readers parse large files in pieces in parallel: the same mesh, colours,
// warnings and errors as reading the file as one piece, for pieces down to a
// few lines (so that every statement meets a piece's edge somewhere).
TEST_F(MeshIo, ObjInPiecesGivesWhatOnePieceGives)
{
    const size_t whole = size_t(1) << 40;
    for (const bool allColoured : {true, false})
        for (const bool relative : {false, true}) {
            const std::string text = variedObj(3000, allColoured, relative);
            TriangleMesh one, pieces;
            ASSERT_EQ(outcome([&] { return detail::readObj("a.obj", text, whole); }, one), "");
            EXPECT_GT(one.triangles.size(), 1000u);
            EXPECT_EQ(one.colors.empty(), !allColoured);
            for (const size_t chunk : {size_t(1), size_t(37), size_t(4096)}) {
                SCOPED_TRACE(fmt::format("pieces of {} bytes, colours on all {}, relative {}", chunk, allColoured,
                                         relative));
                size_t used = 0;
                ASSERT_EQ(outcome([&] { return detail::readObj("a.obj", text, chunk, &used); }, pieces), "");
                expectSameMesh(pieces, one);
                // Relative indices need the vertices before their piece: one piece then.
                if (relative) EXPECT_EQ(used, 0u);
                else EXPECT_GT(used, chunk == 1 ? 3000u : 10u);
            }
        }
    // Errors name the same line: a bad number near the end, an index past the
    // vertices (checked at the end), a relative index before any vertex.
    const std::string good = variedObj(3000, true, false);
    const size_t middle = good.find("vt 0.5 0.5\n", good.size() / 2) + 11; // after a whole statement
    for (const std::string& bad : {good + "v 1 2 x\nf 1 2 3\n", good + "f 1 2 999999\n" + good,
                                   "f -1 -2 -3\n" + good, good.substr(0, middle) + "f 0 1 2\n" + good.substr(middle)}) {
        TriangleMesh mesh;
        const std::string one = outcome([&] { return detail::readObj("a.obj", bad, whole); }, mesh);
        EXPECT_NE(one, "");
        EXPECT_NE(one.find("line "), std::string::npos) << one;
        for (const size_t chunk : {size_t(1), size_t(4096)})
            EXPECT_EQ(outcome([&] { return detail::readObj("a.obj", bad, chunk); }, mesh), one);
    }
}

// loadMesh reads an OBJ file a block at a time, parsing each block's whole
// lines as it goes: the same mesh, colours and errors as the file's text
// read at once, with blocks that end inside lines and `\` continued
// statements, and files that need reading in order (relative indices).
TEST_F(MeshIo, ObjFileInBlocksGivesWhatItsTextGives)
{
    const size_t whole = size_t(1) << 40;
    const std::string good = variedObj(3000, true, false);
    const size_t middle = good.find("vt 0.5 0.5\n", good.size() / 2) + 11;
    const std::vector<std::string> texts = {good, variedObj(3000, false, false), variedObj(3000, true, true),
                                            good + "v 1 2 x\nf 1 2 3\n", good + "f 1 2 999999\n" + good,
                                            good.substr(0, middle) + "f 0 1 2\n" + good.substr(middle),
                                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3"}; // no final newline
    for (size_t k = 0; k < texts.size(); ++k) {
        const std::string file = write(fmt::format("blocks{}.obj", k), texts[k]);
        TriangleMesh one, blocks;
        const std::string expected = outcome([&] { return detail::readObj(file, texts[k], whole); }, one);
        for (const size_t block : {size_t(1), size_t(7), size_t(4096), size_t(1) << 20})
            for (const size_t chunk : {size_t(37), size_t(4096)}) {
                SCOPED_TRACE(fmt::format("text {}, blocks of {} bytes, pieces of {}", k, block, chunk));
                ASSERT_EQ(outcome([&] { return detail::readObjFile(file, block, chunk); }, blocks), expected);
                if (expected.empty()) expectSameMesh(blocks, one);
            }
    }
    const std::string file = write("loaded.obj", good);
    TriangleMesh one;
    ASSERT_EQ(outcome([&] { return detail::readObj(file, good, whole); }, one), "");
    expectSameMesh(loadMesh(file), one);
}

TEST_F(MeshIo, OffInPiecesGivesWhatOnePieceGives)
{
    const size_t whole = size_t(1) << 40;
    for (const std::string keyword : {"OFF", "COFF"}) {
        std::string body;
        const int nv = 2000, nf = 1500;
        for (int v = 0; v < nv; ++v) {
            if (v % 97 == 0) body += "# a comment\n\n";
            body += fmt::format("{} {} {}{}\n", 0.01 * v, std::cos(v * 0.3), 1.0 / (v + 7),
                                keyword == "COFF" ? (v % 2 ? " 255 128 0 255" : " 0.5 0.25 1 1") : "");
        }
        for (int f = 0; f < nf; ++f) {
            const int n = 3 + f % 4;
            body += std::to_string(n);
            for (int i = 0; i < n; ++i) body += " " + std::to_string((f * 7 + i * 13) % nv);
            body += f % 50 == 0 ? "  # trailing comment\n" : "\n";
        }
        const std::string text = keyword + "\n# counts follow\n" + fmt::format("{} {} 0\n", nv, nf) + body + "trailing text\n";
        SCOPED_TRACE(keyword);
        TriangleMesh one, pieces;
        ASSERT_EQ(outcome([&] { return detail::readOff("a.off", text, whole); }, one), "");
        EXPECT_EQ(one.positions.size(), size_t(nv));
        EXPECT_EQ(one.colors.size(), keyword == "COFF" ? size_t(nv) : 0u);
        for (const size_t chunk : {size_t(1), size_t(53), size_t(8192)}) {
            SCOPED_TRACE(chunk);
            size_t used = 0;
            ASSERT_EQ(outcome([&] { return detail::readOff("a.off", text, chunk, &used); }, pieces), "");
            expectSameMesh(pieces, one);
            EXPECT_GT(used, chunk == 1 ? 3000u : 10u);
        }
        // Errors: a bad coordinate, a face index out of range, a truncated file,
        // a face count whose sum with the vertex count overflows 64 bits.
        const size_t mid = text.find('\n', text.size() / 3);
        const std::string huge = keyword + fmt::format("\n{} 9223372036854775807 0\n", nv) + body;
        for (const std::string& bad : {text.substr(0, mid + 1) + "1 2 nan\n" + text.substr(mid + 1),
                                       text.substr(0, text.size() - 30) + "\n3 0 1 2000000\n",
                                       text.substr(0, text.size() / 2), huge}) {
            TriangleMesh mesh;
            const std::string msg = outcome([&] { return detail::readOff("a.off", bad, whole); }, mesh);
            EXPECT_NE(msg, "");
            if (bad == huge) EXPECT_NE(msg.find("declares 9223372036854775807 faces"), std::string::npos) << msg;
            for (const size_t chunk : {size_t(1), size_t(8192)})
                EXPECT_EQ(outcome([&] { return detail::readOff("a.off", bad, chunk); }, mesh), msg);
        }
    }
}

// STL corners are welded in parallel (buckets by hash, then a running count):
// the vertices must be the distinct corners in order of first appearance, as
// one pass with a map gives them, with -0 and +0 kept apart.
TEST_F(MeshIo, StlCornersWeldInOrderOfFirstAppearance)
{
    // A 300 x 300 grid of quads (two triangles each), corners shared by up to
    // six triangles, in a shuffled triangle order; a few corners at -0.
    std::vector<std::array<Vec3f, 3>> tris;
    const int n = 300;
    auto corner = [&](int i, int j) { return Vec3f{float(i) * 0.25f, float(j) == 7 ? -0.0f : float(j) * 0.5f, 1.0f}; };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            tris.push_back({corner(i, j), corner(i + 1, j), corner(i + 1, j + 1)});
            tris.push_back({corner(i, j), corner(i + 1, j + 1), corner(i, j + 1)});
        }
    for (size_t k = 0; k < tris.size(); ++k) std::swap(tris[k], tris[(k * 7919) % tris.size()]);
    tris.push_back({Vec3f{0, 0, 0}, Vec3f{-0.0f, 0, 0}, Vec3f{0, 0, 0}}); // -0 is another vertex
    std::string stl(80, ' ');
    put<uint32_t>(stl, uint32_t(tris.size()));
    for (const auto& t : tris) {
        for (int a = 0; a < 3; ++a) put<float>(stl, 0);
        for (const Vec3f& c : t) put(stl, c.x), put(stl, c.y), put(stl, c.z);
        put<uint16_t>(stl, 0);
    }
    // The reference: one pass with a map from the coordinates' bits.
    std::map<std::array<uint32_t, 3>, uint32_t> ids;
    std::vector<Vec3f> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
    for (const auto& t : tris) {
        std::array<uint32_t, 3> tri;
        for (int c = 0; c < 3; ++c) {
            std::array<uint32_t, 3> bits;
            std::memcpy(bits.data(), &t[size_t(c)], 12);
            const auto [it, added] = ids.try_emplace(bits, uint32_t(positions.size()));
            if (added) positions.push_back(t[size_t(c)]);
            tri[size_t(c)] = it->second;
        }
        triangles.push_back(tri);
    }
    const TriangleMesh m = loadMesh(write("grid.stl", stl));
    ASSERT_EQ(m.positions.size(), positions.size());
    EXPECT_EQ(m.triangles, triangles);
    for (size_t i = 0; i < positions.size(); ++i) {
        EXPECT_EQ(std::signbit(m.positions[i].x), std::signbit(positions[i].x)) << i;
        EXPECT_EQ(m.positions[i].x, double(positions[i].x)) << i;
        EXPECT_EQ(m.positions[i].y, double(positions[i].y)) << i;
        EXPECT_EQ(m.positions[i].z, double(positions[i].z)) << i;
    }
    // A bad coordinate deep in the file names the first bad triangle.
    std::string bad = stl;
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&bad[84 + 50 * 100000 + 12 + 20], &inf, 4);
    std::memcpy(&bad[84 + 50 * 150000 + 12], &nan, 4);
    expectError(write("bad.stl", bad), "triangle 100000 has a non-finite coordinate (inf)");
}

// ASCII PLY bodies of `parallelFrom` bytes or more are read record by record
// in parallel: the same mesh and the same errors as the one-piece reader,
// with extra properties, lists and elements, faces before vertices, and
// polygons (binary bodies, read in one piece, give the same mesh too).
TEST_F(MeshIo, PlyInParallelGivesWhatOnePieceGives)
{
    for (const PlyBody::Kind kind : {PlyBody::Ascii, PlyBody::Little, PlyBody::Big}) {
        SCOPED_TRACE(int(kind));
        const int nv = 3000, nf = 2500;
        PlyBody faces(kind), vertices(kind), extra(kind);
        for (int f = 0; f < nf; ++f) {
            const int n = 1 + f % 5;
            faces(uint8_t(n));
            for (int i = 0; i < n; ++i) faces(int32_t((f * 31 + i * 7) % nv));
            faces(uint8_t(2))(int16_t(f))(int16_t(-f))(float(f) * 0.5f).endl(); // a list and a scalar to skip
        }
        for (int v = 0; v < nv; ++v) vertices(float(v) * 0.25f)(int16_t(v))(double(v) / 3.0)(uint8_t(v)).endl();
        for (int k = 0; k < 10; ++k) extra(int32_t(k)).endl();
        const std::string header = fmt::format(
            "ply\nformat {} 1.0\ncomment faces first\nelement face {}\nproperty list uchar int vertex_indices\n"
            "property list uchar short texcoord\nproperty float quality\nelement vertex {}\nproperty float x\n"
            "property short y\nproperty double z\nproperty uchar red\nelement other 10\nproperty int tag\n"
            "element empty 5\nend_header\n",
            faces.format(), nf, nv);
        const std::string text = header + faces.text + vertices.text + extra.text;
        TriangleMesh one, both;
        bool parallel = true;
        ASSERT_EQ(outcome([&] { return detail::readPly("a.ply", text, size_t(1) << 40, &parallel); }, one), "");
        EXPECT_FALSE(parallel);
        EXPECT_EQ(one.positions.size(), size_t(nv));
        ASSERT_EQ(outcome([&] { return detail::readPly("a.ply", text, 1, &parallel); }, both), "");
        EXPECT_EQ(parallel, kind == PlyBody::Ascii) << "ASCII bodies are read in parallel, binary ones in one piece";
        expectSameMesh(both, one);
        // Errors read in one piece and named as it names them.
        const size_t vertexStart = header.size() + faces.text.size();
        std::string nanVertex = text, badIndex = text;
        const double nan = std::numeric_limits<double>::quiet_NaN();
        if (kind == PlyBody::Ascii) {
            const size_t line = text.find('\n', vertexStart + vertices.text.size() / 2) + 1;
            nanVertex.insert(line, "1 2 nan 4\n"); // and one line too many at the end
            badIndex.replace(header.size(), 2, "3 0 1 9999 ");
        } else {
            // Vertex 1500's z, and face 0's first index, in the body's byte order.
            auto put = [&](std::string& s, size_t at, const auto value) {
                char b[sizeof value];
                std::memcpy(b, &value, sizeof value);
                if (kind == PlyBody::Big) std::reverse(b, b + sizeof value);
                std::memcpy(&s[at], b, sizeof value);
            };
            put(nanVertex, vertexStart + 15 * 1500 + 6, nan);
            put(badIndex, header.size() + 1, int32_t(9999));
        }
        for (const std::string& bad : {nanVertex, badIndex, text.substr(0, text.size() - 40)}) {
            TriangleMesh mesh;
            const std::string msg = outcome([&] { return detail::readPly("a.ply", bad, size_t(1) << 40); }, mesh);
            EXPECT_NE(msg, "");
            EXPECT_EQ(outcome([&] { return detail::readPly("a.ply", bad, 1); }, mesh), msg);
        }
    }
}

namespace {

/// A binary OFF file word by word: the header line, then big-endian int32 and
/// float32 words, as the OFF spec lays them out.
class BinaryOff {
public:
    explicit BinaryOff(const std::string& header = "OFF BINARY") : bytes(header + "\n") {}
    BinaryOff& i(int32_t v) { return word(v); }
    BinaryOff& f(float v) { return word(v); }
    /// Counts, then a unit right triangle's corners (no normals, colours, texture).
    static BinaryOff triangle(int32_t faces)
    {
        BinaryOff b;
        b.i(3).i(faces).i(0);
        for (int v = 0; v < 3; ++v) b.f(float(v == 1)).f(float(v == 2)).f(0);
        return b;
    }
    std::string bytes;

private:
    template <typename T> BinaryOff& word(T v)
    {
        char b[4];
        std::memcpy(b, &v, 4);
        std::reverse(b, b + 4); // the test machines are little-endian
        bytes.append(b, 4);
        return *this;
    }
};

} // namespace

// OpenMesh read a negative polygon size as a huge count and allocated for it
// until memory ran out (or std::bad_alloc escaped as an internal error).
TEST_F(MeshIo, BinaryOffNegativePolygonSizeIsAClearError)
{
    for (const int32_t n : {-1, -2, std::numeric_limits<int32_t>::min()}) {
        SCOPED_TRACE(n);
        expectError(write("neg.off", BinaryOff::triangle(1).i(n).i(0).i(1).i(2).i(0).bytes),
                    fmt::format("face 0 has {} vertices", n));
    }
}

// A polygon size of 2^30 in a small file kept OpenMesh busy for minutes: the
// size is now held to the words the file has left before any is read.
TEST_F(MeshIo, BinaryOffHugePolygonSizeIsRefusedAtOnce)
{
    for (const int32_t n : {1 << 30, std::numeric_limits<int32_t>::max(), 4}) {
        SCOPED_TRACE(n);
        expectError(write("huge.off", BinaryOff::triangle(1).i(n).i(0).i(1).i(2).i(0).bytes),
                    fmt::format("face 0 has {} vertices, more than the rest of the file holds", n));
    }
}

// OpenMesh took a face cut short for a segment of the indices it found (exit
// 0). Every cut of a valid file, anywhere after the header line, is an error.
TEST_F(MeshIo, BinaryOffTruncatedAnywhereIsAnError)
{
    const std::string whole = BinaryOff::triangle(2).i(3).i(0).i(1).i(2).i(0).i(3).i(2).i(1).i(0).i(3).f(1).f(0).f(0).bytes;
    ASSERT_EQ(loadMesh(write("whole.off", whole)).triangles.size(), 2u);
    for (size_t cut = std::string("OFF BINARY\n").size(); cut < whole.size(); ++cut) {
        SCOPED_TRACE(cut);
        expectError(write("cut.off", whole.substr(0, cut)), "truncated");
    }
    // The reported case: a triangle whose last index and colour count are missing.
    expectError(write("segment.off", BinaryOff::triangle(1).i(3).i(0).i(1).bytes),
                "face 0 has 3 vertices, more than the rest of the file holds (truncated file?)");
}

// `OFF BINARY` alone made OpenMesh read counts and indices it never stored:
// a different garbage vertex index on every run.
TEST_F(MeshIo, BinaryOffHeaderAloneIsATruncationError)
{
    // Also a CRLF header line, and a body of one word.
    for (const std::string& bytes : {std::string("OFF BINARY"), std::string("OFF BINARY\n"),
                                     std::string("OFF BINARY\r\n\0\0\0\3", 16)}) {
        SCOPED_TRACE(detail::escaped(bytes));
        expectError(write("alone.off", bytes),
                    "truncated binary OFF: the counts need 12 bytes after the header line");
    }
}

// OpenMesh read binary COFF as "no triangles". The spec gives each vertex an
// RGBA colour of four floats, and each face a colour-component count.
TEST_F(MeshIo, BinaryCoffReadsItsVertexColours)
{
    BinaryOff b("COFF BINARY");
    b.i(4).i(1).i(0);
    const float rgba[4][4] = {{1, 0, 0, 1}, {0, 0.5f, 0, 1}, {0, 0, 0.25f, 0.5f}, {0.75f, 0.75f, 0.75f, 0}};
    for (int v = 0; v < 4; ++v) {
        b.f(float(v & 1)).f(float(v >> 1)).f(2);
        for (float c : rgba[v]) b.f(c);
    }
    b.i(4).i(0).i(1).i(3).i(2).i(3).f(0.1f).f(0.2f).f(0.3f); // a quad with an RGB face colour
    const auto m = loadMesh(write("c.off", b.bytes));
    ASSERT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 3}));
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 3, 2}));
    ASSERT_EQ(m.colors.size(), 4u);
    for (size_t v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) EXPECT_EQ(m.colors[v][k], rgba[v][k]) << v << " " << k;
    EXPECT_EQ(m.positions[3], (Vec3d{1, 1, 2}));
}

// Every layout svo reads in binary (normals, colours, texture coordinates,
// polygons of 1 to 5 corners, face colours of 0 to 4 components) gives the
// mesh of the same file in text.
TEST_F(MeshIo, BinaryOffGivesTheMeshOfTheSameTextOff)
{
    const int nv = 7;
    const std::vector<std::vector<int32_t>> faces = {{0, 1, 2}, {0, 1, 3, 2}, {2, 3, 4, 5, 6}, {6}, {5, 6}};
    for (const std::string prefix : {"", "C", "N", "ST", "CN", "STC", "STCN", "NC"}) {
        SCOPED_TRACE(prefix);
        const bool normals = prefix.find('N') != std::string::npos, colours = prefix.find('C') != std::string::npos,
                   texture = prefix.find("ST") != std::string::npos;
        BinaryOff b(prefix + "OFF BINARY");
        std::string text = fmt::format("{}OFF\n{} {} 0\n", prefix, nv, faces.size());
        b.i(nv).i(int32_t(faces.size())).i(0);
        for (int v = 0; v < nv; ++v) {
            // Values a float holds exactly, so that text and binary agree bit for bit.
            const float p[3] = {0.25f * float(v), float(v % 3) - 1.5f, 1.0f / float(1 << v)};
            const float c[4] = {0.5f, 0.125f * float(v), 1.0f, 0.75f};
            b.f(p[0]).f(p[1]).f(p[2]);
            text += fmt::format("{} {} {}", p[0], p[1], p[2]);
            if (normals) b.f(0).f(0).f(1), text += " 0 0 1";
            if (colours) b.f(c[0]).f(c[1]).f(c[2]).f(c[3]), text += fmt::format(" {:.4f} {:.4f} {:.4f} {:.4f}", c[0], c[1], c[2], c[3]);
            if (texture) b.f(0.5f).f(0.25f), text += " 0.5 0.25";
            text += '\n';
        }
        for (size_t f = 0; f < faces.size(); ++f) {
            b.i(int32_t(faces[f].size()));
            text += std::to_string(faces[f].size());
            for (int32_t k : faces[f]) b.i(k), text += fmt::format(" {}", k);
            b.i(int32_t(f % 5));
            for (size_t c = 0; c < f % 5; ++c) b.f(0.5f);
            text += '\n';
        }
        const auto fromText = loadMesh(write("t.off", text));
        const auto fromBinary = loadMesh(write("b.off", b.bytes));
        EXPECT_EQ(fromText.triangles.size(), 1u + 2u + 3u + 1u + 1u);
        EXPECT_EQ(fromBinary.colors.size(), colours ? size_t(nv) : 0u);
        expectSameMesh(fromBinary, fromText);
    }
}

// The rest of what a binary file can get wrong: one line naming the file and
// the problem, before any allocation that a count in the file would size.
TEST_F(MeshIo, BinaryOffBadCountsIndicesAndKeywordsAreClearErrors)
{
    const auto face = [](BinaryOff b, int32_t k) { return b.i(3).i(0).i(k).i(2).i(0).bytes; };
    expectError(write("nv.off", BinaryOff().i(-3).i(1).i(0).bytes), "the binary header declares -3 vertices and 1 faces");
    expectError(write("nf.off", BinaryOff().i(3).i(-1).i(0).bytes), "the binary header declares 3 vertices and -1 faces");
    expectError(write("many.off", BinaryOff().i(3).i(std::numeric_limits<int32_t>::max()).i(0).bytes),
                "the header declares 3 vertices and 2147483647 faces, more than the file's 23 bytes can hold");
    expectError(write("manyv.off", BinaryOff().i(1 << 30).i(0).i(0).bytes), "more than the file's 23 bytes can hold");
    expectError(write("range.off", face(BinaryOff::triangle(1), 3)), "face 0 uses vertex index 3, but the file has 3 vertices");
    expectError(write("below.off", face(BinaryOff::triangle(1), -1)), "face 0 uses vertex index -1, but the file has 3 vertices");
    expectError(write("zero.off", BinaryOff::triangle(1).i(0).i(0).i(0).i(0).bytes), "face 0 has 0 vertices");
    for (const int32_t c : {-1, 5, std::numeric_limits<int32_t>::max()})
        expectError(write("colours.off", BinaryOff::triangle(1).i(3).i(0).i(1).i(2).i(c).f(0).f(0).f(0).f(0).f(0).bytes),
                    fmt::format("face 0 has {} colour components (OFF allows 0 to 4)", c));
    BinaryOff nan;
    nan.i(1).i(1).i(0).f(0).f(std::numeric_limits<float>::quiet_NaN()).f(0).i(1).i(0).i(0);
    expectError(write("nan.off", nan.bytes), "vertex 0 has a non-finite coordinate (0, nan, 0)");
    BinaryOff inf("COFF BINARY");
    inf.i(1).i(1).i(0).f(0).f(0).f(0).f(std::numeric_limits<float>::infinity()).f(0).f(0).f(1).i(1).i(0).i(0);
    expectError(write("inf.off", inf.bytes), "vertex 0 has a non-finite colour (inf, 0, 0)");
    expectError(write("x.off", "XOFF BINARY\n" + BinaryOff::triangle(0).bytes.substr(11)), "'XOFF' has fields svo cannot place");
    expectError(write("cc.off", "CCOFF BINARY\n" + BinaryOff::triangle(0).bytes.substr(11)), "'CCOFF' has fields");
    expectError(write("4.off", "4OFF BINARY\n" + BinaryOff::triangle(0).bytes.substr(11)), "not 3D");
    expectError(write("after.off", "OFF BINARY 3 1 0\n"), "line 1: unexpected '3' after BINARY");
    // OpenMesh writes the machine's byte order: such a file is named, not misread.
    std::string little = "OFF BINARY\n";
    for (int32_t k : {3, 1, 0}) put<int32_t>(little, k);
    for (int k = 0; k < 9; ++k) put<float>(little, float(k == 3 || k == 7));
    for (int32_t k : {3, 0, 1, 2, 0}) put<int32_t>(little, k);
    expectError(write("little.off", little), "(a little-endian file? svo reads binary OFF big-endian");
    // Valid, with bytes after the last face (ignored, as text after the last face is).
    EXPECT_EQ(loadMesh(write("tail.off", BinaryOff::triangle(1).i(3).i(0).i(1).i(2).i(0).i(77).bytes)).triangles.size(), 1u);
}

// OBJ materials: the diffuse colour (Kd) of each face's material becomes the
// colour of its corners; a vertex on faces of two colours is split, keeping
// its position, so the triangles cover what they covered.
TEST_F(MeshIo, ObjMaterialColoursFromMtl)
{
    const std::string obj = "mtllib colours.mtl\n"
                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\n"
                            "usemtl red\nf 1 2 3\nf 2 4 3\n"
                            "usemtl sky blue\nf 1 3 5\n"
                            "usemtl grey\nf 2 4 5\n";
    write("colours.mtl", "# a comment\nnewmtl red\nKa 0 0 0\nKd 1 0 0\nnewmtl sky blue\nKd 0.25 0.5 1  # rgb\n"
                         "newmtl grey\nKd 0.5\nmap_Kd t.png\n");
    const std::string path = write("m.obj", obj);
    const TriangleMesh mesh = loadMesh(path);
    EXPECT_TRUE(mesh.warnings.empty());
    const Vec3f red{1, 0, 0}, blue{0.25f, 0.5f, 1}, grey{0.5f, 0.5f, 0.5f};
    const std::vector<Vec3f> expected{red, red, blue, grey};
    const std::vector<std::array<Vec3d, 3>> corners{{Vec3d{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                                    {Vec3d{1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                                                    {Vec3d{0, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                                    {Vec3d{1, 0, 0}, {1, 1, 0}, {0, 0, 1}}};
    ASSERT_EQ(mesh.triangles.size(), 4u);
    ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
    for (size_t t = 0; t < 4; ++t)
        for (size_t k = 0; k < 3; ++k) {
            EXPECT_TRUE(mesh.colors[mesh.triangles[t][k]] == expected[t]) << t << " " << k;
            EXPECT_TRUE(mesh.corners(t)[k] == corners[t][k]) << t << " " << k;
        }
    // Every vertex is on faces of two colours: one copy each.
    EXPECT_EQ(mesh.positions.size(), 5u + 5u);

    // Vertex colours, where every vertex has one, win over materials.
    const TriangleMesh own = loadMesh(write("own.obj", "mtllib colours.mtl\nv 0 0 0 0 1 0\nv 1 0 0 0 1 0\nv 0 1 0 0 1 0\n"
                                                       "usemtl red\nf 1 2 3\n"));
    ASSERT_EQ(own.colors.size(), 3u);
    EXPECT_TRUE(own.colors[0] == (Vec3f{0, 1, 0}));
}

TEST_F(MeshIo, ObjMaterialProblemsAreWarningsOrNamedErrors)
{
    const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    // A library that is not there: the geometry still reads, and the user is told.
    const TriangleMesh gone = loadMesh(write("gone.obj", "mtllib gone.mtl\n" + body + "usemtl red\nf 1 2 3\n"));
    EXPECT_TRUE(gone.colors.empty());
    ASSERT_EQ(gone.warnings.size(), 1u);
    EXPECT_NE(gone.warnings[0].find("line 1: material library 'gone.mtl' not found"), std::string::npos) << gone.warnings[0];
    // A face before any usemtl among faces with colours: no colours, said.
    write("a.mtl", "newmtl red\nKd 1 0 0\n");
    const TriangleMesh part = loadMesh(write("part.obj", "mtllib a.mtl\n" + body + "f 1 2 3\nusemtl red\nf 2 4 3\n"));
    EXPECT_TRUE(part.colors.empty());
    ASSERT_EQ(part.warnings.size(), 1u);
    EXPECT_NE(part.warnings[0].find("1 of 2 faces have no material colour"), std::string::npos) << part.warnings[0];
    // A library name with a blank, and two libraries on one line.
    write("my colours.mtl", "newmtl red\nKd 1 0 0\n");
    write("b.mtl", "newmtl blue\nKd 0 0 1\n");
    const TriangleMesh blank = loadMesh(write("blank.obj", "mtllib my colours.mtl\n" + body + "usemtl red\nf 1 2 3\n"));
    EXPECT_TRUE(blank.warnings.empty());
    ASSERT_EQ(blank.colors.size(), 4u); // the unused vertex 4 too
    EXPECT_TRUE(blank.colors[0] == (Vec3f{1, 0, 0}));
    const TriangleMesh two = loadMesh(write("two.obj", "mtllib a.mtl b.mtl\n" + body + "usemtl red\nf 1 2 3\nusemtl blue\nf 2 4 3\n"));
    EXPECT_TRUE(two.warnings.empty());
    EXPECT_EQ(two.colors.size(), 6u); // vertices 2 and 3 split
    // A damaged library is an error naming it and its line.
    const std::string bad = write("bad.mtl", "newmtl red\nKd 1 zero 0\n");
    try {
        loadMesh(write("bad.obj", "mtllib bad.mtl\n" + body + "usemtl red\nf 1 2 3\n"));
        FAIL() << "a malformed Kd loaded";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(bad + ": line 2: malformed number 'zero' in Kd"), std::string::npos) << e.what();
    }
}

// Materials whose runs cross the pieces a large file is read in give what
// one piece gives.
TEST_F(MeshIo, ObjMaterialsInPiecesGiveWhatOnePieceGives)
{
    std::string obj = "mtllib m.mtl\n";
    for (int i = 0; i < 40; ++i) obj += fmt::format("v {} {} 0\n", i, i % 3);
    for (int i = 0; i < 38; ++i) {
        if (i % 5 == 0) obj += i % 2 ? "usemtl a\n" : "usemtl b\n";
        obj += fmt::format("f {} {} {}\n", i + 1, i + 2, i + 3);
    }
    const detail::MaterialFiles files = [](const std::string& name) -> std::optional<std::string> {
        if (name != "m.mtl") return std::nullopt;
        return std::string("newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n");
    };
    size_t pieces = 0;
    const TriangleMesh whole = detail::readObj("m.obj", obj, size_t(1) << 30, nullptr, files);
    const TriangleMesh cut = detail::readObj("m.obj", obj, 16, &pieces, files);
    EXPECT_GT(pieces, 10u);
    ASSERT_EQ(whole.colors.size(), whole.positions.size());
    expectSameMesh(whole, cut);
}
