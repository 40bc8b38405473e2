// .vdb output read back with OpenVDB's own reader: the exact voxel set and transform.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <set>
#include <sstream>

#include "scenes.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/error.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_key.h"
#include "svo/vdb_io/vdb_file.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace svo;

namespace {

std::set<std::array<int64_t, 3>> globalVoxels(const Voxelization& v)
{
    std::set<std::array<int64_t, 3>> s;
    for (uint64_t k : v.keys) s.insert(v.grid.toGlobal(unpackVoxelKey(k)));
    return s;
}

openvdb::GridPtrVecPtr readAll(const std::string& path)
{
    openvdb::initialize();
    openvdb::io::File f(path);
    f.open();
    auto grids = f.getGrids();
    f.close();
    return grids;
}

void expectRoundTrip(const TriangleMesh& mesh, const GridRequest& req, bool fog)
{
    const GridSpec grid = makeGrid(mesh, req);
    const Voxelization v = voxelizeCpu(mesh, grid);
    const test::TempDir tmp("vdb_io");
    const std::string path = tmp.path("out.vdb");
    vdb::WriteOptions o;
    o.fog = fog;
    o.metadata["svo:source"] = mesh.source;
    vdb::writeVdb(path, buildOctree(v.grid, v.keys), o);
    auto grids = readAll(path);
    ASSERT_EQ(grids->size(), fog ? 2u : 1u);
    const auto expected = globalVoxels(v);
    for (auto& base : *grids) {
        std::set<std::array<int64_t, 3>> got;
        if (auto mask = openvdb::gridPtrCast<openvdb::MaskGrid>(base)) {
            EXPECT_EQ(mask->getName(), "surface");
            for (auto it = mask->cbeginValueOn(); it; ++it) {
                ASSERT_TRUE(it.isVoxelValue());
                const auto c = it.getCoord();
                got.insert({c.x(), c.y(), c.z()});
            }
        } else if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) {
            EXPECT_EQ(f->getGridClass(), openvdb::GRID_FOG_VOLUME);
            for (auto it = f->cbeginValueOn(); it; ++it) {
                EXPECT_EQ(*it, 1.0f);
                const auto c = it.getCoord();
                got.insert({c.x(), c.y(), c.z()});
            }
        } else {
            FAIL() << "unexpected grid type " << base->type();
        }
        EXPECT_EQ(got, expected);
        EXPECT_EQ(base->metaValue<std::string>("svo:source"), mesh.source);
        // The transform: voxel size and translation exactly as the grid says.
        const auto& xf = base->transform();
        EXPECT_DOUBLE_EQ(xf.voxelSize()[0], grid.voxelSize);
        const auto t = grid.translation();
        const auto origin = xf.indexToWorld(openvdb::Vec3d(0, 0, 0));
        EXPECT_DOUBLE_EQ(origin[0], t[0]);
        EXPECT_DOUBLE_EQ(origin[1], t[1]);
        EXPECT_DOUBLE_EQ(origin[2], t[2]);
        // World bounds of the voxels match the mesh's within one voxel.
        const auto bbox = base->evalActiveVoxelBoundingBox();
        const auto lo = xf.indexToWorld(bbox.min()), hi = xf.indexToWorld(bbox.max());
        const auto mb = mesh.bounds();
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(lo[a], mb.min[a], grid.voxelSize * 1.0001);
            EXPECT_NEAR(hi[a], mb.max[a], grid.voxelSize * 1.0001);
        }
    }
    fs::remove(path);
}

} // namespace

TEST(VdbIo, SphereRoundTripsExactly) { expectRoundTrip(test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24), {100, 0}, true); }

TEST(VdbIo, FarFromOriginKeepsTheLatticeAndTheVoxels)
{
    // 1e9 world units away, at a voxel size that divides 1e9: the grid is
    // shifted by whole voxels and the voxel set is the same as at the origin.
    const double h = 1.0 / 64;
    const auto near = test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24);
    auto far = near;
    for (auto& p : far.positions) p = p + Vec3d{1e9, -1e9, 1e9};
    expectRoundTrip(far, {0, h}, false);
    const auto a = voxelizeCpu(near, makeGrid(near, {0, h}));
    const auto b = voxelizeCpu(far, makeGrid(far, {0, h}));
    EXPECT_EQ(a.keys.size(), b.keys.size());
    std::set<std::array<int64_t, 3>> sa, sb;
    const int64_t shift = int64_t(1e9 / h);
    for (auto v : globalVoxels(a)) sa.insert(v);
    for (auto v : globalVoxels(b)) {
        const auto& g = b.grid;
        sb.insert({v[0] + g.shift[0] - shift, v[1] + g.shift[1] + shift, v[2] + g.shift[2] - shift});
    }
    EXPECT_EQ(sa, sb);
}

TEST(VdbIo, UnwritableFolderIsAnErrorAndLeavesNothing)
{
    const auto mesh = test::box({0, 0, 0}, {1, 1, 1});
    const auto v = voxelizeCpu(mesh, makeGrid(mesh, {8, 0}));
    EXPECT_THROW(vdb::writeVdb("/nonexistent-folder/out.vdb", buildOctree(v.grid, v.keys), {}), svo::Error);
}

// svo writes a grid's leaf buffers on all cores (parallel_buffers.h) and
// must give OpenVDB's own bytes: a level set sphere of thousands of leaves
// (many chunks), and a bool, a mask, an int and a vector grid, written by svo
// and by openvdb::io::File, differ only in the header's random UUID (bytes
// 21-56: magic, versions and the offsets flag come before it).
TEST(VdbIo, ParallelLeafBuffersWriteOpenVdbsOwnBytes)
{
    openvdb::initialize();
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(40.0f, openvdb::Vec3f(1.5f, -2.f, 0.5f),
                                                                         0.5f, 3.0f);
    sphere->setName("surface");
    ASSERT_GT(sphere->tree().leafCount(), 2000u);
    auto flags = openvdb::BoolGrid::create(false);
    auto mask = openvdb::MaskGrid::create();
    auto ids = openvdb::Int32Grid::create(-1);
    auto normals = openvdb::Vec3SGrid::create();
    uint32_t seed = 7;
    for (int i = 0; i < 20000; ++i) {
        seed = seed * 1664525u + 1013904223u;
        const openvdb::Coord c(int(seed % 300) - 150, int((seed >> 9) % 300), int((seed >> 18) % 64));
        flags->tree().setValue(c, (seed >> 3) & 1);
        mask->tree().setValueOn(c);
        ids->tree().setValue(c, int(seed >> 4));
        normals->tree().setValue(c, openvdb::Vec3s(float(seed % 7), -1.0f, float(i)));
    }
    flags->setName("flags"), mask->setName("mask"), ids->setName("ids"), normals->setName("normals");
    const openvdb::GridPtrVec grids{sphere, flags, mask, ids, normals};
    test::TempDir dir("parallel_buffers");
    vdb::writeVdbGrids(dir.path("svo.vdb"), grids, {{"svo:test", "1"}});
    {
        openvdb::io::File reference(dir.path("openvdb.vdb"));
        reference.write(grids);
        reference.close();
    }
    auto bytes = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const std::string ours = bytes(dir.path("svo.vdb")), theirs = bytes(dir.path("openvdb.vdb"));
    ASSERT_EQ(ours.size(), theirs.size());
    ASSERT_GT(ours.size(), 100000u);
    // The first byte that differs outside the UUID (none: the file's size).
    size_t differs = ours.size();
    for (size_t i = 0; i < ours.size() && differs == ours.size(); ++i)
        if ((i < 21 || i >= 57) && ours[i] != theirs[i]) differs = i;
    EXPECT_EQ(differs, ours.size()) << "the files differ at byte " << differs;
    EXPECT_EQ(readAll(dir.path("svo.vdb"))->size(), 5u);
}

// --- damaged files (issue 17, item 5) ------------------------------------

namespace {

using Bytes = std::string;

Bytes readBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const std::string& path, const Bytes& b) { std::ofstream(path, std::ios::binary) << b; }

/// A .vdb svo writes for a sphere: a mask or bool grid "surface", with a fog grid when asked.
Bytes svoVdb(const test::TempDir& tmp, vdb::Topology topology, bool fog)
{
    const auto mesh = test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24);
    const Voxelization v = voxelizeCpu(mesh, makeGrid(mesh, {64, 0}));
    vdb::WriteOptions o;
    o.topology = topology;
    o.fog = fog;
    const std::string path = tmp.path("written.vdb");
    vdb::writeVdb(path, buildOctree(v.grid, v.keys), o);
    return readBytes(path);
}

/// Writes `bytes` as `file` and expects readVdbBricks to refuse it with one
/// line naming the file and saying it is damaged.
void expectRefused(const test::TempDir& tmp, const std::string& file, const Bytes& bytes,
                   const std::string& gridName = {})
{
    const std::string path = tmp.path(file);
    writeBytes(path, bytes);
    try {
        vdb::readVdbBricks(path, gridName);
        ADD_FAILURE() << file << ": read without an error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(what.find("truncated or damaged"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

Bytes flipped(Bytes b, size_t at, size_t n)
{
    for (size_t i = at; i < at + n && i < b.size(); ++i) b[i] = char(~uint8_t(b[i]));
    return b;
}

struct Kind {
    const char* name;
    vdb::Topology topology;
    bool fog;
};
const Kind kKinds[] = {{"mask", vdb::Topology::Mask, false},
                       {"bool", vdb::Topology::Bool, false},
                       {"mask_fog", vdb::Topology::Mask, true},
                       {"bool_fog", vdb::Topology::Bool, true}};

} // namespace

TEST(VdbDamage, UndamagedFilesAreRead)
{
    const test::TempDir tmp("vdb_damage");
    for (const Kind& k : kKinds) {
        const Bytes b = svoVdb(tmp, k.topology, k.fog);
        // From a file and from a stream holding it, every grid.
        const std::string path = tmp.path(std::string(k.name) + ".vdb");
        writeBytes(path, b);
        const auto fromFile = vdb::readVdbBricks(path);
        std::istringstream in(b);
        const auto fromStream = vdb::readVdbBricks(in, "stream.vdb", "surface");
        EXPECT_EQ(fromFile.bricks.size(), fromStream.bricks.size()) << k.name;
        EXPECT_GT(fromStream.bricks.size(), 100u) << k.name;
        if (k.fog) {
            EXPECT_EQ(vdb::readVdbBricks(path, "density").bricks.size(), fromStream.bricks.size()) << k.name;
        }
    }
}

TEST(VdbDamage, TruncatedByOneByteIsRefused)
{
    const test::TempDir tmp("vdb_damage");
    for (const Kind& k : kKinds) {
        const Bytes b = svoVdb(tmp, k.topology, k.fog);
        expectRefused(tmp, std::string(k.name) + "_cut1.vdb", b.substr(0, b.size() - 1));
    }
}

TEST(VdbDamage, TruncatedAtHalfIsRefused)
{
    const test::TempDir tmp("vdb_damage");
    for (const Kind& k : kKinds) {
        const Bytes b = svoVdb(tmp, k.topology, k.fog);
        expectRefused(tmp, std::string(k.name) + "_half.vdb", b.substr(0, b.size() / 2));
        // Cut anywhere, even inside the header or a descriptor.
        for (size_t n : {size_t(1), size_t(8), size_t(40), size_t(200), b.size() / 3, b.size() - 64})
            expectRefused(tmp, std::string(k.name) + "_cut.vdb", b.substr(0, n));
    }
}

TEST(VdbDamage, SixteenBytesFlippedMidFileAreRefused)
{
    // As in the issue: 16 bytes inverted in the middle of the file. In these
    // files the middle lies in the leaf masks, which mask and bool grids
    // store twice (in the tree and, with the leaf's origin, in the voxel
    // data); OpenVDB keeps the second copy, so a flip there changed voxels
    // (the 64 spurious ones) and one in the first went unseen.
    const test::TempDir tmp("vdb_damage");
    for (const Kind& k : kKinds) {
        const Bytes b = svoVdb(tmp, k.topology, k.fog);
        expectRefused(tmp, std::string(k.name) + "_flip.vdb", flipped(b, b.size() / 2, 16), "surface");
    }
}

TEST(VdbDamage, DamageInAGridNotReadIsRefused)
{
    // The fog grid is damaged; the mask grid asked for is whole.
    const test::TempDir tmp("vdb_damage");
    const Bytes b = svoVdb(tmp, vdb::Topology::Mask, true);
    const size_t density = b.find("density");
    ASSERT_NE(density, Bytes::npos);
    // Its tree and voxel data follow the descriptor: cut them short by
    // dropping 100 bytes at three quarters of the file.
    const size_t at = std::max(density + 2000, b.size() * 3 / 4);
    ASSERT_LT(at + 100, b.size());
    expectRefused(tmp, "fog_cut.vdb", b.substr(0, at) + b.substr(at + 100), "surface");
}

TEST(VdbDamage, AppendedBytesAreRefused)
{
    const test::TempDir tmp("vdb_damage");
    for (const Kind& k : kKinds) {
        const Bytes b = svoVdb(tmp, k.topology, k.fog);
        expectRefused(tmp, std::string(k.name) + "_appended.vdb", b + "garbage bytes after the last grid");
        expectRefused(tmp, std::string(k.name) + "_zero.vdb", b + Bytes(1, '\0'));
    }
}

namespace {

/// A level set sphere written by OpenVDB's own writer, with or without the
/// statistics metadata (file_voxel_count, file_bbox_min/max, ...) and in a
/// given compression.
Bytes openvdbSphere(const test::TempDir& tmp, bool stats, uint32_t compression)
{
    openvdb::initialize();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.0f, openvdb::Vec3f(0.5f, 0, 0), 0.25f);
    grid->setName("sphere");
    const std::string path = tmp.path("openvdb.vdb");
    openvdb::io::File file(path);
    file.setGridStatsMetadataEnabled(stats);
    file.setCompression(compression);
    file.write({grid});
    file.close();
    return readBytes(path);
}

} // namespace

TEST(VdbDamage, FilesFromOpenVdbAreAcceptedWithOrWithoutStatistics)
{
    const test::TempDir tmp("vdb_damage");
    for (bool stats : {true, false})
        for (uint32_t c : {uint32_t(openvdb::io::COMPRESS_NONE),
                           uint32_t(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK),
                           uint32_t(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK)}) {
            const Bytes b = openvdbSphere(tmp, stats, c);
            // OpenVDB writes the statistics only when asked (the default).
            EXPECT_EQ(b.find("file_voxel_count") != Bytes::npos, stats);
            const std::string path = tmp.path("sphere.vdb");
            writeBytes(path, b);
            const auto vb = vdb::readVdbBricks(path);
            EXPECT_EQ(vb.gridName, "sphere");
            uint64_t voxels = 0;
            for (const auto& [key, brick] : vb.bricks) voxels += brick.count();
            EXPECT_EQ(voxels, (*readAll(path))[0]->activeVoxelCount()); // as OpenVDB reads it
            EXPECT_GT(voxels, 1000u);
            // And cut short, they are refused like svo's own.
            expectRefused(tmp, "sphere_cut1.vdb", b.substr(0, b.size() - 1));
        }
}

TEST(VdbDamage, RecordedVoxelCountCatchesAMaskBitThatStillDecodes)
{
    // An uncompressed float grid stores all 512 values of a leaf whatever its
    // mask, so a changed mask bit in the tree still decodes: one voxel more
    // or less. Only the voxel count OpenVDB records finds it; without that
    // record nothing can (the format has no checksum), and the file is read.
    const test::TempDir tmp("vdb_damage");
    openvdb::initialize();
    for (bool stats : {true, false}) {
        auto grid = openvdb::FloatGrid::create(0.0f);
        grid->setName("marked");
        // One leaf whose mask words are a pattern found nowhere else in the file.
        const uint64_t pattern = 0x5a3c96e1f00f7b2dull;
        auto* leaf = grid->tree().touchLeaf(openvdb::Coord(0, 0, 0));
        for (openvdb::Index bit = 0; bit < 64; ++bit)
            if ((pattern >> bit) & 1) leaf->setValueOn(bit, 1.0f);
        const std::string path = tmp.path("marked.vdb");
        openvdb::io::File file(path);
        file.setGridStatsMetadataEnabled(stats);
        file.setCompression(openvdb::io::COMPRESS_NONE);
        file.write({grid});
        file.close();
        Bytes b = readBytes(path);
        Bytes word(8, '\0');
        std::memcpy(word.data(), &pattern, 8);
        const size_t at = b.find(word); // the tree's copy of the mask, which OpenVDB uses
        ASSERT_NE(at, Bytes::npos);
        b[at + 7] = char(uint8_t(b[at + 7]) ^ 0x80); // voxel 63 of the leaf, (0, 7, 7), turned on
        if (stats) {
            expectRefused(tmp, "marked_flip.vdb", b);
        } else {
            const std::string flipPath = tmp.path("marked_flip.vdb");
            writeBytes(flipPath, b);
            EXPECT_EQ(vdb::readVdbBricks(flipPath).bricks.size(), 1u);
        }
    }
}

TEST(VdbDamage, RootTileOffTheLatticeIsRefused)
{
    // A root tile's origin is read as is; one near INT32_MAX and off the
    // 4096 lattice would overflow when OpenVDB takes the tile's bounding box.
    const test::TempDir tmp("vdb_damage");
    openvdb::initialize();
    auto grid = openvdb::MaskGrid::create();
    grid->setName("tiled");
    const int32_t at = 4096 * 7; // a value found nowhere else in the file once statistics are off
    grid->tree().addTile(3, openvdb::Coord(at), true, true);
    const std::string path = tmp.path("tiled.vdb");
    openvdb::io::File file(path);
    file.setGridStatsMetadataEnabled(false);
    file.write({grid});
    file.close();
    const Bytes b = readBytes(path);
    // Whole, it is read up to the expansion it asks for: 4096^3 voxels, 2^27 bricks.
    std::ifstream whole(path, std::ios::binary);
    try {
        vdb::readVdbBricks(whole, path, {}, uint64_t(1) << 26);
        ADD_FAILURE() << "a tile of 2^27 bricks expanded under a limit of 2^26";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("more than svo expands"), std::string::npos) << e.what();
    }
    Bytes coord(12, '\0');
    for (int a = 0; a < 3; ++a) std::memcpy(coord.data() + 4 * a, &at, 4);
    const size_t pos = b.find(coord);
    ASSERT_NE(pos, Bytes::npos);
    ASSERT_EQ(b.find(coord, pos + 1), Bytes::npos);
    for (const int32_t bad : {at + 1, 2147483646}) {
        Bytes d = b;
        for (int a = 0; a < 3; ++a) std::memcpy(d.data() + pos + 4 * a, &bad, 4);
        expectRefused(tmp, "tiled_off.vdb", d);
    }
}

namespace {
/// True when the bytes are well-formed UTF-8 (RFC 3629).
bool isUtf8(const std::string& s)
{
    const auto* p = reinterpret_cast<const unsigned char*>(s.data());
    for (size_t i = 0, n = s.size(); i < n;) {
        const unsigned c = p[i];
        size_t len = c < 0x80 ? 1 : c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
        if (!len || i + len > n) return false;
        uint32_t cp = len == 1 ? c : len == 2 ? c & 0x1F : len == 3 ? c & 0x0F : c & 0x07;
        for (size_t k = 1; k < len; ++k) {
            if ((p[i + k] & 0xC0) != 0x80) return false;
            cp = cp << 6 | (p[i + k] & 0x3F);
        }
        static const uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
        if (cp < least[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
        i += len;
    }
    return true;
}
} // namespace

// A mesh whose name is not UTF-8 (any bytes make a Linux file name): the
// metadata svo stores is valid UTF-8, the bad bytes as \xNN, and
// python3-openvdb reads it (it raised UnicodeDecodeError on the raw bytes).
TEST(VdbIo, StringMetadataIsValidUtf8WhateverTheFileName)
{
    EXPECT_EQ(vdb::validUtf8("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x90\x87.obj"), "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x90\x87.obj");
    EXPECT_EQ(vdb::validUtf8("bad\xff\xfe.obj"), "bad\\xFF\\xFE.obj");
    EXPECT_EQ(vdb::validUtf8("\xc3"), "\\xC3");                 // cut short
    EXPECT_EQ(vdb::validUtf8("\xc0\xaf"), "\\xC0\\xAF");        // overlong '/'
    EXPECT_EQ(vdb::validUtf8("\xed\xa0\x80"), "\\xED\\xA0\\x80"); // a surrogate
    EXPECT_EQ(vdb::validUtf8("\xf4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80"); // above U+10FFFF

    const auto mesh = test::box({0, 0, 0}, {1, 1, 1});
    const auto v = voxelizeCpu(mesh, makeGrid(mesh, {8, 0}));
    const test::TempDir tmp("vdb_utf8");
    const std::string path = tmp.path("out.vdb");
    const std::string source = "/tmp/m\xe9sh\xff.obj"; // Latin-1 é, and a byte no encoding uses
    vdb::WriteOptions o;
    o.topology = vdb::Topology::Bool; // python3-openvdb reads no MaskGrid
    o.metadata["svo:source"] = source;
    vdb::writeVdb(path, buildOctree(v.grid, v.keys), o);
    const auto grids = readAll(path);
    ASSERT_EQ(grids->size(), 1u);
    const std::string stored = (*grids)[0]->metaValue<std::string>("svo:source");
    EXPECT_TRUE(isUtf8(stored)) << stored;
    EXPECT_EQ(stored, "/tmp/m\\xE9sh\\xFF.obj");

    const std::string py = "/usr/bin/python3 -c \"import pyopenvdb; print(pyopenvdb.readAllGridMetadata('" + path +
                           "')[0]['svo:source'])\" 2>&1";
    FILE* p = popen(py.c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string out;
    char buf[512];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    EXPECT_EQ(pclose(p), 0) << out;
    EXPECT_EQ(out, stored + "\n");
}

// A device named like a .vdb file is refused as what it is, not read as an
// empty (or endless) file.
TEST(VdbIo, ADeviceNamedVdbIsRefusedAsADevice)
{
    const test::TempDir tmp("vdb_device");
    const std::string z = tmp.path("z.vdb");
    fs::create_symlink("/dev/zero", z);
    try {
        vdb::readVdbBricks(z);
        FAIL() << "read /dev/zero";
    } catch (const svo::Error& e) {
        EXPECT_EQ(std::string(e.what()), z + ": is a character device, not a .vdb file; svo reads .vdb files that are "
                                             "regular files");
    }
    EXPECT_THROW(vdb::readVdbGrids(z), svo::Error);
}

// Without a grid name a file stands for its main grid: a level set, else a
// grid of voxels (an unsigned field among them), else the first grid; per-voxel channels, which sort
// before the grid they annotate, are never picked over it.
TEST(VdbIo, AFileWithoutAGridNameStandsForItsMainGrid)
{
    auto named = [](openvdb::GridBase::Ptr g, const char* name) {
        g->setName(name);
        return g;
    };
    auto color = named(openvdb::Vec3SGrid::create(), "color");
    auto closest = named(openvdb::Int32Grid::create(-1), "closest_triangle");
    auto surface = named(openvdb::BoolGrid::create(), "surface");
    auto density = openvdb::FloatGrid::create(0.f);
    density->setGridClass(openvdb::GRID_FOG_VOLUME);
    named(density, "density");
    auto field = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.f, openvdb::Vec3f(0.f), 0.25f);
    named(field, "z_level_set");
    openvdb::gridPtrCast<openvdb::Vec3SGrid>(color)->tree().setValueOn(openvdb::Coord(0), openvdb::Vec3s(1.f));
    openvdb::gridPtrCast<openvdb::Int32Grid>(closest)->tree().setValueOn(openvdb::Coord(0), 3);
    openvdb::gridPtrCast<openvdb::BoolGrid>(surface)->tree().setValueOn(openvdb::Coord(0), true);
    density->tree().setValueOn(openvdb::Coord(0), 1.f);

    using List = openvdb::GridPtrVec;
    EXPECT_EQ(vdb::mainGrid(List{color, closest, surface, density, field}), field);
    EXPECT_EQ(vdb::mainGrid(List{color, closest, surface, density}), density);
    EXPECT_EQ(vdb::mainGrid(List{closest, color, surface}), surface);
    EXPECT_EQ(vdb::mainGrid(List{color, closest}), closest); // no grid of voxels: the first in name order
    auto distance = named(openvdb::FloatGrid::create(3.f), "distance"); // an unsigned field's grid
    EXPECT_EQ(vdb::mainGrid(List{closest, distance}), distance);

    // The readers pick the same.
    const test::TempDir tmp("vdb_main_grid");
    const std::string path = tmp.path("grids.vdb");
    openvdb::io::File(path).write(List{color, closest, surface});
    EXPECT_EQ(vdb::readVdbBricks(path).gridName, "surface");
    EXPECT_EQ(vdb::readVdbBricks(path, "color").gridName, "color");
}
