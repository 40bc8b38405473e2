// NanoVDB grids laid out from sparse leaves (svo/vdb_io/nanovdb_layout.h).
#include "svo/vdb_io/nanovdb_layout.h"

#include <algorithm>
#include <cstring>
#include <fmt/format.h>
#include <limits>
#include <nanovdb/util/GridChecksum.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include "svo/core/error.h"
#include "svo/vdb_io/nanovdb_checksum.h"

namespace svo::vdb {
namespace {

using nanovdb::Coord;
using nanovdb::CoordBBox;

/// Minimum and maximum of active values as nanovdb::Extrema keeps them:
/// scalars by value, vectors by squared length, the first of equals kept.
template <typename V>
struct MinMax {
    bool any = false;
    V lo{}, hi{};
    static auto key(const V& v)
    {
        if constexpr (std::is_same_v<V, nanovdb::Vec3f>) return v.lengthSqr(); // float, as nanovdb::Extrema
        else return v;
    }
    void add(const V& v)
    {
        if (!any) {
            lo = hi = v;
            any = true;
            return;
        }
        if (key(v) < key(lo)) lo = v;
        if (key(hi) < key(v)) hi = v;
    }
    /// A child's extrema, as nanovdb::Extrema merges them: its minimum against
    /// the minimum only, its maximum against the maximum only.
    void add(const MinMax& o)
    {
        if (!o.any) return;
        if (!any) {
            *this = o;
            return;
        }
        if (key(o.lo) < key(lo)) lo = o.lo;
        if (key(hi) < key(o.hi)) hi = o.hi;
    }
};

/// A node's statistics: the bounding box of its active values and their extrema.
template <typename V>
struct NodeStats {
    CoordBBox bbox; // empty by default
    MinMax<V> extrema;
    void addBox(const Coord& lo, const Coord& hi)
    {
        bbox[0].minComponent(lo);
        bbox[1].maxComponent(hi);
    }
    void add(const NodeStats& o)
    {
        if (!o.bbox.empty()) addBox(o.bbox[0], o.bbox[1]);
        extrema.add(o.extrema);
    }
};

bool lessCoord(const std::array<int32_t, 3>& a, const std::array<int32_t, 3>& b) { return a < b; }

std::array<int32_t, 3> masked(const std::array<int32_t, 3>& c, int32_t m) { return {c[0] & ~m, c[1] & ~m, c[2] & ~m}; }

/// Index of a child in an internal node of 2^log2Dim children of 2^childTotal voxels each.
uint32_t childIndex(const std::array<int32_t, 3>& c, int log2Dim, int childTotal)
{
    const int32_t m = (1 << (log2Dim + childTotal)) - 1;
    return (uint32_t((c[0] & m) >> childTotal) << (2 * log2Dim)) | (uint32_t((c[1] & m) >> childTotal) << log2Dim) |
           uint32_t((c[2] & m) >> childTotal);
}

Coord toCoord(const std::array<int32_t, 3>& c) { return Coord(c[0], c[1], c[2]); }

constexpr int kUpperMask = 4095, kLowerMask = 127;

template <typename BuildT, typename V>
constexpr bool hasStats()
{
    return !std::is_same_v<BuildT, nanovdb::ValueMask> && !std::is_same_v<BuildT, bool>;
}

/// The order of every node of the tree (nodes by parent, then index in it).
template <typename V>
struct TreeOrder {
    std::vector<std::array<int32_t, 3>> uppers; // sorted origins
    std::vector<uint64_t> lowers;               // sorted keys: upper rank << 15 | index in it
    std::vector<uint64_t> leaves;               // sorted keys: lower rank << 12 | index in it
    std::vector<uint32_t> leafInput;            // per leaf in order: its index in the input
    std::vector<uint32_t> lowerFirstLeaf;       // per lower, its first leaf (then one past the last)
    std::vector<uint32_t> upperFirstLower;      // per upper, its first lower (then one past the last)
};

template <typename V>
uint32_t upperRank(const TreeOrder<V>& t, const std::array<int32_t, 3>& c)
{
    const auto u = masked(c, kUpperMask);
    return uint32_t(std::lower_bound(t.uppers.begin(), t.uppers.end(), u, lessCoord) - t.uppers.begin());
}

template <typename V>
uint64_t lowerKey(const TreeOrder<V>& t, const std::array<int32_t, 3>& c)
{
    return uint64_t(upperRank(t, c)) << 15 | childIndex(c, 5, 7);
}

template <typename V>
TreeOrder<V> orderTree(const SparseVoxels<V>& in)
{
    TreeOrder<V> t;
    for (const auto& o : in.origins) t.uppers.push_back(masked(o, kUpperMask));
    for (const auto& tile : in.tiles) t.uppers.push_back(masked(tile.origin, kUpperMask));
    std::sort(t.uppers.begin(), t.uppers.end(), lessCoord);
    t.uppers.erase(std::unique(t.uppers.begin(), t.uppers.end()), t.uppers.end());
    for (const auto& o : in.origins) t.lowers.push_back(lowerKey(t, o));
    for (const auto& tile : in.tiles)
        if (tile.level == 1) t.lowers.push_back(lowerKey(t, tile.origin));
    std::sort(t.lowers.begin(), t.lowers.end());
    t.lowers.erase(std::unique(t.lowers.begin(), t.lowers.end()), t.lowers.end());
    std::vector<std::pair<uint64_t, uint32_t>> leaves(in.origins.size());
    for (size_t i = 0; i < in.origins.size(); ++i) {
        const uint64_t lower = uint64_t(std::lower_bound(t.lowers.begin(), t.lowers.end(), lowerKey(t, in.origins[i])) -
                                        t.lowers.begin());
        leaves[i] = {lower << 12 | childIndex(in.origins[i], 4, 3), uint32_t(i)};
    }
    std::sort(leaves.begin(), leaves.end());
    for (size_t i = 1; i < leaves.size(); ++i)
        if (leaves[i].first == leaves[i - 1].first) {
            const auto& o = in.origins[leaves[i].second];
            throw InvalidInput(fmt::format("NanoVDB layout: leaf ({}, {}, {}) given twice", o[0], o[1], o[2]));
        }
    for (const auto& [key, input] : leaves) {
        t.leaves.push_back(key);
        t.leafInput.push_back(input);
    }
    // Children are contiguous per parent: find each parent's first.
    t.lowerFirstLeaf.assign(t.lowers.size() + 1, uint32_t(t.leaves.size()));
    for (size_t i = t.leaves.size(); i-- > 0;) t.lowerFirstLeaf[t.leaves[i] >> 12] = uint32_t(i);
    for (size_t l = t.lowers.size(); l-- > 0;) t.lowerFirstLeaf[l] = std::min(t.lowerFirstLeaf[l], t.lowerFirstLeaf[l + 1]);
    t.upperFirstLower.assign(t.uppers.size() + 1, uint32_t(t.lowers.size()));
    for (size_t i = t.lowers.size(); i-- > 0;) t.upperFirstLower[t.lowers[i] >> 15] = uint32_t(i);
    for (size_t u = t.uppers.size(); u-- > 0;) t.upperFirstLower[u] = std::min(t.upperFirstLower[u], t.upperFirstLower[u + 1]);
    return t;
}

template <typename V>
void checkInput(const SparseVoxels<V>& in, const NanoGridInfo& info)
{
    if (info.name.size() >= nanovdb::GridData::MaxNameSize)
        throw InvalidInput(fmt::format("NanoVDB layout: grid name of {} bytes; NanoVDB holds at most {}", info.name.size(),
                                       nanovdb::GridData::MaxNameSize - 1));
    if (in.masks.size() != in.origins.size() || (!in.values.empty() && in.values.size() != 512 * in.origins.size()))
        throw InvalidInput("NanoVDB layout: leaves, masks and values differ in count");
    for (const auto& o : in.origins)
        if ((o[0] | o[1] | o[2]) & 7)
            throw InvalidInput(fmt::format("NanoVDB layout: leaf origin ({}, {}, {}) is not a multiple of 8", o[0], o[1], o[2]));
    for (const auto& t : in.tiles) {
        const int32_t m = t.level == 1 ? 7 : t.level == 2 ? kLowerMask : -1;
        if (m < 0 || ((t.origin[0] | t.origin[1] | t.origin[2]) & m))
            throw InvalidInput(fmt::format("NanoVDB layout: tile ({}, {}, {}) at level {}: the origin must be a multiple of "
                                           "the tile's size, the level 1 or 2",
                                           t.origin[0], t.origin[1], t.origin[2], t.level));
    }
}

template <typename BuildT, typename V>
NodeStats<V> fillLeaf(typename nanovdb::NanoLeaf<BuildT>::DataType& d, const SparseVoxels<V>& in, uint32_t k)
{
    const auto& o = in.origins[k];
    const Brick& mask = in.masks[k];
    NodeStats<V> s;
    d.mBBoxMin = toCoord(o);
    for (uint32_t w = 0; w < 8; ++w) d.mValueMask.template getWord<uint64_t>(w) = mask.words[w];
    const bool given = !in.values.empty();
    const size_t at = size_t(k) * 512;
    if constexpr (std::is_same_v<BuildT, bool>) {
        if (!given) // the values are the active voxels: the mask's words
            for (uint32_t w = 0; w < 8; ++w) d.mValues.template getWord<uint64_t>(w) = mask.words[w];
        else
            for (uint32_t v = 0; v < 512; ++v) d.mValues.set(v, bool(in.values[at + v]));
    } else if constexpr (!std::is_same_v<BuildT, nanovdb::ValueMask>) {
        if (given)
            for (uint32_t v = 0; v < 512; ++v) d.mValues[v] = in.values[at + v];
        else
            for (uint32_t v = 0; v < 512; ++v)
                d.mValues[v] = in.activeValue && ((mask.words[v >> 6] >> (v & 63)) & 1u) ? *in.activeValue : in.background;
    }
    // The bounding box of the active voxels, as LeafNode::updateBBox sets it.
    Coord lo(8, 8, 8), hi(-1, -1, -1);
    for (uint32_t w = 0; w < 8; ++w)
        for (uint64_t bits = mask.words[w]; bits; bits &= bits - 1) {
            const uint32_t v = w * 64 + uint32_t(__builtin_ctzll(bits));
            const Coord c(int32_t(v >> 6), int32_t((v >> 3) & 7), int32_t(v & 7));
            lo.minComponent(c);
            hi.maxComponent(c);
            if constexpr (hasStats<BuildT, V>()) s.extrema.add(d.mValues[v]);
        }
    if (hi[0] < 0) return s; // no active voxel: no bounding box (flag bit 1 off)
    d.mBBoxMin = toCoord(o) + lo;
    for (int a = 0; a < 3; ++a) d.mBBoxDif[a] = uint8_t(hi[a] - lo[a]);
    d.mFlags = 2;
    s.addBox(d.mBBoxMin, toCoord(o) + hi);
    if constexpr (hasStats<BuildT, V>()) {
        d.mMinimum = s.extrema.lo;
        d.mMaximum = s.extrema.hi;
    }
    return s;
}

/// An internal node's tiles, children, bounding box and extrema; `childStats`
/// gives a child's statistics and byte address, by its index in the parent.
template <typename BuildT, typename NodeData, typename V, typename Tiles, typename Children>
NodeStats<V> fillInternal(NodeData& d, const std::array<int32_t, 3>& origin, const V& background, uint32_t childTotal,
                          Tiles&& tiles, Children&& children)
{
    constexpr uint32_t kSize = sizeof(d.mTable) / sizeof(d.mTable[0]);
    const uint32_t log2Dim = kSize == 32768 ? 5 : 4;
    d.mBBox[0] = toCoord(origin);
    for (uint32_t n = 0; n < kSize; ++n) d.mTable[n].value = background;
    NodeStats<V> s;
    tiles([&](uint32_t n, const V& value, bool active) {
        d.mTable[n].value = value;
        if (!active) return;
        d.mValueMask.setOn(n);
        const Coord c = toCoord(origin) + Coord(int32_t((n >> (2 * log2Dim)) << childTotal),
                                                int32_t(((n >> log2Dim) & ((1u << log2Dim) - 1)) << childTotal),
                                                int32_t((n & ((1u << log2Dim) - 1)) << childTotal));
        s.addBox(c, c + Coord(int32_t(1u << childTotal) - 1));
    });
    // nanovdb::GridStats adds active tiles first, in index order, then children.
    if constexpr (hasStats<BuildT, V>())
        for (auto it = d.mValueMask.beginOn(); it; ++it) s.extrema.add(d.mTable[*it].value);
    children([&](uint32_t n, const uint8_t* child, const NodeStats<V>& cs) {
        d.mChildMask.setOn(n);
        d.mTable[n].child = child - reinterpret_cast<const uint8_t*>(&d);
        s.add(cs);
    });
    if (s.bbox.empty()) {
        d.mBBox = s.bbox; // empty, as nanovdb::GridStats leaves it
        d.mFlags = 1; // nothing active: not rendered, no bounding box
        return s;
    }
    d.mBBox = s.bbox;
    d.mFlags = 2;
    if constexpr (hasStats<BuildT, V>()) {
        d.mMinimum = s.extrema.lo;
        d.mMaximum = s.extrema.hi;
    }
    return s;
}

} // namespace

template <typename BuildT>
nanovdb::GridHandle<nanovdb::HostBuffer> buildNanoGrid(const SparseVoxels<typename nanovdb::BuildToValueMap<BuildT>::Type>& in,
                                                       const NanoGridInfo& info)
{
    using V = typename nanovdb::BuildToValueMap<BuildT>::Type;
    using GridT = nanovdb::NanoGrid<BuildT>;
    using TreeT = nanovdb::NanoTree<BuildT>;
    using RootT = nanovdb::NanoRoot<BuildT>;
    using UpperT = nanovdb::NanoUpper<BuildT>;
    using LowerT = nanovdb::NanoLower<BuildT>;
    using LeafT = nanovdb::NanoLeaf<BuildT>;
    checkInput(in, info);
    const TreeOrder<V> t = orderTree(in);
    const size_t nUpper = t.uppers.size(), nLower = t.lowers.size(), nLeaf = t.leaves.size();

    // Byte offsets, breadth-first.
    const uint64_t treeAt = GridT::memUsage(), rootAt = treeAt + TreeT::memUsage();
    const uint64_t upperAt = rootAt + RootT::memUsage(uint32_t(nUpper));
    const uint64_t lowerAt = upperAt + nUpper * UpperT::memUsage();
    const uint64_t leafAt = lowerAt + nLower * LowerT::memUsage();
    const uint64_t size = leafAt + nLeaf * sizeof(LeafT);
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(size);
    uint8_t* base = buffer.data();
    std::memset(base, 0, size);

    // Leaves, in parallel.
    std::vector<NodeStats<V>> leafStats(nLeaf);
    tbb::parallel_for(size_t(0), nLeaf, [&](size_t i) {
        auto* d = reinterpret_cast<typename LeafT::DataType*>(base + leafAt + i * sizeof(LeafT));
        leafStats[i] = fillLeaf<BuildT>(*d, in, t.leafInput[i]);
    });

    // Tiles per parent node.
    std::vector<std::vector<const typename SparseVoxels<V>::Tile*>> lowerTiles(nLower), upperTiles(nUpper);
    for (const auto& tile : in.tiles) {
        const uint32_t u = upperRank(t, tile.origin);
        if (tile.level == 2) {
            const uint64_t key = uint64_t(u) << 15 | childIndex(tile.origin, 5, 7);
            if (std::binary_search(t.lowers.begin(), t.lowers.end(), key))
                throw InvalidInput("NanoVDB layout: a level-2 tile holds leaves or smaller tiles");
            upperTiles[u].push_back(&tile);
        } else {
            const size_t l = size_t(std::lower_bound(t.lowers.begin(), t.lowers.end(), uint64_t(u) << 15 | childIndex(tile.origin, 5, 7)) -
                                    t.lowers.begin());
            const uint64_t key = uint64_t(l) << 12 | childIndex(tile.origin, 4, 3);
            if (std::binary_search(t.leaves.begin(), t.leaves.end(), key))
                throw InvalidInput("NanoVDB layout: a level-1 tile lies on a leaf");
            lowerTiles[l].push_back(&tile);
        }
    }
    auto tileVisitor = [](const auto& list, int log2Dim, int childTotal) {
        return [&list, log2Dim, childTotal](auto&& visit) {
            for (const auto* tile : list) visit(childIndex(tile->origin, log2Dim, childTotal), tile->value, tile->active);
        };
    };

    std::vector<NodeStats<V>> lowerStats(nLower);
    tbb::parallel_for(size_t(0), nLower, [&](size_t l) {
        auto* d = reinterpret_cast<typename LowerT::DataType*>(base + lowerAt + l * LowerT::memUsage());
        const auto& up = t.uppers[t.lowers[l] >> 15];
        const uint32_t n1 = uint32_t(t.lowers[l] & 0x7FFF);
        const std::array<int32_t, 3> origin{up[0] + int32_t((n1 >> 10) << 7), up[1] + int32_t(((n1 >> 5) & 31) << 7),
                                            up[2] + int32_t((n1 & 31) << 7)};
        lowerStats[l] = fillInternal<BuildT>(*d, origin, in.background, 3, tileVisitor(lowerTiles[l], 4, 3), [&](auto&& visit) {
            for (uint32_t i = t.lowerFirstLeaf[l]; i < t.lowerFirstLeaf[l + 1]; ++i)
                visit(uint32_t(t.leaves[i] & 0xFFF), base + leafAt + i * sizeof(LeafT), leafStats[i]);
        });
    });

    std::vector<NodeStats<V>> upperStats(nUpper);
    tbb::parallel_for(size_t(0), nUpper, [&](size_t u) {
        auto* d = reinterpret_cast<typename UpperT::DataType*>(base + upperAt + u * UpperT::memUsage());
        upperStats[u] = fillInternal<BuildT>(*d, t.uppers[u], in.background, 7, tileVisitor(upperTiles[u], 5, 7), [&](auto&& visit) {
            for (uint32_t l = t.upperFirstLower[u]; l < t.upperFirstLower[u + 1]; ++l)
                visit(uint32_t(t.lowers[l] & 0x7FFF), base + lowerAt + l * LowerT::memUsage(), lowerStats[l]);
        });
    });

    // Root: one child tile per upper node, in origin order.
    auto* root = reinterpret_cast<typename RootT::DataType*>(base + rootAt);
    root->mTableSize = uint32_t(nUpper);
    root->mBackground = in.background;
    NodeStats<V> total;
    for (size_t u = 0; u < nUpper; ++u) {
        auto* tile = root->tile(uint32_t(u));
        tile->setChild(toCoord(t.uppers[u]), reinterpret_cast<const UpperT*>(base + upperAt + u * UpperT::memUsage()), root);
        total.add(upperStats[u]);
    }
    root->mBBox = total.bbox;
    if constexpr (hasStats<BuildT, V>()) {
        root->mMinimum = total.extrema.any ? total.extrema.lo : in.background;
        root->mMaximum = total.extrema.any ? total.extrema.hi : in.background;
    }

    // Tree: first node of each level, counts, active tiles and voxels.
    auto* tree = reinterpret_cast<typename TreeT::DataType*>(base + treeAt);
    tree->mNodeOffset[0] = nLeaf ? leafAt - treeAt : 0;
    tree->mNodeOffset[1] = nLower ? lowerAt - treeAt : 0;
    tree->mNodeOffset[2] = nUpper ? upperAt - treeAt : 0;
    tree->mNodeOffset[3] = rootAt - treeAt;
    tree->mNodeCount[0] = uint32_t(nLeaf);
    tree->mNodeCount[1] = uint32_t(nLower);
    tree->mNodeCount[2] = uint32_t(nUpper);
    uint64_t voxels = 0;
    for (const Brick& m : in.masks) voxels += m.count();
    for (const auto& tile : in.tiles)
        if (tile.active) {
            ++tree->mTileCount[tile.level - 1];
            voxels += tile.level == 1 ? LeafT::NUM_VALUES : LowerT::NUM_VALUES;
        }
    tree->mVoxelCount = voxels;

    // Grid.
    auto* grid = reinterpret_cast<nanovdb::GridData*>(base);
    grid->mMagic = NANOVDB_MAGIC_NUMBER;
    grid->mVersion = nanovdb::Version();
    grid->mFlags = uint32_t(nanovdb::GridFlags::IsBreadthFirst);
    if constexpr (hasStats<BuildT, V>()) grid->setMinMaxOn();
    grid->mGridIndex = 0;
    grid->mGridCount = 1;
    grid->mGridSize = size;
    std::strncpy(grid->mGridName, info.name.c_str(), nanovdb::GridData::MaxNameSize - 1);
    grid->mMap.set(info.voxelSize, nanovdb::Vec3d(info.translation[0], info.translation[1], info.translation[2]), 1.0);
    grid->mVoxelSize = nanovdb::Vec3d(info.voxelSize);
    grid->mGridClass = std::is_same_v<BuildT, nanovdb::ValueMask> ? nanovdb::GridClass::Topology : info.gridClass;
    grid->mGridType = nanovdb::mapToGridType<BuildT>();
    grid->mWorldBBox = nanovdb::BBox<nanovdb::Vec3d>(); // empty, as nanovdb::GridStats leaves it
    if (!total.bbox.empty()) {
        // As nanovdb::GridStats: the corners of the index box, its maximum one past.
        const Coord lo = total.bbox[0], hi = total.bbox[1] + Coord(1);
        grid->mWorldBBox[0] = grid->mWorldBBox[1] = grid->mMap.applyMap(nanovdb::Vec3d(lo[0], lo[1], lo[2]));
        for (int c = 1; c < 8; ++c)
            grid->mWorldBBox.expand(grid->mMap.applyMap(
                nanovdb::Vec3d((c & 4) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 1) ? hi[2] : lo[2])));
        grid->setBBoxOn();
    }
    nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
    if (info.checksum) updateFullChecksum(*handle.template grid<BuildT>());
    return handle;
}

template <typename BuildT>
void updateFullChecksum(nanovdb::NanoGrid<BuildT>& grid)
{
    auto& tree = grid.tree();
    if (tree.isEmpty()) return nanovdb::updateChecksum(grid, nanovdb::ChecksumMode::Full);
    auto crc = [](const void* p, size_t n) { return uint32_t(crc32_z(0UL, static_cast<const Bytef*>(p), n)); };
    const auto* base = reinterpret_cast<const uint8_t*>(&grid);
    const uint64_t rootEnd = grid.memUsage() + tree.memUsage() + tree.root().memUsage();
    const uint32_t head = crc(base + 16, rootEnd - 16); // past mMagic and mChecksum
    const uint32_t n2 = tree.nodeCount(2), n1 = tree.nodeCount(1), n0 = tree.nodeCount(0);
    // nanovdb::GridChecksum keeps each node's CRC in a std::uint_fast32_t and hashes that array's bytes.
    std::vector<std::uint_fast32_t> sums(size_t(n2) + n1 + n0);
    auto nodes = [&](const void* first, size_t size, size_t count, size_t at) {
        tbb::parallel_for(size_t(0), count, [&, first, size, at](size_t i) {
            sums[at + i] = crc(static_cast<const uint8_t*>(first) + i * size, size);
        });
    };
    nodes(tree.template getFirstNode<2>(), sizeof(nanovdb::NanoUpper<BuildT>), n2, 0);
    nodes(tree.template getFirstNode<1>(), sizeof(nanovdb::NanoLower<BuildT>), n1, n2);
    nodes(tree.template getFirstNode<0>(), sizeof(nanovdb::NanoLeaf<BuildT>), n0, size_t(n2) + n1);
    const uint32_t tail = crc(sums.data(), sums.size() * sizeof(std::uint_fast32_t));
    grid.data()->mChecksum = uint64_t(tail) << 32 | head;
}

template nanovdb::GridHandle<nanovdb::HostBuffer> buildNanoGrid<float>(const SparseVoxels<float>&, const NanoGridInfo&);
template nanovdb::GridHandle<nanovdb::HostBuffer> buildNanoGrid<int32_t>(const SparseVoxels<int32_t>&, const NanoGridInfo&);
template nanovdb::GridHandle<nanovdb::HostBuffer> buildNanoGrid<nanovdb::Vec3f>(const SparseVoxels<nanovdb::Vec3f>&,
                                                                              const NanoGridInfo&);
template nanovdb::GridHandle<nanovdb::HostBuffer> buildNanoGrid<bool>(const SparseVoxels<bool>&, const NanoGridInfo&);
template nanovdb::GridHandle<nanovdb::HostBuffer> buildNanoGrid<nanovdb::ValueMask>(const SparseVoxels<bool>&,
                                                                                  const NanoGridInfo&);
template void updateFullChecksum<float>(nanovdb::NanoGrid<float>&);
template void updateFullChecksum<int32_t>(nanovdb::NanoGrid<int32_t>&);
template void updateFullChecksum<nanovdb::Vec3f>(nanovdb::NanoGrid<nanovdb::Vec3f>&);
template void updateFullChecksum<bool>(nanovdb::NanoGrid<bool>&);
template void updateFullChecksum<nanovdb::ValueMask>(nanovdb::NanoGrid<nanovdb::ValueMask>&);

} // namespace svo::vdb
