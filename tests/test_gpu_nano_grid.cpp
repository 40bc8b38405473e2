// NanoVDB grids built on the GPU (svo/gl/nano_grid_builder.h) against the CPU
// layout builder (svo::vdb::buildNanoGrid, itself proven against
// nanovdb::openToNanoVDB by test_nanovdb_layout): the whole grid, byte for
// byte, once the host copy gets its checksum (svo::vdb::updateFullChecksum),
// and with the checksum made on the GPU (NanoGridHeader::checksum);
// and against NanoVDB's own host code: nanovdb::isValid (full checksum), a
// ReadAccessor voxel for voxel against the input, and nanovdb_validate on
// the written .nvdb. Then the front door (svo::Voxelizer) on a GL backend,
// whose unsigned fields and surfaces take the GPU builder: the same bytes as
// the CPU layout of the same data. Runs on every GL 4.5 device, llvmpipe included.
#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <gtest/gtest.h>
#include <memory>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/GridValidator.h>
#include <random>
#include <set>

#include "nano_layout.h"
#include "scenes.h"
#include "svo/core/error.h"
#include "svo/gl/buffer.h"
#include "svo/gl/device.h"
#include "svo/gl/field_pipeline.h"
#include "svo/gl/nano_grid_builder.h"
#include "svo/gl/voxelize_pipeline.h"
#include "svo/vdb_io/nanovdb_checksum.h"
#include "svo/vdb_io/nanovdb_file.h"
#include "svo/vdb_io/nanovdb_grids.h"
#include "svo/vdb_io/nanovdb_layout.h"
#include "svo/voxelizer.h"
#include "temp_dir.h"

namespace svo {
namespace {

// The shared layout's facts against NanoVDB's own structs.
using FloatGrid = nanovdb::NanoGrid<float>;
static_assert(sizeof(nanovdb::GridData) == gpu::kNanoGridBytes);
static_assert(sizeof(nanovdb::NanoTree<float>::DataType) == gpu::kNanoTreeBytes);
static_assert(sizeof(nanovdb::NanoRoot<float>::DataType) == gpu::kNanoRootBytes);
static_assert(sizeof(nanovdb::NanoRoot<nanovdb::ValueMask>::DataType) == gpu::kNanoRootBytes);
static_assert(sizeof(nanovdb::NanoRoot<bool>::DataType) == gpu::kNanoRootBytes);
static_assert(sizeof(nanovdb::NanoRoot<float>::DataType::Tile) == gpu::kNanoTileBytes);
using LowerData = nanovdb::NanoLower<float>::DataType;
using UpperData = nanovdb::NanoUpper<float>::DataType;
static_assert(offsetof(LowerData, mFlags) == 4 * gpu::kNanoNodeFlags);
static_assert(offsetof(LowerData, mValueMask) == 4 * gpu::kNanoNodeValueMask);
static_assert(offsetof(LowerData, mChildMask) == 4 * gpu::kNanoLowerChildMask);
static_assert(offsetof(LowerData, mMinimum) == 4 * gpu::kNanoLowerMinimum);
static_assert(offsetof(LowerData, mTable) == 4 * gpu::kNanoLowerTable);
static_assert(sizeof(nanovdb::NanoLower<float>) == 4 * gpu::kNanoLowerWords);
static_assert(sizeof(nanovdb::NanoLower<nanovdb::ValueMask>) == 4 * gpu::kNanoLowerWords);
static_assert(sizeof(nanovdb::NanoLower<bool>) == 4 * gpu::kNanoLowerWords);
static_assert(offsetof(UpperData, mChildMask) == 4 * gpu::kNanoUpperChildMask);
static_assert(offsetof(UpperData, mMinimum) == 4 * gpu::kNanoUpperMinimum);
static_assert(offsetof(UpperData, mTable) == 4 * gpu::kNanoUpperTable);
static_assert(sizeof(nanovdb::NanoUpper<float>) == 4 * gpu::kNanoUpperWords);
static_assert(sizeof(nanovdb::NanoUpper<int32_t>) == 4 * gpu::kNanoUpperWords);
using LeafData = nanovdb::NanoLeaf<float>::DataType;
static_assert(offsetof(LeafData, mFlags) == 4 * gpu::kNanoLeafDifFlags + 3);
static_assert(offsetof(LeafData, mValueMask) == 4 * gpu::kNanoLeafValueMask);
static_assert(offsetof(LeafData, mMinimum) == 4 * gpu::kNanoLeafMinimum);
static_assert(offsetof(LeafData, mValues) == 4 * gpu::kNanoLeafValues);
static_assert(offsetof(nanovdb::NanoLeaf<bool>::DataType, mValues) == 4 * gpu::kNanoLeafBoolValues);
static_assert(sizeof(nanovdb::NanoLeaf<float>) == 4 * gpu::kNanoLeafWordsValue);
static_assert(sizeof(nanovdb::NanoLeaf<int32_t>) == 4 * gpu::kNanoLeafWordsValue);
static_assert(sizeof(nanovdb::NanoLeaf<nanovdb::ValueMask>) == 4 * gpu::kNanoLeafWordsMask);
static_assert(sizeof(nanovdb::NanoLeaf<bool>) == 4 * gpu::kNanoLeafWordsBool);
// Vec3f: values of 3 words, table entries of 4, a larger root.
using Vec3Leaf = nanovdb::NanoLeaf<nanovdb::Vec3f>::DataType;
using Vec3Lower = nanovdb::NanoLower<nanovdb::Vec3f>::DataType;
using Vec3Upper = nanovdb::NanoUpper<nanovdb::Vec3f>::DataType;
using Vec3Root = nanovdb::NanoRoot<nanovdb::Vec3f>::DataType;
static_assert(offsetof(Vec3Leaf, mMinimum) == 4 * gpu::kNanoLeafMinimum && offsetof(Vec3Leaf, mMaximum) == 4 * (gpu::kNanoLeafMinimum + 3));
static_assert(offsetof(Vec3Leaf, mValues) == 4 * gpu::kNanoLeafValuesVec3f);
static_assert(sizeof(nanovdb::NanoLeaf<nanovdb::Vec3f>) == 4 * gpu::kNanoLeafWordsVec3f);
static_assert(offsetof(Vec3Lower, mMinimum) == 4 * gpu::kNanoLowerMinimum && offsetof(Vec3Lower, mMaximum) == 4 * (gpu::kNanoLowerMinimum + 3));
static_assert(offsetof(Vec3Lower, mTable) == 4 * gpu::kNanoLowerTable && sizeof(Vec3Lower::Tile) == 16);
static_assert(sizeof(nanovdb::NanoLower<nanovdb::Vec3f>) == 4 * gpu::kNanoLowerWordsVec3f);
static_assert(offsetof(Vec3Upper, mMinimum) == 4 * gpu::kNanoUpperMinimum && offsetof(Vec3Upper, mTable) == 4 * gpu::kNanoUpperTable);
static_assert(sizeof(nanovdb::NanoUpper<nanovdb::Vec3f>) == 4 * gpu::kNanoUpperWordsVec3f);
static_assert(sizeof(Vec3Root) == gpu::kNanoRootBytesVec3f && sizeof(Vec3Root::Tile) == gpu::kNanoTileBytes);
static_assert(offsetof(Vec3Root, mBackground) == 4 * gpu::kNanoRootBackground && offsetof(Vec3Root, mMinimum) == 4 * (gpu::kNanoRootBackground + 3) &&
              offsetof(Vec3Root, mMaximum) == 4 * (gpu::kNanoRootBackground + 6));
static_assert(offsetof(nanovdb::NanoRoot<float>::DataType, mBackground) == 4 * gpu::kNanoRootBackground &&
              offsetof(nanovdb::NanoRoot<float>::DataType, mMinimum) == 4 * (gpu::kNanoRootBackground + 1) &&
              offsetof(nanovdb::NanoRoot<float>::DataType, mMaximum) == 4 * (gpu::kNanoRootBackground + 2));
static_assert(uint32_t(nanovdb::GridType::Float) == gpu::kNanoTypeFloat &&
              uint32_t(nanovdb::GridType::Int32) == gpu::kNanoTypeInt32 &&
              uint32_t(nanovdb::GridType::Vec3f) == gpu::kNanoTypeVec3f &&
              uint32_t(nanovdb::GridType::Mask) == gpu::kNanoTypeMask &&
              uint32_t(nanovdb::GridType::Boolean) == gpu::kNanoTypeBool);

/// Leaves as both builders take them: value words for the GPU, typed values
/// for the CPU; and 8³ tiles.
struct Leaves {
    std::vector<std::array<int32_t, 3>> origins;
    std::vector<Brick> masks;
    std::vector<uint32_t> words; // 512 per leaf, or empty
    std::vector<gl::NanoTile> tiles;
};

template <typename BuildT>
using ValueOf = typename nanovdb::BuildToValueMap<BuildT>::Type;

template <typename BuildT>
constexpr gl::NanoKind kindOf()
{
    if constexpr (std::is_same_v<BuildT, float>) return gl::NanoKind::Float;
    else if constexpr (std::is_same_v<BuildT, int32_t>) return gl::NanoKind::Int32;
    else if constexpr (std::is_same_v<BuildT, bool>) return gl::NanoKind::Bool;
    else return gl::NanoKind::Mask;
}

template <typename BuildT>
ValueOf<BuildT> fromWord(uint32_t w)
{
    if constexpr (std::is_same_v<BuildT, float>) {
        float f;
        std::memcpy(&f, &w, 4);
        return f;
    } else if constexpr (std::is_same_v<BuildT, int32_t>) {
        return int32_t(w);
    } else {
        return w != 0;
    }
}

template <typename BuildT>
vdb::SparseVoxels<ValueOf<BuildT>> sparse(const Leaves& in, double background)
{
    vdb::SparseVoxels<ValueOf<BuildT>> s;
    s.background = fromWord<BuildT>(gl::backgroundWord(kindOf<BuildT>(), background));
    s.origins = in.origins;
    s.masks = in.masks;
    for (uint32_t w : in.words) s.values.push_back(fromWord<BuildT>(w));
    for (const gl::NanoTile& t : in.tiles) s.tiles.push_back({t.origin, 1, fromWord<BuildT>(t.value), t.active != 0});
    return s;
}

/// NanoVDB's own host code reads the grid: valid with its full checksum, and
/// every input voxel where the input puts it, with its value; the voxels
/// just outside each leaf's neighbourhood hold the background.
template <typename BuildT>
void expectNanoVdbReads(const nanovdb::GridHandle<nanovdb::HostBuffer>& h, const Leaves& in, double background)
{
    const auto* grid = h.template grid<BuildT>();
    ASSERT_NE(grid, nullptr);
    EXPECT_TRUE(nanovdb::isValid(*grid, true, true));
    auto acc = grid->getAccessor();
    const auto bg = fromWord<BuildT>(gl::backgroundWord(kindOf<BuildT>(), background));
    uint64_t wrong = 0, active = 0;
    for (size_t i = 0; i < in.origins.size(); ++i)
        for (uint32_t v = 0; v < 512; ++v) {
            const auto& o = in.origins[i];
            const nanovdb::Coord c(o[0] + int32_t(v >> 6), o[1] + int32_t((v >> 3) & 7), o[2] + int32_t(v & 7));
            const bool on = (in.masks[i].words[v >> 6] >> (v & 63)) & 1u;
            active += on;
            bool ok = acc.isActive(c) == on;
            if constexpr (!std::is_same_v<BuildT, nanovdb::ValueMask>) {
                const auto want = std::is_same_v<BuildT, bool> && in.words.empty()
                                      ? ValueOf<BuildT>(on)
                                      : in.words.empty() ? bg : fromWord<BuildT>(in.words[i * 512 + v]);
                const ValueOf<BuildT> got = acc.getValue(c);
                ok = ok && std::memcmp(&want, &got, sizeof want) == 0;
            }
            if (!ok && ++wrong <= 3) ADD_FAILURE() << "voxel (" << c[0] << ", " << c[1] << ", " << c[2] << ") differs";
        }
    for (const gl::NanoTile& t : in.tiles)
        for (uint32_t v = 0; v < 512; v += 73) { // a spread of its voxels, corners included
            const nanovdb::Coord c(t.origin[0] + int32_t(v >> 6), t.origin[1] + int32_t((v >> 3) & 7),
                                   t.origin[2] + int32_t(v & 7));
            bool ok = acc.isActive(c) == (t.active != 0);
            if constexpr (!std::is_same_v<BuildT, nanovdb::ValueMask>) {
                const ValueOf<BuildT> want = fromWord<BuildT>(t.value), got = acc.getValue(c);
                ok = ok && std::memcmp(&want, &got, sizeof want) == 0;
            }
            if (!ok && ++wrong <= 3) ADD_FAILURE() << "tile voxel (" << c[0] << ", " << c[1] << ", " << c[2] << ") differs";
        }
    EXPECT_EQ(wrong, 0u);
    for (const gl::NanoTile& t : in.tiles) active += t.active ? 512 : 0;
    EXPECT_EQ(grid->activeVoxelCount(), active);
}

/// The first differing byte past the checksum (which differs whenever another byte does), else the checksum.
std::string firstDifference(const uint8_t* a, const uint8_t* b, size_t n)
{
    for (size_t i = 16; i < n; ++i)
        if (a[i] != b[i]) return "byte " + std::to_string(i) + ": " + std::to_string(a[i]) + " vs " + std::to_string(b[i]);
    return "the checksum alone";
}

class GpuNanoGrid : public ::testing::Test {
protected:
    /// Builds the grid both ways and holds them to each other and to NanoVDB.
    template <typename BuildT>
    void expectSameAsCpu(const Leaves& in, const gl::NanoGridHeader& header, bool deviceInput = false)
    {
        vdb::NanoGridInfo info;
        info.name = header.name;
        info.gridClass = nanovdb::GridClass(header.gridClass);
        info.voxelSize = header.voxelSize;
        info.translation = header.translation;
        const auto cpu = vdb::buildNanoGrid<BuildT>(sparse<BuildT>(in, header.background), info);
        gl::Context& context = device.context();
        const gl::Context::Scope scope(context); // the grid's buffer is freed in it too
        gl::NanoGridBuffer gpu;
        gl::NanoLeaves leaves;
        leaves.count = uint32_t(in.origins.size());
        leaves.tileCount = uint32_t(in.tiles.size());
        leaves.tiles = in.tiles.data();
        if (deviceInput) {
            gl::Buffer origins("test origins", 12 * in.origins.size(), in.origins.data());
            gl::Buffer masks("test masks", 64 * in.masks.size(), in.masks.data());
            gl::Buffer values("test values", 4 * in.words.size(), in.words.data());
            leaves.originBuffer = &origins;
            leaves.maskBuffer = &masks;
            leaves.valueBuffer = in.words.empty() ? nullptr : &values;
            gpu = gl::buildNanoGridGpu(context, kindOf<BuildT>(), leaves, header, true);
        } else {
            leaves.origins = in.origins.data();
            leaves.masks = in.masks.data();
            leaves.values = in.words.empty() ? nullptr : in.words.data();
            gpu = gl::buildNanoGridGpu(context, kindOf<BuildT>(), leaves, header, true);
        }
        ASSERT_EQ(gpu.bytes, cpu.size());
        ASSERT_EQ(gpu.host.size(), cpu.size());
        // No checksum from the GPU: NanoVDB's "none", then the CPU's full one on the host copy.
        uint64_t none = 0;
        std::memcpy(&none, gpu.host.data() + 8, 8);
        EXPECT_EQ(none, ~uint64_t(0));
        nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(gpu.host.size());
        std::memcpy(buffer.data(), gpu.host.data(), gpu.host.size());
        nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
        ASSERT_NE(handle.template grid<BuildT>(), nullptr);
        EXPECT_TRUE(nanovdb::isValid(*handle.template grid<BuildT>(), true, true)) << "as built, without a checksum";
        vdb::updateFullChecksum(*handle.template grid<BuildT>());
        EXPECT_EQ(0, std::memcmp(handle.data(), cpu.data(), cpu.size()))
            << header.name << ": " << firstDifference(handle.data(), cpu.data(), cpu.size());
        EXPECT_EQ(gpu.nodes[0], in.origins.size());
        // The checksum made on the GPU (NanoGridHeader::checksum): the whole grid as is.
        if (!deviceInput) {
            gl::NanoGridHeader summed = header;
            summed.checksum = true;
            const gl::NanoGridBuffer withSum = gl::buildNanoGridGpu(context, kindOf<BuildT>(), leaves, summed, true);
            ASSERT_EQ(withSum.host.size(), cpu.size());
            if (in.origins.empty() && in.tiles.empty()) {
                std::memcpy(&none, withSum.host.data() + 8, 8);
                EXPECT_EQ(none, ~uint64_t(0)) << "no leaves: no checksum from the GPU";
            } else {
                EXPECT_EQ(0, std::memcmp(withSum.host.data(), cpu.data(), cpu.size()))
                    << header.name << " (checksum on the GPU): " << firstDifference(withSum.host.data(), cpu.data(), cpu.size());
                uint64_t a = 0, b = 0;
                std::memcpy(&a, withSum.host.data() + 8, 8);
                std::memcpy(&b, cpu.data() + 8, 8);
                EXPECT_EQ(a, b) << header.name << ": checksums";
            }
        }
        expectNanoVdbReads<BuildT>(handle, in, header.background);
        if (HasFailure()) return;
        written.push_back(std::move(handle));
    }

    /// The grids built so far, written as one .nvdb and passed by NanoVDB's validator.
    void TearDown() override
    {
        if (written.empty() || HasFailure()) return;
        test::TempDir dir("gpu_nano_grid");
        const std::string path = dir.path("grids.nvdb");
        vdb::writeNanoVdb(path, written);
        if (std::system("command -v nanovdb_validate > /dev/null 2>&1") != 0) return; // not installed
        const std::string cmd = "nanovdb_validate " + path + " > /dev/null 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }

    // Made and freed inside main: the context's statics outlive it.
    static void SetUpTestSuite() { devicePtr = std::make_unique<gl::Device>(); }
    static void TearDownTestSuite() { devicePtr.reset(); }
    static std::unique_ptr<gl::Device> devicePtr;
    gl::Device& device = *devicePtr;
    std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> written;
};

std::unique_ptr<gl::Device> GpuNanoGrid::devicePtr;

/// Random leaves in a cube of side @a span (voxels) centred on the origin,
/// so over several upper nodes and negative coordinates; some leaves empty.
Leaves randomLeaves(uint32_t count, int32_t span, bool values, uint32_t seed, bool intValues = false)
{
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int32_t> coord(-span / 16, span / 16 - 1);
    Leaves in;
    std::vector<std::array<int32_t, 3>> seen;
    while (in.origins.size() < count) {
        const std::array<int32_t, 3> o{coord(rng) * 8, coord(rng) * 8, coord(rng) * 8};
        if (std::find(seen.begin(), seen.end(), o) != seen.end()) continue;
        seen.push_back(o);
        in.origins.push_back(o);
        Brick b;
        const uint32_t kind = rng() % 5; // empty, one voxel, sparse, dense, full
        for (uint32_t w = 0; w < 8; ++w) {
            const uint64_t r = uint64_t(rng()) << 32 | rng();
            b.words[w] = kind == 0 ? 0 : kind == 2 ? r & (r >> 7) : kind == 3 ? r : kind == 4 ? ~uint64_t(0) : 0;
        }
        if (kind == 1) b.words[rng() % 8] = uint64_t(1) << (rng() % 64);
        in.masks.push_back(b);
    }
    if (!values) return in;
    // Some leaves hold only signed zeros, equal but of different bits: the
    // first of equals in the CPU's order must win, in leaves and in nodes.
    // Others hold few distinct values, or any.
    const float pool[] = {0.0f, -0.0f, 1.5f, -2.25f, 3.0f, -3.0f, 0.125f, 7.0f};
    for (uint32_t leaf = 0; leaf < count; ++leaf) {
        const uint32_t mode = rng() % 3;
        for (uint32_t v = 0; v < 512; ++v) {
            uint32_t w;
            if (intValues) w = uint32_t(int32_t(rng() % 64) - 32);
            else if (mode < 2) std::memcpy(&w, &pool[rng() % (mode == 0 ? 2 : 8)], 4);
            else {
                const float f = std::uniform_real_distribution<float>(-100.0f, 100.0f)(rng);
                std::memcpy(&w, &f, 4);
            }
            in.words.push_back(w);
        }
    }
    return in;
}

/// @a count 8³ tiles added to @a in, on no leaf and no other tile: half of
/// them in lower nodes of their own (far from the leaves, which lie within
/// @a span of the origin), the rest beside leaves; active or not, values
/// from a small pool (signed zeros and the leaves' values among them, so
/// that ties between tiles and children test the order of NanoVDB's
/// statistics: active tiles first).
void addTiles(Leaves& in, uint32_t count, int32_t span, uint32_t seed, bool intValues = false)
{
    std::mt19937 rng(seed);
    std::set<std::array<int32_t, 3>> taken(in.origins.begin(), in.origins.end());
    const float pool[] = {0.0f, -0.0f, 1.5f, -2.25f, 3.0f, -3.0f, 0.125f, 7.0f};
    std::uniform_int_distribution<int32_t> near(-span / 16, span / 16 - 1), far(span / 8 + 32, span / 8 + 63);
    while (in.tiles.size() < count) {
        const bool own = in.tiles.size() % 2 == 0;
        auto coord = [&] { return (own ? far(rng) : near(rng)) * 8; };
        const std::array<int32_t, 3> o{coord(), own ? coord() : near(rng) * 8, coord()};
        if (!taken.insert(o).second) continue;
        gl::NanoTile t;
        t.origin = o;
        if (intValues) t.value = uint32_t(int32_t(rng() % 64) - 32);
        else std::memcpy(&t.value, &pool[rng() % 8], 4);
        t.active = rng() % 3 != 0;
        in.tiles.push_back(t);
    }
}

gl::NanoGridHeader header(const std::string& name, uint32_t gridClass, double background)
{
    gl::NanoGridHeader h;
    h.name = name;
    h.gridClass = gridClass;
    h.voxelSize = 0.037;
    h.translation = {-1.25, 0.5, 3.0 / 7.0};
    h.background = background;
    return h;
}

TEST_F(GpuNanoGrid, RandomFloatLeavesEqualTheCpuBuilder)
{
    for (const uint32_t count : {1u, 2u, 37u, 300u}) {
        SCOPED_TRACE(count);
        expectSameAsCpu<float>(randomLeaves(count, 1024, true, count), header("sdf", 1, 0.2));
        expectSameAsCpu<float>(randomLeaves(count, 9000, true, count + 1), header("fog", 2, 0.0));
        expectSameAsCpu<float>(randomLeaves(count, 300, false, count + 2), header("background only", 0, -3.5));
    }
    // Past one block of the sort's shared-memory steps (1024 entries): the
    // long distances' dispatches and every merge's block steps.
    for (const uint32_t count : {1025u, 5000u}) {
        SCOPED_TRACE(count);
        expectSameAsCpu<float>(randomLeaves(count, 4096, true, count), header("sdf", 1, 0.2));
        expectSameAsCpu<nanovdb::ValueMask>(randomLeaves(count, 9000, false, count + 1), header("topology", 6, 0.0));
    }
}

// The builder's signed flood fill (NanoGridHeader::signedFloodFill) gives
// the bits the host's vdb::signedFloodFill gives on the CPU layout of the
// same leaves, checksum made after: random signs over one to several upper
// nodes (so leaves, lower and upper tables all take the fill), with 8³
// tiles among them, and leaves of no active voxel (a node's first value).
TEST_F(GpuNanoGrid, SignedFloodFillEqualsTheHosts)
{
    gl::Context& context = device.context();
    for (const auto& [count, span] : {std::pair{1u, 300}, {37u, 1024}, {300u, 4096}, {2000u, 9000}}) {
        SCOPED_TRACE(std::to_string(count) + " leaves over " + std::to_string(span));
        Leaves in = randomLeaves(count, span, true, 3 * count);
        std::mt19937 rng(count);
        std::uniform_int_distribution<int32_t> coord(-span / 16, span / 16 - 1);
        for (uint32_t t = 0; t < count / 4; ++t) {
            const std::array<int32_t, 3> o{coord(rng) * 8, coord(rng) * 8, coord(rng) * 8};
            if (std::find(in.origins.begin(), in.origins.end(), o) != in.origins.end()) continue;
            bool twice = false;
            for (const auto& u : in.tiles) twice = twice || (u.origin == o);
            if (twice) continue;
            const float v = t % 2 ? -0.6f : 0.6f;
            uint32_t word = 0;
            std::memcpy(&word, &v, 4);
            in.tiles.push_back({o, word, 0});
        }
        const gl::NanoGridHeader h = header("surface", uint32_t(nanovdb::GridClass::LevelSet), 0.6);
        vdb::NanoGridInfo info;
        info.name = h.name;
        info.gridClass = nanovdb::GridClass::LevelSet;
        info.voxelSize = h.voxelSize;
        info.translation = h.translation;
        info.checksum = false;
        nanovdb::GridHandle<nanovdb::HostBuffer> cpu = vdb::buildNanoGrid<float>(sparse<float>(in, h.background), info);
        vdb::signedFloodFill(*cpu.grid<float>());
        vdb::updateFullChecksum(*cpu.grid<float>());
        const gl::Context::Scope scope(context);
        gl::NanoLeaves leaves;
        leaves.count = uint32_t(in.origins.size());
        leaves.origins = in.origins.data();
        leaves.masks = in.masks.data();
        leaves.values = in.words.data();
        leaves.tileCount = uint32_t(in.tiles.size());
        leaves.tiles = in.tiles.data();
        gl::NanoGridHeader flood = h;
        flood.signedFloodFill = true;
        flood.checksum = true;
        const gl::NanoGridBuffer gpu = gl::buildNanoGridGpu(context, gl::NanoKind::Float, leaves, flood, true);
        ASSERT_EQ(gpu.host.size(), cpu.size());
        EXPECT_EQ(0, std::memcmp(gpu.host.data(), cpu.data(), cpu.size()))
            << firstDifference(gpu.host.data(), cpu.data(), cpu.size());
        EXPECT_GT(gpu.nodes[2], count > 100 ? 1u : 0u);
    }
    gl::NanoLeaves none;
    gl::NanoGridHeader boolFlood = header("mask", 0, 0.0);
    boolFlood.signedFloodFill = true;
    EXPECT_THROW(gl::buildNanoGridGpu(context, gl::NanoKind::Bool, none, boolFlood), InvalidInput);
}

TEST_F(GpuNanoGrid, DeviceInputEqualsTheCpuBuilder)
{
    expectSameAsCpu<float>(randomLeaves(200, 2048, true, 7), header("udf", 0, 2.5), true);
    expectSameAsCpu<nanovdb::ValueMask>(randomLeaves(200, 2048, false, 8), header("topology", 0, 0.0), true);
}

TEST_F(GpuNanoGrid, MaskBoolAndInt32LeavesEqualTheCpuBuilder)
{
    for (const uint32_t count : {1u, 50u, 400u}) {
        SCOPED_TRACE(count);
        expectSameAsCpu<nanovdb::ValueMask>(randomLeaves(count, 5000, false, 10 * count), header("topology", 6, 0.0));
        expectSameAsCpu<bool>(randomLeaves(count, 5000, false, 10 * count + 1), header("mask", 0, 0.0));
        expectSameAsCpu<bool>(randomLeaves(count, 700, true, 10 * count + 2, true), header("bools", 0, 1.0));
        expectSameAsCpu<int32_t>(randomLeaves(count, 3000, true, 10 * count + 3, true), header("closest", 0, -1.0));
    }
}

TEST_F(GpuNanoGrid, TilesEqualTheCpuBuilder)
{
    for (const uint32_t count : {1u, 40u, 700u}) {
        SCOPED_TRACE(count);
        Leaves sdf = randomLeaves(count, 1024, true, 20 * count);
        addTiles(sdf, count, 1024, 20 * count + 1);
        expectSameAsCpu<float>(sdf, header("sdf", 1, 0.2));
        Leaves topology = randomLeaves(count, 5000, false, 20 * count + 2);
        addTiles(topology, 2 * count, 5000, 20 * count + 3);
        expectSameAsCpu<nanovdb::ValueMask>(topology, header("topology", 6, 0.0));
        expectSameAsCpu<bool>(topology, header("solid", 0, 0.0));
        Leaves closest = randomLeaves(count, 3000, true, 20 * count + 4, true);
        addTiles(closest, count, 3000, 20 * count + 5, true);
        expectSameAsCpu<int32_t>(closest, header("closest", 0, -1.0));
    }
    // Tiles alone (no leaf): lower nodes of tiles only; and device leaves with host tiles.
    Leaves tilesOnly;
    addTiles(tilesOnly, 30, 512, 5);
    const size_t before = written.size();
    expectSameAsCpu<float>(tilesOnly, header("tiles", 1, 0.5));
    expectSameAsCpu<nanovdb::ValueMask>(tilesOnly, header("tiles", 6, 0.0));
    // Not for nanovdb_validate: Debian's asserts on a grid of no leaf
    // (NanoVDB.h's PtrDiff of the null first leaf), whoever built it.
    written.resize(before);
    Leaves mixed = randomLeaves(300, 2048, true, 6);
    addTiles(mixed, 300, 2048, 7);
    expectSameAsCpu<float>(mixed, header("udf", 0, 2.5), true);
    // Past one block of the sort's shared-memory steps.
    Leaves many = randomLeaves(1500, 4096, false, 8);
    addTiles(many, 1500, 4096, 9);
    expectSameAsCpu<bool>(many, header("solid", 0, 0.0));
}

/// Vec3f leaves (3 words a value) from host and device input against the
/// CPU builder: values from a pool of vectors of equal squared length but
/// different bits (unit axes both ways, signed zero components), so the
/// first of equals must win in leaves, nodes and the root; and any vectors.
TEST_F(GpuNanoGrid, Vec3fLeavesEqualTheCpuBuilder)
{
    const std::array<float, 3> pool[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}, {-1, 0, 0}, {0.0f, -0.0f, 1}, {0, 0, 0},
                                         {-0.0f, 0, 0}, {0.6f, 0.8f, 0}, {0.8f, 0, 0.6f}};
    for (const uint32_t count : {1u, 60u, 700u, 1500u}) {
        for (const bool deviceInput : {false, true}) {
            SCOPED_TRACE(std::to_string(count) + (deviceInput ? " device" : " host"));
            Leaves in = randomLeaves(count, 3000, false, 30 * count + deviceInput);
            std::mt19937 rng(count);
            std::vector<uint32_t> words(1536 * size_t(count));
            for (size_t i = 0; i < 512 * size_t(count); ++i) {
                std::array<float, 3> v = pool[rng() % 9];
                if ((i / 512) % 3 == 2) // some leaves hold any vectors
                    for (float& c : v) c = std::uniform_real_distribution<float>(-2.0f, 2.0f)(rng);
                std::memcpy(&words[3 * i], v.data(), 12);
            }
            vdb::SparseVoxels<nanovdb::Vec3f> sparse;
            sparse.origins = in.origins;
            sparse.masks = in.masks;
            for (size_t i = 0; i < 512 * size_t(count); ++i) {
                float v[3];
                std::memcpy(v, &words[3 * i], 12);
                sparse.values.emplace_back(v[0], v[1], v[2]);
            }
            const gl::NanoGridHeader h = header("normal", 0, 0.0);
            vdb::NanoGridInfo info;
            info.name = h.name;
            info.voxelSize = h.voxelSize;
            info.translation = h.translation;
            const auto cpu = vdb::buildNanoGrid<nanovdb::Vec3f>(sparse, info);
            gl::Context& context = device.context();
            const gl::Context::Scope scope(context);
            gl::NanoLeaves leaves;
            leaves.count = count;
            gl::Buffer origins("test origins", 12 * in.origins.size(), in.origins.data());
            gl::Buffer masks("test masks", 64 * in.masks.size(), in.masks.data());
            gl::Buffer values("test values", 4 * words.size(), words.data());
            if (deviceInput) {
                leaves.originBuffer = &origins, leaves.maskBuffer = &masks, leaves.valueBuffer = &values;
            } else {
                leaves.origins = in.origins.data(), leaves.masks = in.masks.data(), leaves.values = words.data();
            }
            for (const bool sum : {false, true}) {
                gl::NanoGridHeader hs = h;
                hs.checksum = sum;
                gl::NanoGridBuffer gpu = gl::buildNanoGridGpu(context, gl::NanoKind::Vec3f, leaves, hs, true);
                ASSERT_EQ(gpu.host.size(), cpu.size());
                nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(gpu.host.size());
                std::memcpy(buffer.data(), gpu.host.data(), gpu.host.size());
                nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
                const auto* grid = handle.grid<nanovdb::Vec3f>();
                ASSERT_NE(grid, nullptr);
                if (!sum) vdb::updateFullChecksum(*handle.grid<nanovdb::Vec3f>());
                EXPECT_EQ(0, std::memcmp(handle.data(), cpu.data(), cpu.size()))
                    << (sum ? "checksum on the GPU: " : "") << firstDifference(handle.data(), cpu.data(), cpu.size());
                EXPECT_TRUE(nanovdb::isValid(*grid, true, true));
                // NanoVDB's accessor: every input voxel's state, and the value of every 7th.
                auto acc = grid->getAccessor();
                uint64_t wrong = 0;
                for (size_t i = 0; i < in.origins.size(); ++i)
                    for (uint32_t v = 0; v < 512; v += 7) {
                        const auto& o = in.origins[i];
                        const nanovdb::Coord c(o[0] + int32_t(v >> 6), o[1] + int32_t((v >> 3) & 7), o[2] + int32_t(v & 7));
                        const bool on = (in.masks[i].words[v >> 6] >> (v & 63)) & 1u;
                        const nanovdb::Vec3f got = acc.getValue(c);
                        wrong += acc.isActive(c) != on || std::memcmp(&got, &words[3 * (512 * i + v)], 12) != 0;
                    }
                EXPECT_EQ(wrong, 0u);
                if (sum && !HasFailure()) written.push_back(std::move(handle));
            }
        }
    }
    gl::NanoLeaves bad;
    std::vector<gl::NanoTile> tiles(1);
    bad.tiles = tiles.data();
    bad.tileCount = 1;
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Vec3f, bad, header("tiles", 0, 0.0)), InvalidInput);
}

TEST_F(GpuNanoGrid, NoLeavesGiveAnEmptyGrid)
{
    expectSameAsCpu<float>(Leaves{}, header("empty", 1, 3.0));
    expectSameAsCpu<nanovdb::ValueMask>(Leaves{}, header("empty", 6, 0.0));
    // Vec3f: its own root layout (a larger RootData), no leaves.
    vdb::NanoGridInfo info;
    info.name = "empty";
    info.voxelSize = 0.037;
    info.translation = {-1.25, 0.5, 3.0 / 7.0};
    const auto cpu = vdb::buildNanoGrid<nanovdb::Vec3f>(vdb::SparseVoxels<nanovdb::Vec3f>{}, info);
    gl::NanoGridHeader h = header("empty", 0, 0.0);
    const gl::NanoGridBuffer gpu = gl::buildNanoGridGpu(device.context(), gl::NanoKind::Vec3f, gl::NanoLeaves{}, h, true);
    ASSERT_EQ(gpu.host.size(), cpu.size());
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(gpu.host.size());
    std::memcpy(buffer.data(), gpu.host.data(), gpu.host.size());
    nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
    vdb::updateFullChecksum(*handle.grid<nanovdb::Vec3f>());
    EXPECT_EQ(0, std::memcmp(handle.data(), cpu.data(), cpu.size())) << firstDifference(handle.data(), cpu.data(), cpu.size());
}

TEST_F(GpuNanoGrid, BadLeavesAreRefused)
{
    Leaves in = randomLeaves(20, 512, false, 3);
    gl::NanoLeaves leaves;
    leaves.count = uint32_t(in.origins.size());
    leaves.origins = in.origins.data();
    leaves.masks = in.masks.data();
    in.origins[5] = in.origins[11];
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Mask, leaves, header("twice", 0, 0.0)), InvalidInput);
    in.origins[5] = {8, 4, 0};
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Mask, leaves, header("odd", 0, 0.0)), InvalidInput);
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Mask, leaves, header(std::string(256, 'n'), 0, 0.0)),
                 InvalidInput);
    in.origins[5] = {8, 8, 0};
    // A tile on a leaf, a tile twice, a tile off the lattice, tiles missing.
    std::vector<gl::NanoTile> tiles(2);
    tiles[0].origin = in.origins[7];
    leaves.tiles = tiles.data();
    leaves.tileCount = 1;
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Mask, leaves, header("on a leaf", 0, 0.0)), InvalidInput);
    tiles[0].origin = tiles[1].origin = {4096, 0, 0};
    leaves.tileCount = 2;
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Mask, leaves, header("tile twice", 0, 0.0)), InvalidInput);
    tiles[1].origin = {4096, 3, 0};
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Mask, leaves, header("odd tile", 0, 0.0)), InvalidInput);
    leaves.tiles = nullptr;
    EXPECT_THROW(gl::buildNanoGridGpu(device.context(), gl::NanoKind::Mask, leaves, header("no tiles", 0, 0.0)), InvalidInput);
}

/// The leaves of a NanoVDB grid, shuffled (the GPU sorts them).
template <typename BuildT>
Leaves leavesOf(const nanovdb::NanoGrid<BuildT>& grid, bool values, uint32_t seed)
{
    Leaves in;
    const auto& tree = grid.tree();
    const auto* leaf = tree.template getFirstNode<0>();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i, ++leaf) {
        const auto o = leaf->origin();
        in.origins.push_back({o[0], o[1], o[2]});
        Brick b;
        for (uint32_t w = 0; w < 8; ++w) b.words[w] = leaf->valueMask().template getWord<uint64_t>(w);
        in.masks.push_back(b);
        if (values)
            for (uint32_t v = 0; v < 512; ++v) {
                const auto value = leaf->getValue(v);
                uint32_t w = 0;
                std::memcpy(&w, &value, sizeof value);
                in.words.push_back(w);
            }
    }
    // The same permutation for origins, masks and values.
    std::vector<uint32_t> order(in.origins.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    Leaves out;
    for (uint32_t i : order) {
        out.origins.push_back(in.origins[i]);
        out.masks.push_back(in.masks[i]);
        if (values) out.words.insert(out.words.end(), in.words.begin() + 512 * i, in.words.begin() + 512 * (i + 1));
    }
    return out;
}

template <typename BuildT>
gl::NanoGridHeader headerOf(const nanovdb::NanoGrid<BuildT>& grid)
{
    gl::NanoGridHeader h;
    h.name = grid.gridName();
    h.gridClass = uint32_t(grid.gridClass());
    h.voxelSize = grid.voxelSize()[0];
    for (int i = 0; i < 3; ++i) h.translation[size_t(i)] = grid.map().mVecD[i];
    if constexpr (!std::is_same_v<BuildT, nanovdb::ValueMask>) h.background = double(grid.tree().background());
    return h;
}

/// A mesh's octree (the GL voxelizer) and its distance bricks: the CPU
/// builder's grids of them (vdb_io's nanovdb_grids.h), rebuilt on the GPU
/// from their leaves.
TEST_F(GpuNanoGrid, MeshGridsEqualTheCpuBuilder)
{
    const TriangleMesh mesh = test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24);
    const GridSpec grid = makeGrid(mesh, {96, 0.0});
    VoxelizeSettings settings;
    settings.backend = Backend::Raster;
    settings.attributes = kNormals | kTriangles;
    VoxelizeStats stats;
    const Octree octree = gl::voxelizeMesh(device, mesh, grid, settings, Checkpoint{}, stats);
    GridOptions fog;
    fog.fog = true;
    const auto surface = vdb::octreeToNanoGrids(octree, fog);
    ASSERT_GE(surface.size(), 2u);
    const auto* topology = surface[0].grid<nanovdb::ValueMask>();
    const auto* density = surface[1].grid<float>();
    ASSERT_NE(topology, nullptr);
    ASSERT_NE(density, nullptr);
    ASSERT_GT(topology->tree().nodeCount(0), 100u);
    expectSameAsCpu<nanovdb::ValueMask>(leavesOf(*topology, false, 1), headerOf(*topology));
    expectSameAsCpu<float>(leavesOf(*density, true, 2), headerOf(*density));

    LevelSetOptions ls;
    ls.sign = SignOptions(SignMethod::Winding);
    ls.closestTriangle = true;
    ls.interiorBand = 2.0;
    const DistanceBricks field = gl::levelSetBricks(device, mesh, grid, ls, settings, Checkpoint{}, stats);
    const auto levelSet = vdb::levelSetNanoGrids(field, ls.exteriorBand, ls.interiorBand, grid);
    ASSERT_EQ(levelSet.size(), 2u);
    const auto* sdf = levelSet[0].grid<float>();
    const auto* closest = levelSet[1].grid<int32_t>();
    ASSERT_NE(sdf, nullptr);
    ASSERT_NE(closest, nullptr);
    expectSameAsCpu<float>(leavesOf(*sdf, true, 3), headerOf(*sdf));
    expectSameAsCpu<int32_t>(leavesOf(*closest, true, 4), headerOf(*closest));
}


/// Whether `stats` holds a stage named `name`.
bool hasStage(const VoxelizeStats& stats, const std::string& name)
{
    return std::any_of(stats.stages.begin(), stats.stages.end(), [&](const StageTime& s) { return s.name == name; });
}

/// The same grids, byte for byte (checksums included), each valid with its
/// full checksum; the GPU's kept for nanovdb_validate.
void expectSameBytes(const std::vector<vdb::NanoHandle>& gpu, const std::vector<vdb::NanoHandle>& cpu,
                     std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>>& written)
{
    ASSERT_EQ(gpu.size(), cpu.size());
    for (size_t i = 0; i < gpu.size(); ++i) {
        const std::string name = cpu[i].gridMetaData()->shortGridName();
        ASSERT_EQ(gpu[i].size(), cpu[i].size()) << name;
        EXPECT_EQ(0, std::memcmp(gpu[i].data(), cpu[i].data(), cpu[i].size()))
            << name << ": " << firstDifference(gpu[i].data(), cpu[i].data(), cpu[i].size());
        uint64_t checksum = 0;
        std::memcpy(&checksum, gpu[i].data() + 8, 8);
        EXPECT_NE(checksum, ~uint64_t(0)) << name << ": no checksum";
    }
    for (const auto& h : gpu) {
        nanovdb::HostBuffer b = nanovdb::HostBuffer::create(h.size());
        std::memcpy(b.data(), h.data(), h.size());
        written.emplace_back(std::move(b));
    }
}

/// The front door's scenes: test_nanovdb_layout's closed box and sphere
/// open at its seams, and a sphere without its top cap (a hole whose
/// winding numbers classify bricks far from any triangle voxel by voxel).
std::vector<std::pair<std::string, TriangleMesh>> frontDoorScenes()
{
    TriangleMesh cut = test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24);
    std::vector<std::array<uint32_t, 3>> kept;
    for (const auto& t : cut.triangles)
        if (cut.positions[t[0]][2] + cut.positions[t[1]][2] + cut.positions[t[2]][2] < 3 * (0.1 + 0.6)) kept.push_back(t);
    cut.triangles = std::move(kept);
    return {{"sphere", test::sphere({0.3, -0.2, 0.1}, 1.0, 48, 24)},
            {"box", test::box({-1, -0.5, -0.25}, {1, 0.5, 0.25})},
            {"cut sphere", std::move(cut)}};
}

/// The path before the GPU builder: the same call's bricks read back
/// (levelSetBricks on the compute backend), laid out on the CPU.
std::pair<DistanceBricks, std::vector<vdb::NanoHandle>> readBackLayout(gl::Device& device, const TriangleMesh& mesh,
                                                                      const GridSpec& grid, const LevelSetOptions& ls)
{
    VoxelizeSettings settings;
    settings.backend = Backend::Compute;
    VoxelizeStats stats;
    DistanceBricks field = gl::levelSetBricks(device, mesh, grid, ls, settings, Checkpoint{}, stats);
    std::vector<vdb::NanoHandle> grids = vdb::levelSetNanoGrids(field, ls.exteriorBand, ls.interiorBand, grid);
    return {std::move(field), std::move(grids)};
}

/// levelSetNanoVdb of @a mesh on its 60-voxel grid on the compute backend
/// (a voxel size that is no power of two, so world distances round), its
/// stages in @a stats.
std::vector<vdb::NanoHandle> frontDoorLevelSet(Voxelizer& voxelizer, const TriangleMesh& mesh, const GridSpec& grid,
                                               const LevelSetOptions& ls, VoxelizeStats& stats)
{
    VoxelizeOptions options;
    options.backend = Backend::Compute;
    options.stats = &stats;
    return voxelizer.levelSetNanoVdb(mesh, grid, ls, options);
}

/// The grids a `...NanoVdbOnDevice` call hands its callback, each read back
/// there (the Voxelizer's context current, the buffers GL buffers of it).
template <typename Call>
std::vector<std::vector<uint8_t>> keptOnDevice(Call&& call)
{
    std::vector<std::vector<uint8_t>> out;
    size_t calls = 0;
    call([&](const std::vector<gl::NanoGridBuffer>& grids) {
        ++calls;
        for (const gl::NanoGridBuffer& g : grids) {
            EXPECT_TRUE(glIsBuffer(g.grid.id())) << "a GL buffer of the current context";
            std::vector<uint8_t> bytes(g.bytes);
            g.grid.readBulk(0, bytes.size(), bytes.data());
            out.push_back(std::move(bytes));
        }
    });
    EXPECT_EQ(calls, 1u);
    return out;
}

/// Grids kept on the device hold the host handles' bytes, checksums (the GPU's) included.
void expectSameAsKept(const std::vector<std::vector<uint8_t>>& kept, const std::vector<vdb::NanoHandle>& host)
{
    ASSERT_EQ(kept.size(), host.size());
    for (size_t i = 0; i < kept.size(); ++i) {
        ASSERT_EQ(kept[i].size(), host[i].size()) << "grid " << i;
        EXPECT_EQ(0, std::memcmp(kept[i].data(), host[i].data(), kept[i].size()))
            << "grid " << i << " on the device: " << firstDifference(kept[i].data(), host[i].data(), kept[i].size());
    }
}

/// levelSetNanoVdbOnDevice's grids (compute backend), read back in its
/// callback, are @a host's bytes.
void expectLevelSetKeptOnDevice(Voxelizer& voxelizer, const TriangleMesh& mesh, const GridSpec& grid,
                                const LevelSetOptions& ls, const std::vector<vdb::NanoHandle>& host)
{
    VoxelizeOptions onDevice;
    onDevice.backend = Backend::Compute;
    expectSameAsKept(keptOnDevice([&](const NanoGridsOnDevice& use) {
                         voxelizer.levelSetNanoVdbOnDevice(mesh, grid, ls, onDevice, use);
                     }),
                     host);
}

/// An unsigned field through the front door on a GL backend: its band stays
/// on the device and the GPU builder lays it out ("band leaves", "nanovdb
/// grid (gpu)"), giving the bytes the CPU layout (levelSetNanoGrids) gives
/// of the same call's bricks read back (levelSetBricks, the old path); and
/// NanoVDB's accessor reads each band voxel's distance in world units, the
/// background elsewhere.
TEST_F(GpuNanoGrid, FrontDoorUnsignedFieldsEqualTheCpuLayout)
{
    Voxelizer voxelizer;
    for (const auto& [name, mesh] : frontDoorScenes())
        for (const bool closest : {false, true}) {
            SCOPED_TRACE(name + (closest ? " with closest triangles" : ""));
            const GridSpec grid = makeGrid(mesh, {60, 0.0});
            LevelSetOptions ls;
            ls.unsignedDistance = true;
            ls.exteriorBand = 2.5;
            ls.closestTriangle = closest;
            VoxelizeStats stats;
            const auto gpu = frontDoorLevelSet(voxelizer, mesh, grid, ls, stats);
            EXPECT_TRUE(hasStage(stats, "band leaves"));
            EXPECT_TRUE(hasStage(stats, "nanovdb grid (gpu)"));
            EXPECT_FALSE(hasStage(stats, "band packing"));
            const auto readBack = readBackLayout(device, mesh, grid, ls);
            const DistanceBricks& field = readBack.first;
            const std::vector<vdb::NanoHandle>& cpu = readBack.second;
            expectSameBytes(gpu, cpu, written);
            ASSERT_EQ(gpu.size(), closest ? 2u : 1u);
            expectLevelSetKeptOnDevice(voxelizer, mesh, grid, ls, gpu); // unsigned fields too
            const auto* udf = gpu[0].grid<float>();
            ASSERT_NE(udf, nullptr);
            EXPECT_TRUE(nanovdb::isValid(*udf, true, true));
            EXPECT_EQ(stats.voxels, udf->activeVoxelCount());
            ASSERT_GT(udf->activeVoxelCount(), 1000u);
            auto acc = udf->getAccessor();
            const float background = float(ls.exteriorBand * grid.voxelSize);
            uint64_t wrong = 0, active = 0;
            for (size_t b = 0; b < field.bricks.size(); ++b) {
                uint32_t packed = field.offsets[b];
                for (uint32_t v = 0; v < 512; ++v) {
                    if (!((field.near[b].words[v >> 6] >> (v & 63)) & 1u)) continue;
                    const nanovdb::Coord c(int32_t(field.grid.anchor[0] + 8 * field.bricks[b][0] + (v >> 6)),
                                           int32_t(field.grid.anchor[1] + 8 * field.bricks[b][1] + ((v >> 3) & 7)),
                                           int32_t(field.grid.anchor[2] + 8 * field.bricks[b][2] + (v & 7)));
                    const float want = float(double(field.distances[packed++]) * grid.voxelSize);
                    ++active;
                    if ((!acc.isActive(c) || acc.getValue(c) != want) && ++wrong <= 3)
                        ADD_FAILURE() << "voxel (" << c[0] << ", " << c[1] << ", " << c[2] << ")";
                }
            }
            EXPECT_EQ(wrong, 0u);
            EXPECT_EQ(active, udf->activeVoxelCount());
            EXPECT_EQ(acc.getValue(nanovdb::Coord(1 << 20)), background);
            // The CPU backend's front door: the CPU layout of the CPU's bricks. (Against the
            // GPU's bytes it holds on llvmpipe, but not everywhere: on an H200 one voxel of
            // the sphere, equally near two triangles, kept the other triangle and a distance
            // 3 ulps apart, the multiply-adds fused differently; test_cpu_fields compares
            // the CPU and GPU fields themselves.)
            VoxelizeOptions cpuOptions;
            cpuOptions.backend = Backend::Cpu;
            VoxelizeSettings cpuSettings;
            cpuSettings.backend = Backend::Cpu;
            VoxelizeStats cpuStats;
            const DistanceBricks cpuField = gl::levelSetBricks(device, mesh, grid, ls, cpuSettings, Checkpoint{}, cpuStats);
            expectSameBytes(voxelizer.levelSetNanoVdb(mesh, grid, ls, cpuOptions),
                            vdb::levelSetNanoGrids(cpuField, ls.exteriorBand, ls.interiorBand, grid), written);
            // The grids left on the GPU: the same bytes, read in the callback (the context current there).
            VoxelizeStats deviceStats;
            VoxelizeOptions options;
            options.backend = Backend::Compute;
            options.stats = &deviceStats;
            size_t calls = 0;
            voxelizer.unsignedFieldNanoVdbOnDevice(mesh, grid, ls, options, [&](const std::vector<gl::NanoGridBuffer>& grids) {
                ++calls;
                ASSERT_EQ(grids.size(), cpu.size());
                for (size_t i = 0; i < grids.size(); ++i) {
                    ASSERT_EQ(grids[i].bytes, cpu[i].size());
                    EXPECT_TRUE(glIsBuffer(grids[i].grid.id())) << "a GL buffer of the current context";
                    std::vector<uint8_t> bytes(grids[i].bytes);
                    grids[i].grid.readBulk(0, bytes.size(), bytes.data());
                    EXPECT_EQ(0, std::memcmp(bytes.data(), cpu[i].data(), bytes.size()))
                        << "on the device: " << firstDifference(bytes.data(), cpu[i].data(), bytes.size());
                }
            });
            EXPECT_EQ(calls, 1u);
            EXPECT_EQ(deviceStats.voxels, udf->activeVoxelCount());
            EXPECT_EQ(deviceStats.bricks, udf->tree().nodeCount(0));
            EXPECT_THROW(voxelizer.unsignedFieldNanoVdbOnDevice(mesh, grid, ls, cpuOptions,
                                                                [](const std::vector<gl::NanoGridBuffer>&) {}),
                         Unsupported);
        }
}

/// A band's topology (Voxelizer::bandNanoVdb, `--fill band`): on a GL
/// backend its leaves stay on the device without values, and its distance
/// pass skips triangles at voxels already in the band; the voxels must be
/// exactly the unsigned field's active ones (the full pass's, every
/// distance the least), the grid the CPU backend's bytes and the bytes kept
/// on the device, mask and bool alike, and band()'s OpenVDB grid the same voxels.
TEST_F(GpuNanoGrid, FrontDoorBandsAreTheUnsignedFieldsActiveVoxels)
{
    Voxelizer voxelizer;
    for (const auto& [name, mesh] : frontDoorScenes())
        for (const auto topology : {GridOptions::Topology::Mask, GridOptions::Topology::Bool}) {
            const bool mask = topology == GridOptions::Topology::Mask;
            SCOPED_TRACE(name + (mask ? ", mask" : ", bool"));
            const GridSpec grid = makeGrid(mesh, {60, 0.0});
            const double width = 2.5;
            VoxelizeStats stats;
            VoxelizeOptions options;
            options.backend = Backend::Compute;
            options.stats = &stats;
            std::vector<vdb::NanoHandle> gpu;
            gpu.push_back(voxelizer.bandNanoVdb(mesh, grid, width, options, topology));
            EXPECT_TRUE(hasStage(stats, "band leaves"));
            EXPECT_TRUE(hasStage(stats, "nanovdb grid (gpu)"));
            VoxelizeOptions cpuOptions;
            cpuOptions.backend = Backend::Cpu;
            std::vector<vdb::NanoHandle> cpu;
            cpu.push_back(voxelizer.bandNanoVdb(mesh, grid, width, cpuOptions, topology));
            expectSameBytes(gpu, cpu, written);
            expectSameAsKept(keptOnDevice([&](const NanoGridsOnDevice& use) {
                                 voxelizer.bandNanoVdbOnDevice(mesh, grid, width, options, topology, use);
                             }),
                             gpu);
            LevelSetOptions ls;
            ls.unsignedDistance = true;
            ls.exteriorBand = width;
            VoxelizeStats udfStats;
            const auto udf = frontDoorLevelSet(voxelizer, mesh, grid, ls, udfStats);
            const auto* distance = udf.at(0).grid<float>();
            ASSERT_NE(distance, nullptr);
            ASSERT_GT(distance->activeVoxelCount(), 1000u);
            EXPECT_EQ(gpu[0].gridMetaData()->shortGridName(), std::string("band"));
            EXPECT_EQ(gpu[0].gridMetaData()->activeVoxelCount(), distance->activeVoxelCount());
            EXPECT_EQ(stats.voxels, distance->activeVoxelCount());
            uint64_t missing = 0;
            auto expectHolds = [&](auto* band) {
                ASSERT_NE(band, nullptr);
                EXPECT_TRUE(nanovdb::isValid(*band, true, true));
                auto acc = band->getAccessor();
                const auto* leaf = distance->tree().getFirstNode<0>();
                for (uint32_t i = 0; i < distance->tree().nodeCount(0); ++i, ++leaf)
                    for (auto it = leaf->beginValueOn(); it; ++it)
                        if (!acc.isActive(it.getCoord()) && ++missing <= 3)
                            ADD_FAILURE() << "voxel " << it.getCoord()[0] << ", " << it.getCoord()[1] << ", "
                                          << it.getCoord()[2] << " of the field is not in the band";
            };
            if (mask) expectHolds(gpu[0].grid<nanovdb::ValueMask>());
            else expectHolds(gpu[0].grid<bool>());
            EXPECT_EQ(missing, 0u);
            const openvdb::MaskGrid::Ptr vdbBand = voxelizer.band(mesh, grid, width, options);
            EXPECT_EQ(vdbBand->getName(), "band");
            EXPECT_EQ(vdbBand->activeVoxelCount(), distance->activeVoxelCount());
            auto acc = distance->getAccessor();
            uint64_t outside = 0;
            for (auto it = vdbBand->cbeginValueOn(); it; ++it) {
                const openvdb::Coord c = it.getCoord();
                outside += !acc.isActive(nanovdb::Coord(c.x(), c.y(), c.z()));
            }
            EXPECT_EQ(outside, 0u) << "band() voxels that are not the field's";
        }
}

/// A signed field through the front door on a GL backend. Signed by parity
/// (closed meshes), its band stays on the device, the inside voxels negated
/// there, and the host flood fills the grid read back ("nanovdb flood
/// fill"): the bytes the CPU layout gives of the same call's bricks read back
/// (levelSetBricks, then levelSetNanoGrids, which flood fills its own grid),
/// checksum included. Signed by winding numbers (an open mesh), it keeps the
/// CPU layout. NanoVDB's accessor gives each band voxel its signed distance.
TEST_F(GpuNanoGrid, FrontDoorSignedFieldsEqualTheCpuLayout)
{
    Voxelizer voxelizer;
    std::set<bool> signedBy; // parity or not: both must be seen
    // The box is closed (parity); both spheres are open (winding numbers).
    for (const auto& [name, mesh] : frontDoorScenes())
        for (const bool closest : {false, true}) {
            SCOPED_TRACE(name + (closest ? " with closest triangles" : ""));
            const GridSpec grid = makeGrid(mesh, {60, 0.0});
            LevelSetOptions ls;
            ls.exteriorBand = 2.5;
            ls.interiorBand = 1.5; // unequal bands: a voxel's sign picks its band
            ls.closestTriangle = closest;
            VoxelizeStats stats;
            const auto gpu = frontDoorLevelSet(voxelizer, mesh, grid, ls, stats);
            const bool parity = stats.sign.rfind("parity", 0) == 0;
            EXPECT_TRUE(parity || stats.sign.rfind("winding", 0) == 0) << stats.sign;
            signedBy.insert(parity);
            // Both on the GPU builder; the values beyond parity's band flood filled.
            EXPECT_TRUE(hasStage(stats, "band leaves"));
            EXPECT_TRUE(hasStage(stats, "nanovdb grid (gpu)"));
            EXPECT_FALSE(hasStage(stats, "nanovdb flood fill")) << "the builder's, on the GPU";
            EXPECT_FALSE(hasStage(stats, "band packing"));
            const auto readBack = readBackLayout(device, mesh, grid, ls);
            const DistanceBricks& field = readBack.first;
            const std::vector<vdb::NanoHandle>& cpu = readBack.second;
            expectSameBytes(gpu, cpu, written);
            ASSERT_EQ(gpu.size(), closest ? 2u : 1u);
            expectLevelSetKeptOnDevice(voxelizer, mesh, grid, ls, gpu); // by parity, flood filled there too
            if (!parity) { // the scene has what winding signs add: leaves of inside voxels alone, inside tiles, and (the hole) bricks beyond the band
                size_t insideOnly = 0;
                for (size_t b = 0; b < field.bricks.size(); ++b) {
                    bool any = false;
                    uint32_t packed = field.offsets[b];
                    for (uint32_t v = 0; v < 512; ++v) {
                        if (!((field.near[b].words[v >> 6] >> (v & 63)) & 1u)) continue;
                        const bool inside = (field.signs.inside[b].words[v >> 6] >> (v & 63)) & 1u;
                        any = any || field.distances[packed] < (inside ? ls.interiorBand : ls.exteriorBand);
                        ++packed;
                    }
                    insideOnly += !any && field.signs.inside[b].count();
                }
                EXPECT_GT(insideOnly, 5u);
                EXPECT_GT(field.signs.insideBricks.size(), 20u);
                if (name == "cut sphere") {
                    EXPECT_GT(field.signs.partial.size(), 10u);
                }
            }
            const auto* sdf = gpu[0].grid<float>();
            ASSERT_NE(sdf, nullptr);
            EXPECT_EQ(sdf->gridClass(), nanovdb::GridClass::LevelSet);
            EXPECT_TRUE(nanovdb::isValid(*sdf, true, true));
            EXPECT_EQ(stats.voxels, sdf->activeVoxelCount());
            ASSERT_GT(sdf->activeVoxelCount(), 1000u);
            auto acc = sdf->getAccessor();
            uint64_t wrong = 0, active = 0, negative = 0;
            for (size_t b = 0; b < field.bricks.size(); ++b) {
                uint32_t packed = field.offsets[b];
                for (uint32_t v = 0; v < 512; ++v) {
                    if (!((field.near[b].words[v >> 6] >> (v & 63)) & 1u)) continue;
                    const bool inside = (field.signs.inside[b].words[v >> 6] >> (v & 63)) & 1u;
                    const float d = field.distances[packed++];
                    if (!(d < (inside ? ls.interiorBand : ls.exteriorBand))) continue;
                    const nanovdb::Coord c(int32_t(field.grid.anchor[0] + 8 * field.bricks[b][0] + (v >> 6)),
                                           int32_t(field.grid.anchor[1] + 8 * field.bricks[b][1] + ((v >> 3) & 7)),
                                           int32_t(field.grid.anchor[2] + 8 * field.bricks[b][2] + (v & 7)));
                    const float world = float(double(d) * grid.voxelSize);
                    ++active;
                    negative += inside;
                    if ((!acc.isActive(c) || acc.getValue(c) != (inside ? -world : world)) && ++wrong <= 3)
                        ADD_FAILURE() << "voxel (" << c[0] << ", " << c[1] << ", " << c[2] << ")";
                }
            }
            EXPECT_EQ(wrong, 0u);
            EXPECT_EQ(active, sdf->activeVoxelCount());
            EXPECT_GT(negative, 100u);
            const float background = float(ls.exteriorBand * grid.voxelSize);
            EXPECT_EQ(acc.getValue(nanovdb::Coord(1 << 20)), background);
            // The middle of the sphere, beyond the band: inside, -background.
            const Vec3d centre = grid.toIndex({0.3, -0.2, 0.1});
            EXPECT_EQ(acc.getValue(nanovdb::Coord(int32_t(std::floor(centre[0])), int32_t(std::floor(centre[1])),
                                                  int32_t(std::floor(centre[2])))),
                      -background);
        }
    EXPECT_EQ(signedBy.size(), 2u) << "a scene of each sign method";
}

/// Where the driver's loop limit is under the flood fill's walk of an upper
/// node (SVO_LOOP_LIMIT lowers llvmpipe's for a new context), a parity
/// level set's grid is laid out on the CPU instead, the same bytes, with a
/// warning that says why; it cannot stay on the GPU (Unsupported).
TEST_F(GpuNanoGrid, AFloodFillPastTheLoopLimitIsLaidOutOnTheCpu)
{
    if (!device.context().info().loopLimit) GTEST_SKIP() << "a driver without a loop limit: "
                                                            "SVO_LOOP_LIMIT applies to llvmpipe only";
    const TriangleMesh mesh = test::box({-1, -0.5, -0.25}, {1, 0.5, 0.25}); // closed: parity
    const GridSpec grid = makeGrid(mesh, {60, 0.0});
    VoxelizeStats stats;
    Voxelizer whole;
    const auto want = frontDoorLevelSet(whole, mesh, grid, {}, stats);
    ASSERT_EQ(stats.sign.rfind("parity", 0), 0u) << stats.sign;
    EXPECT_TRUE(stats.warnings.empty());
    setenv("SVO_LOOP_LIMIT", "20000", 1); // over the checksum's and the passes' splits, under an upper node's walk
    Voxelizer limited;
    const auto got = frontDoorLevelSet(limited, mesh, grid, {}, stats);
    VoxelizeOptions onDevice;
    onDevice.backend = Backend::Compute;
    EXPECT_THROW(limited.levelSetNanoVdbOnDevice(mesh, grid, {}, onDevice,
                                                 [](const std::vector<gl::NanoGridBuffer>&) { ADD_FAILURE() << "called"; }),
                 Unsupported);
    unsetenv("SVO_LOOP_LIMIT");
    std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> unused;
    expectSameBytes(got, want, unused);
    EXPECT_TRUE(hasStage(stats, "nanovdb grid (cpu)"));
    ASSERT_EQ(stats.warnings.size(), 1u);
    EXPECT_NE(stats.warnings.front().find("loop limit"), std::string::npos) << stats.warnings.front();
}

/// Solids through the front door on the compute backend: the GPU builder
/// lays out the leaves and 8³ tiles of the same call's bricks (solidBricks)
/// byte for byte as solidNanoGrid does on the CPU, and the CPU backend (the
/// CPU voxelizer and signs) gives the same bytes; the sphere's whole inside
/// bricks are active tiles.
TEST_F(GpuNanoGrid, FrontDoorSolidsEqualTheCpuLayout)
{
    Voxelizer voxelizer;
    for (const auto& [name, mesh] : frontDoorScenes())
        for (const auto topology : {GridOptions::Topology::Mask, GridOptions::Topology::Bool}) {
            const bool mask = topology == GridOptions::Topology::Mask;
            SCOPED_TRACE(name + (mask ? " mask" : " bool"));
            const GridSpec grid = makeGrid(mesh, {60, 0.0});
            VoxelizeOptions options;
            options.backend = Backend::Compute;
            VoxelizeStats stats;
            options.stats = &stats;
            std::vector<vdb::NanoHandle> gpu;
            gpu.push_back(voxelizer.solidNanoVdb(mesh, grid, options, SignOptions{}, topology));
            EXPECT_TRUE(hasStage(stats, "nanovdb grid (gpu)"));
            VoxelizeSettings settings;
            settings.backend = Backend::Compute;
            VoxelizeStats local;
            const SolidBricks bricks = gl::solidBricks(device, mesh, grid, settings, SignOptions{}, Checkpoint{}, local);
            std::vector<vdb::NanoHandle> cpu;
            cpu.push_back(vdb::solidNanoGrid(bricks, grid, topology));
            expectSameBytes(gpu, cpu, written);
            VoxelizeStats deviceStats;
            options.stats = &deviceStats;
            expectSameAsKept(keptOnDevice([&](const NanoGridsOnDevice& use) {
                                 voxelizer.solidNanoVdbOnDevice(mesh, grid, options, SignOptions{}, topology, use);
                             }),
                             gpu);
            EXPECT_EQ(deviceStats.voxels, stats.voxels);
            EXPECT_EQ(deviceStats.bricks, stats.bricks);
            options.backend = Backend::Cpu;
            options.stats = nullptr;
            std::vector<vdb::NanoHandle> onCpu;
            onCpu.push_back(voxelizer.solidNanoVdb(mesh, grid, options, SignOptions{}, topology));
            // Not the cut sphere's: in its hole, centres whose winding number is
            // 1/2 to within float rounding take either side, the CPU's climb
            // one and the GPU's walk the other (test_cpu_fields' WindingTies).
            std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> unused;
            if (name != "cut sphere") {
                SCOPED_TRACE("the CPU backend");
                expectSameBytes(onCpu, gpu, unused);
            }
            const auto* meta = gpu[0].gridMetaData();
            EXPECT_EQ(stats.voxels, meta->activeVoxelCount());
            const auto& tree = *reinterpret_cast<const nanovdb::NanoTree<bool>::DataType*>(
                reinterpret_cast<const uint8_t*>(gpu[0].data()) + sizeof(nanovdb::GridData));
            if (name != "box") {
                EXPECT_GT(tree.mTileCount[0], 10u);
            }
            EXPECT_EQ(tree.mTileCount[0], uint32_t(bricks.signs.insideBricks.size()) + [&] {
                uint32_t whole = 0; // parity's whole bricks inside between band bricks
                for (const auto& run : bricks.signs.runs) whole += run.columns == ~uint64_t(0) ? run.bricks : 0;
                return whole;
            }());
            // The sphere's centre is inside; far away is not.
            const Vec3d centre = grid.toIndex(name != "box" ? Vec3d{0.3, -0.2, 0.1} : Vec3d{0.0, 0.0, 0.0});
            const nanovdb::Coord c(int32_t(std::floor(centre[0])), int32_t(std::floor(centre[1])), int32_t(std::floor(centre[2])));
            if (mask) {
                auto acc = gpu[0].grid<nanovdb::ValueMask>()->getAccessor();
                EXPECT_TRUE(acc.isActive(c));
                EXPECT_FALSE(acc.isActive(nanovdb::Coord(1 << 20)));
            } else {
                auto acc = gpu[0].grid<bool>()->getAccessor();
                EXPECT_TRUE(acc.isActive(c) && acc.getValue(c));
                EXPECT_FALSE(acc.isActive(nanovdb::Coord(1 << 20)) || acc.getValue(nanovdb::Coord(1 << 20)));
            }
        }
}

/// Surfaces through the front door on the GL backends: the topology (mask or
/// bool) and the fog built on the GPU, the channels (normals and colours
/// Vec3f, triangle ids Int32) on the host when read back and on the GPU when
/// kept on the device, all the bytes octreeToNanoGrids lays out from the same
/// call's octree.
TEST_F(GpuNanoGrid, FrontDoorSurfacesEqualTheCpuLayout)
{
    Voxelizer voxelizer;
    for (auto [name, mesh] : frontDoorScenes())
        for (const Backend backend : {Backend::Compute, Backend::Raster})
            for (const auto topology : {GridOptions::Topology::Mask, GridOptions::Topology::Bool}) {
                // Vertex colours of every hue, some equal in squared length (the first of equals kept).
                mesh.colors.resize(mesh.positions.size());
                for (size_t i = 0; i < mesh.positions.size(); ++i)
                    mesh.colors[i] = i % 3 == 0 ? Vec3f{1.0f, 0.0f, 0.0f}
                                     : i % 3 == 1 ? Vec3f{0.0f, 1.0f, 0.0f}
                                                  : Vec3f{float(i % 7) / 7.0f, 0.5f, float(i % 5) / 5.0f};
                SCOPED_TRACE(name + (backend == Backend::Compute ? " compute" : " raster") +
                             (topology == GridOptions::Topology::Mask ? " mask" : " bool"));
                const GridSpec grid = makeGrid(mesh, {72, 0.0});
                VoxelizeOptions options;
                options.backend = backend;
                options.attributes = kNormals | kTriangles | kColors;
                VoxelizeStats stats;
                options.stats = &stats;
                GridOptions grids;
                grids.topology = topology;
                grids.fog = true;
                const auto gpu = voxelizer.voxelizeNanoVdb(mesh, grid, options, grids);
                auto stages = [&](const char* stage) {
                    return std::count_if(stats.stages.begin(), stats.stages.end(),
                                         [&](const StageTime& s) { return s.name == stage; });
                };
                EXPECT_EQ(stages("nanovdb grid (gpu)"), 2);
                EXPECT_EQ(stages("nanovdb channels (cpu)"), 1);
                options.stats = nullptr;
                const Octree octree = voxelizer.voxelize(mesh, grid, options);
                const auto cpu = vdb::octreeToNanoGrids(octree, grids);
                ASSERT_EQ(cpu.size(), 5u); // topology, density, normal, triangle_id, color
                expectSameBytes(gpu, cpu, written);
                expectSameAsKept(keptOnDevice([&](const NanoGridsOnDevice& use) {
                                     voxelizer.octreeNanoVdbOnDevice(octree, grids, options, use);
                                 }),
                                 cpu);
                if (topology == GridOptions::Topology::Mask) {
                    ASSERT_NE(gpu[0].grid<nanovdb::ValueMask>(), nullptr);
                    EXPECT_TRUE(nanovdb::isValid(*gpu[0].grid<nanovdb::ValueMask>(), true, true));
                } else {
                    ASSERT_NE(gpu[0].grid<bool>(), nullptr);
                    EXPECT_TRUE(nanovdb::isValid(*gpu[0].grid<bool>(), true, true));
                }
                const auto* fog = gpu[1].grid<float>();
                ASSERT_NE(fog, nullptr);
                EXPECT_TRUE(nanovdb::isValid(*fog, true, true));
                EXPECT_EQ(fog->activeVoxelCount(), gpu[0].gridMetaData()->activeVoxelCount());
                EXPECT_EQ(fog->tree().root().minimum(), 1.0f);
                EXPECT_EQ(fog->tree().root().maximum(), 1.0f);
            }
}

} // namespace
} // namespace svo
