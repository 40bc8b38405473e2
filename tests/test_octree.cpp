// The octree layout, the CPU reference build, the structural checks and the
// .svo file format, independent of any GPU.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <set>
#include <unistd.h>

#include "octree_scenes.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/error.h"
#include "svo/core/octree.h"
#include "svo/core/octree_file.h"
#include "svo/core/voxel_attributes.h"
#include "temp_dir.h"

using namespace svo;
namespace fs = std::filesystem;

namespace {

std::vector<uint64_t> sortedUnique(std::vector<uint64_t> k)
{
    std::sort(k.begin(), k.end());
    k.erase(std::unique(k.begin(), k.end()), k.end());
    return k;
}

/// Invariants checked by brute force, independently of checkOctree: walking
/// from the root reaches every node and brick once, and the occupancy of each
/// node is the OR of its voxels.
void expectSound(const Octree& o, const std::vector<uint64_t>& keys)
{
    EXPECT_TRUE(checkOctree(o).empty()) << checkOctree(o).front();
    EXPECT_EQ(octreeKeys(o), sortedUnique(keys));
    // Count voxels under each node by recursion and compare with its mask.
    std::vector<int> visits(o.nodes.size(), 0);
    std::function<uint64_t(uint32_t, uint32_t)> voxelsUnder = [&](uint32_t node, uint32_t level) -> uint64_t {
        ++visits[node];
        const OctreeNode& n = o.nodes[node];
        if (level == o.brickLevel) return n.childMask ? o.bricks.at(n.child).count() : 0;
        uint64_t sum = 0;
        for (uint32_t c = 0; c < 8 && n.childMask; ++c) {
            const uint64_t v = voxelsUnder(n.child + c, level + 1);
            EXPECT_EQ(v > 0, bool(n.childMask >> c & 1)) << "node " << node << " child " << c;
            sum += v;
        }
        return sum;
    };
    EXPECT_EQ(voxelsUnder(0, 0), sortedUnique(keys).size());
    EXPECT_TRUE(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; })) << "orphan or shared node";
}

const test::TempDir tmp("test_octree");
std::string tempPath(const char* name) { return tmp.path(name); }

std::vector<char> readBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// FNV-1a 64, written again here so the test does not trust the writer.
void resign(std::vector<char>& b)
{
    std::memset(b.data() + offsetof(OctreeFileHeader, checksum), 0, 8);
    uint64_t h = 0xcbf29ce484222325ull;
    for (char c : b) h = (h ^ uint8_t(c)) * 0x100000001b3ull;
    std::memcpy(b.data() + offsetof(OctreeFileHeader, checksum), &h, 8);
}

void expectRejected(const std::vector<char>& bytes, const std::string& fragment)
{
    try {
        parseOctree(bytes.data(), bytes.size(), "bad.svo");
        ADD_FAILURE() << "accepted a file that should fail with: " << fragment;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.svo"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

} // namespace

TEST(Octree, DepthComesFromTheGridExtent)
{
    EXPECT_EQ(brickLevelFor(test::gridOf(1, 1, 1)), 0u);
    EXPECT_EQ(brickLevelFor(test::gridOf(8, 8, 8)), 0u);
    EXPECT_EQ(brickLevelFor(test::gridOf(9, 1, 1)), 1u);
    EXPECT_EQ(brickLevelFor(test::gridOf(3, 300, 7)), 6u); // 38 bricks -> 64
    EXPECT_EQ(brickLevelFor(test::gridOf(1, 1, 1u << 21)), 18u);
}

TEST(Octree, RandomSetsBuildSoundOctrees)
{
    for (auto dims : {std::array<uint32_t, 3>{1, 1, 1}, {8, 8, 8}, {9, 17, 33}, {100, 3, 250}, {513, 64, 64}}) {
        const GridSpec g = test::gridOf(dims[0], dims[1], dims[2]);
        for (size_t n : {size_t(1), size_t(50), size_t(5000)}) {
            const auto keys = test::randomVoxels(g, n, uint32_t(n + dims[0]));
            const Octree o = buildOctree(g, keys);
            expectSound(o, keys);
            EXPECT_EQ(o.brickLevel, brickLevelFor(g));
            EXPECT_TRUE(sameOctree(canonicalOrder(o), o)) << "the reference build is not in canonical order";
        }
    }
}

TEST(Octree, SphereShellAndEmptySet)
{
    const GridSpec g = test::gridOf(70, 70, 70);
    const auto shell = test::sphereShell(g, 30.0);
    ASSERT_GT(shell.size(), 10000u);
    const Octree o = buildOctree(g, shell);
    expectSound(o, shell);
    const auto st = octreeStats(o);
    EXPECT_EQ(st.voxels, shell.size());
    EXPECT_EQ(st.occupiedPerLevel.back(), o.bricks.size());
    EXPECT_EQ(st.bytes, o.nodes.size() * 8 + o.bricks.size() * 64);

    const Octree empty = buildOctree(g, {});
    EXPECT_TRUE(checkOctree(empty).empty());
    EXPECT_EQ(empty.nodes.size(), 1u);
    EXPECT_EQ(empty.voxelCount(), 0u);
}

TEST(Octree, BrickBitsUseOpenVdbLeafOrder)
{
    const GridSpec g = test::gridOf(16, 16, 16);
    // Voxel (9, 2, 5): brick (1, 0, 0), bit (1<<6)|(2<<3)|5 = 85 -> word 1, bit 21.
    const Octree o = buildOctree(g, {packVoxelKey(9, 2, 5)});
    ASSERT_EQ(o.bricks.size(), 1u);
    EXPECT_EQ(o.bricks[0].words[1], uint64_t(1) << 21);
    const auto refs = occupiedBricks(o);
    ASSERT_EQ(refs.size(), 1u);
    EXPECT_EQ(refs[0].origin, (std::array<uint32_t, 3>{8, 0, 0}));
    // Child order c = x + 2y + 4z: brick x=1 is child 1 of the root.
    EXPECT_EQ(o.nodes[0].childMask, 2u);
}

TEST(Octree, LeavesHoldEveryVoxelInGlobalIndexSpace)
{
    const GridSpec g = test::gridOf(100, 3, 250); // anchor (-64, 8, 1024)
    const auto keys = test::randomVoxels(g, 5000, 7);
    std::set<std::array<int64_t, 3>> want;
    for (uint64_t k : keys) want.insert(g.toGlobal(unpackVoxelKey(k)));
    const OctreeLeaves leaves = octreeLeaves(buildOctree(g, keys));
    ASSERT_EQ(leaves.origins.size(), leaves.masks.size());
    std::set<std::array<int64_t, 3>> got;
    for (size_t i = 0; i < leaves.origins.size(); ++i) {
        const auto& o = leaves.origins[i];
        for (int a = 0; a < 3; ++a) EXPECT_EQ(o[size_t(a)] % 8, 0);
        EXPECT_NE(leaves.masks[i].count(), 0u) << "an empty leaf";
        for (uint32_t v = 0; v < 512; ++v) // OpenVDB's leaf order: x major, z minor
            if ((leaves.masks[i].words[v >> 6] >> (v & 63)) & 1u)
                got.insert({o[0] + int64_t(v >> 6), o[1] + int64_t((v >> 3) & 7), o[2] + int64_t(v & 7)});
    }
    EXPECT_EQ(got, want);
}

TEST(Octree, BricksMergeAndCanonicalOrderIsUnique)
{
    const GridSpec g = test::gridOf(40, 40, 40);
    const auto keys = test::randomVoxels(g, 2000, 5);
    // The same voxels given as bricks, in reverse, split in two halves each.
    std::vector<std::pair<uint64_t, Brick>> bricks;
    for (auto it = keys.rbegin(); it != keys.rend(); ++it) {
        Brick b;
        const uint32_t bit = uint32_t(*it & 511);
        b.words[bit >> 6] = uint64_t(1) << (bit & 63);
        bricks.emplace_back(brickOfKey(*it), b);
    }
    bricks.emplace_back(packVoxelKey(8, 8, 8), Brick{}); // empty: dropped
    EXPECT_TRUE(sameOctree(buildOctreeFromBricks(g, bricks), buildOctree(g, keys)));
}

TEST(Octree, ChecksCatchBrokenStructure)
{
    const GridSpec g = test::gridOf(64, 64, 64);
    const Octree good = buildOctree(g, test::randomVoxels(g, 300, 9));
    ASSERT_TRUE(checkOctree(good).empty());
    auto expectProblem = [&](const Octree& o, const char* what) {
        const auto p = checkOctree(o);
        ASSERT_FALSE(p.empty()) << "not caught: " << what;
        std::string all;
        for (const auto& s : p) all += s + "\n";
        EXPECT_NE(all.find(what), std::string::npos) << all;
    };
    Octree o = good;
    ASSERT_EQ(o.nodes[0].childMask, 0xFFu);
    o.nodes[0].childMask &= 0x7F; // child 7 is occupied, but the mask says not
    expectProblem(o, "mask bit");
    o = good;
    o.nodes[0].child += 8;
    expectProblem(o, "");
    o = good;
    o.nodes[0].child = 1u << 30;
    expectProblem(o, "outside level");
    o = good;
    o.bricks.push_back(o.bricks[0]);
    expectProblem(o, "orphaned");
    o = good;
    o.bricks[0] = Brick{};
    expectProblem(o, "empty");
    o = good;
    o.levelStart.pop_back();
    expectProblem(o, "level table");
    o = good;
    o.grid.dims = {8, 8, 8};
    expectProblem(o, "");
}

TEST(OctreeFile, RoundTripIsExactAndDeterministic)
{
    const GridSpec g = test::gridOf(90, 20, 130);
    const auto keys = test::randomVoxels(g, 4000, 3);
    const Octree o = buildOctree(g, keys);
    const std::string a = tempPath("a.svo"), b = tempPath("b.svo");
    writeOctreeFile(a, o);
    const Octree r = readOctreeFile(a);
    EXPECT_TRUE(sameOctree(r, o));
    EXPECT_EQ(octreeKeys(r), sortedUnique(keys));
    writeOctreeFile(b, r);
    EXPECT_EQ(readBytes(a), readBytes(b));
    EXPECT_EQ(readBytes(a).size(), sizeof(OctreeFileHeader) + 4 * (o.brickLevel + 2) + 8 * o.nodes.size() + 64 * o.bricks.size());
    fs::remove(a);
    fs::remove(b);
}

TEST(OctreeFile, CorruptFilesAreRejected)
{
    const GridSpec g = test::gridOf(50, 50, 50);
    const Octree o = buildOctree(g, test::randomVoxels(g, 500, 4));
    const std::string path = tempPath("c.svo");
    writeOctreeFile(path, o);
    const std::vector<char> good = readBytes(path);
    fs::remove(path);
    ASSERT_NO_THROW(parseOctree(good.data(), good.size(), "good.svo"));

    auto bad = good;
    bad[0] = 'X';
    expectRejected(bad, "magic");
    bad = good;
    bad[8] = 7;
    expectRejected(bad, "version 7");
    bad = good;
    bad.resize(60);
    expectRejected(bad, "truncated header");
    bad = good;
    bad.resize(good.size() - 10);
    expectRejected(bad, "truncated");
    bad = good;
    bad.push_back(0);
    expectRejected(bad, "trailing data");
    bad = good;
    bad[good.size() - 5] ^= 0x10; // a brick bit
    expectRejected(bad, "checksum");
    bad = good;
    uint64_t nodes = 0;
    std::memcpy(&nodes, bad.data() + offsetof(OctreeFileHeader, nodeCount), 8);
    nodes += 8;
    std::memcpy(bad.data() + offsetof(OctreeFileHeader, nodeCount), &nodes, 8);
    expectRejected(bad, "counts need");
    // A consistent checksum over an inconsistent tree: the structure check catches it.
    bad = good;
    const size_t rootMask = sizeof(OctreeFileHeader) + 4 * (o.brickLevel + 2) + 4;
    bad[rootMask] ^= 0x01 ^ 0x80;
    resign(bad);
    expectRejected(bad, "");
    EXPECT_THROW(readOctreeFile(tempPath("missing.svo")), Error);
}

TEST(OctreeAttributes, CpuChannelsFollowTheirTriangles)
{
    // Two triangles in the plane z = 0.25 (index space), overlapping on x in [2, 4]:
    // red with id 0 and normal +z, blue with id 1 and normal -z (wound the other way).
    TriangleMesh m;
    m.source = "two triangles";
    m.positions = {{0.2, 0.2, 0.25}, {4.2, 0.2, 0.25}, {0.2, 4.2, 0.25}, {2.2, 0.2, 0.25}, {6.2, 4.2, 0.25}, {6.2, 0.2, 0.25}};
    m.triangles = {{0, 1, 2}, {3, 4, 5}};
    m.colors = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    const GridSpec g = makeGrid(m, {0, 1.0});
    RunStats report;
    report.tiles = 7; // replaced, not added to
    Voxelization v = voxelizeCpu(m, g, 0.0, VoxelMode::Conservative, nullptr, &report);
    EXPECT_EQ(v.keys, voxelizeCpu(m, g).keys); // the same voxels, asked for a report or not
    ASSERT_EQ(report.stages.size(), 1u);
    EXPECT_EQ(report.stages[0].name, "voxelize (cpu)");
    EXPECT_GE(report.listEntries, v.keys.size());
    EXPECT_EQ(report.tiles, 1u);
    Octree o = buildOctree(g, v.keys);
    attachAttributesCpu(m, o, kNormals | kTriangles | kColors, 0.0);
    ASSERT_TRUE(checkOctree(o).empty());
    ASSERT_EQ(o.attributes.triangles.size(), o.voxelCount());
    const auto offsets = brickVoxelOffsets(o);
    size_t both = 0, onlyBlue = 0;
    for (const auto& r : occupiedBricks(o)) {
        uint64_t at = offsets[r.index];
        for (uint32_t bit = 0; bit < 512; ++bit) {
            if (!(o.bricks[r.index].words[bit >> 6] >> (bit & 63) & 1)) continue;
            const double x = double(g.anchor[0] + r.origin[0] + (bit >> 6)) * g.voxelSize;
            const int32_t id = o.attributes.triangles[at];
            const Vec3f n = o.attributes.normals[at], c = o.attributes.colors[at];
            if (x >= 3.0 && x <= 3.0) { // inside both footprints
                ++both;
                EXPECT_EQ(id, 0);
                EXPECT_NEAR(c.x, 0.5f, 1e-4);
                EXPECT_NEAR(c.z, 0.5f, 1e-4);
            }
            if (x >= 6.0) {
                ++onlyBlue;
                EXPECT_EQ(id, 1);
                EXPECT_EQ(c.z, 1.0f);
                EXPECT_EQ(n.z, -1.0f);
            }
            if (x <= 1.0) {
                EXPECT_EQ(id, 0);
                EXPECT_EQ(n.z, 1.0f);
                EXPECT_EQ(c.x, 1.0f);
            }
            ++at;
        }
    }
    EXPECT_GT(both, 0u);
    EXPECT_GT(onlyBlue, 0u);

    // Channels survive the file and the canonical relayout.
    const std::string path = tempPath("attr.svo");
    writeOctreeFile(path, o);
    const Octree r = readOctreeFile(path);
    fs::remove(path);
    EXPECT_EQ(r.channels(), uint32_t(kNormals | kTriangles | kColors));
    EXPECT_TRUE(sameOctree(r, canonicalOrder(o)));
    // Without colours in the mesh, the colour channel is left out.
    m.colors.clear();
    attachAttributesCpu(m, o, kNormals | kColors, 0.0);
    EXPECT_EQ(o.channels(), uint32_t(kNormals));
}
