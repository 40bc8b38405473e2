// The host-written header of a GPU-built NanoVDB grid (nano_header.h). Each
// field is what svo::vdb::buildNanoGrid writes (NanoVDB's GridData, Map::set,
// TreeData, RootData), at the byte offsets of nano_layout.h's ABI.
#include "nano_header.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "nano_layout.h"

namespace svo::gl {
namespace {

template <typename T>
void put(std::vector<uint8_t>& b, size_t at, const T& v)
{
    std::memcpy(b.data() + at, &v, sizeof v);
}

bool hasStats(NanoKind kind) { return kind == NanoKind::Float || kind == NanoKind::Int32 || kind == NanoKind::Vec3f; }
uint32_t valueWords(NanoKind kind) { return kind == NanoKind::Vec3f ? 3 : 1; }
uint32_t rootBytes(NanoKind kind) { return kind == NanoKind::Vec3f ? gpu::kNanoRootBytesVec3f : gpu::kNanoRootBytes; }

/// nanovdb::Map::set(dx, translation, 1.0): a scale, its inverse, the translation, in float and double.
void putMap(std::vector<uint8_t>& b, size_t at, double dx, const std::array<double, 3>& t)
{
    const double inv = 1.0 / dx;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const size_t k = size_t(3 * i + j);
            put(b, at + 4 * k, float(i == j ? dx : 0.0));
            put(b, at + 36 + 4 * k, float(i == j ? inv : 0.0));
            put(b, at + 88 + 8 * k, i == j ? dx : 0.0);
            put(b, at + 160 + 8 * k, i == j ? inv : 0.0);
        }
        put(b, at + 72 + 4 * size_t(i), float(t[size_t(i)]));
        put(b, at + 232 + 8 * size_t(i), t[size_t(i)]);
    }
    put(b, at + 84, 1.0f);
    put(b, at + 256, 1.0);
}

/// nanovdb::Map::applyMap of a diagonal map: the same fused multiply-adds, in the same order.
std::array<double, 3> applyMap(double dx, const std::array<double, 3>& t, const std::array<double, 3>& p)
{
    std::array<double, 3> r{};
    for (int i = 0; i < 3; ++i) {
        const double m0 = i == 0 ? dx : 0.0, m1 = i == 1 ? dx : 0.0, m2 = i == 2 ? dx : 0.0;
        r[size_t(i)] = std::fma(p[0], m0, std::fma(p[1], m1, std::fma(p[2], m2, t[size_t(i)])));
    }
    return r;
}

/// The world box as nanovdb::GridStats sets it: the index box's eight corners, its maximum one past, mapped.
void putWorldBox(std::vector<uint8_t>& b, const NanoGridHeader& h, const NanoTreeFacts& tree)
{
    std::array<double, 3> lo{}, hi{};
    lo.fill(std::numeric_limits<double>::max());
    hi.fill(-std::numeric_limits<double>::max());
    if (tree.any)
        for (int c = 0; c < 8; ++c) {
            const std::array<double, 3> p{double((c & 4) ? tree.bbox[3] + 1 : tree.bbox[0]),
                                          double((c & 2) ? tree.bbox[4] + 1 : tree.bbox[1]),
                                          double((c & 1) ? tree.bbox[5] + 1 : tree.bbox[2])};
            const auto w = applyMap(h.voxelSize, h.translation, p);
            for (size_t a = 0; a < 3; ++a) {
                if (c == 0 || w[a] < lo[a]) lo[a] = w[a];
                if (c == 0 || hi[a] < w[a]) hi[a] = w[a];
            }
        }
    for (size_t a = 0; a < 3; ++a) {
        put(b, 560 + 8 * a, lo[a]);
        put(b, 584 + 8 * a, hi[a]);
    }
}

void putGrid(std::vector<uint8_t>& b, NanoKind kind, const NanoGridHeader& h, const NanoTreeFacts& tree)
{
    put(b, 0, uint64_t(0x304244566f6e614eULL)); // "NanoVDB0"
    put(b, 8, ~uint64_t(0));                     // no checksum (nanovdb::ChecksumMode::Disable)
    put(b, 16, uint32_t(32u << 21 | 4u << 10 | 2u)); // nanovdb::Version() of 32.4.2
    const uint32_t flags = 1u << 5 | (hasStats(kind) ? 1u << 2 : 0u) | (tree.any ? 1u << 1 : 0u); // breadth-first, min/max, bbox
    put(b, 20, flags);
    put(b, 24, uint32_t(0)); // grid index
    put(b, 28, uint32_t(1)); // grid count
    put(b, 32, tree.gridBytes);
    std::memcpy(b.data() + 40, h.name.data(), h.name.size()); // < 256 bytes, the rest stays 0
    putMap(b, 296, h.voxelSize, h.translation);
    putWorldBox(b, h, tree);
    for (size_t a = 0; a < 3; ++a) put(b, 608 + 8 * a, h.voxelSize);
    put(b, 632, kind == NanoKind::Mask ? uint32_t(6) : h.gridClass); // Topology for masks
    put(b, 636, uint32_t(kind));
}

void putTree(std::vector<uint8_t>& b, const NanoTreeFacts& tree)
{
    const size_t at = gpu::kNanoGridBytes;
    const uint64_t treeAt = at;
    for (size_t level = 0; level < 3; ++level)
        put(b, at + 8 * level, tree.nodes[level] ? tree.at[level] - treeAt : uint64_t(0));
    put(b, at + 24, tree.at[3] - treeAt);
    for (size_t level = 0; level < 3; ++level) put(b, at + 32 + 4 * level, tree.nodes[level]);
    put(b, at + 44, tree.activeTiles); // active tiles per level: 8³ tiles only
    put(b, at + 56, tree.voxels);
}

void putRoot(std::vector<uint8_t>& b, NanoKind kind, const NanoGridHeader& h, const NanoTreeFacts& tree)
{
    const size_t at = gpu::kNanoGridBytes + gpu::kNanoTreeBytes;
    const std::array<int32_t, 6> empty{std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::max(),
                                       std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::min(),
                                       std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::min()};
    const auto& box = tree.any ? tree.bbox : empty;
    for (size_t i = 0; i < 6; ++i) put(b, at + 4 * i, box[i]);
    put(b, at + 24, tree.nodes[2]); // table size: one tile per upper node
    const uint32_t background = backgroundWord(kind, h.background);
    if (kind == NanoKind::Mask || kind == NanoKind::Bool) {
        b[at + 28] = uint8_t(background); // a bool
        return;
    }
    // The background, then the minimum and maximum, a value (1 or 3 words) each.
    const uint32_t n = valueWords(kind);
    for (uint32_t c = 0; c < n; ++c) {
        const size_t word = at + 4 * (gpu::kNanoRootBackground + c);
        put(b, word, background);
        put(b, word + 4 * n, tree.any ? tree.minimum[c] : background);
        put(b, word + 8 * n, tree.any ? tree.maximum[c] : background);
    }
}

} // namespace

uint32_t backgroundWord(NanoKind kind, double background)
{
    switch (kind) {
    case NanoKind::Float:
    case NanoKind::Vec3f: { // each component
        const float f = float(background);
        uint32_t bits = 0;
        std::memcpy(&bits, &f, 4);
        return bits;
    }
    case NanoKind::Int32: return uint32_t(int32_t(background));
    case NanoKind::Mask: // a bool, as for Bool
    case NanoKind::Bool: return background != 0.0 ? 1u : 0u;
    }
    return 0u;
}

std::vector<uint8_t> nanoHeader(NanoKind kind, const NanoGridHeader& header, const NanoTreeFacts& tree)
{
    std::vector<uint8_t> b(gpu::kNanoGridBytes + gpu::kNanoTreeBytes + rootBytes(kind), 0);
    putGrid(b, kind, header, tree);
    putTree(b, tree);
    putRoot(b, kind, header, tree);
    return b;
}

uint32_t crc32Of(const void* bytes, size_t n, uint32_t crc)
{
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t e = 0; e < 256; ++e) {
            uint32_t c = e;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[e] = c;
        }
        return t;
    }();
    const auto* p = static_cast<const uint8_t*>(bytes);
    crc = ~crc;
    for (size_t i = 0; i < n; ++i) crc = table[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
    return ~crc;
}

} // namespace svo::gl
