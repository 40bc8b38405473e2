#include "svo/core/octree.h"

#include <algorithm>
#include <fmt/format.h>
#include <functional>
#include <tuple>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include "svo/core/error.h"
#include "svo/core/voxel_key.h"

namespace svo {
namespace {

/// Interleaves 18-bit brick coordinates: bit i of x, y, z goes to bit 3i, 3i+1, 3i+2,
/// so each 3-bit digit is a child index c = x + 2y + 4z.
uint64_t morton(uint32_t x, uint32_t y, uint32_t z)
{
    auto spread = [](uint64_t v) {
        v &= 0x3FFFF; // 18 bits
        v = (v | v << 32) & 0x001F00000000FFFFull;
        v = (v | v << 16) & 0x001F0000FF0000FFull;
        v = (v | v << 8) & 0x100F00F00F00F00Full;
        v = (v | v << 4) & 0x10C30C30C30C30C3ull;
        v = (v | v << 2) & 0x1249249249249249ull;
        return v;
    };
    return spread(x) | spread(y) << 1 | spread(z) << 2;
}

std::array<uint32_t, 3> brickCoords(uint64_t key)
{
    const auto p = unpackVoxelKey(key);
    return {p[0] >> 3, p[1] >> 3, p[2] >> 3};
}

} // namespace

bool Brick::operator==(const Brick& o) const { return std::equal(words, words + 8, o.words); }

uint32_t Brick::count() const
{
    uint32_t n = 0;
    for (uint64_t w : words) n += uint32_t(__builtin_popcountll(w));
    return n;
}

bool VoxelAttributes::operator==(const VoxelAttributes& o) const
{
    auto eq3 = [](const std::vector<Vec3f>& a, const std::vector<Vec3f>& b) {
        return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                          [](const Vec3f& x, const Vec3f& y) { return x.x == y.x && x.y == y.y && x.z == y.z; });
    };
    return channels() == o.channels() && eq3(normals, o.normals) && triangles == o.triangles && eq3(colors, o.colors);
}

uint32_t VoxelAttributes::channels() const
{
    return computed | (normals.empty() ? 0u : kNormals) | (triangles.empty() ? 0u : kTriangles) |
           (colors.empty() ? 0u : kColors);
}

uint32_t Octree::channels() const { return attributes.channels(); }

uint64_t Octree::bytes() const
{
    return nodes.size() * sizeof(OctreeNode) + bricks.size() * sizeof(Brick) +
           attributes.normals.size() * sizeof(Vec3f) + attributes.triangles.size() * sizeof(int32_t) +
           attributes.colors.size() * sizeof(Vec3f);
}

std::vector<uint64_t> brickVoxelOffsets(const Octree& o)
{
    std::vector<uint64_t> offsets(o.bricks.size() + 1, 0);
    for (size_t b = 0; b < o.bricks.size(); ++b) offsets[b + 1] = offsets[b] + o.bricks[b].count();
    return offsets;
}

uint64_t Octree::voxelCount() const
{
    // In parallel: a portable build counts bits in software, 2 ms for 56,000 bricks.
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, bricks.size(), 4096), uint64_t(0),
        [&](const tbb::blocked_range<size_t>& r, uint64_t n) {
            for (size_t i = r.begin(); i != r.end(); ++i) n += bricks[i].count();
            return n;
        },
        std::plus<uint64_t>());
}

uint32_t brickLevelFor(const GridSpec& grid)
{
    const uint32_t bricks = (std::max(grid.maxDim(), 1u) + 7) / 8;
    uint32_t level = 0;
    while ((1u << level) < bricks) ++level;
    return level;
}

Octree buildOctreeFromBricks(const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> input)
{
    Octree out;
    out.grid = grid;
    out.brickLevel = brickLevelFor(grid);
    const uint32_t L = out.brickLevel;

    // Bricks in Morton order, equal ones merged, empty ones dropped. Only
    // (code, index) pairs are sorted; the 64-byte bricks move once.
    for (const auto& [key, brick] : input) {
        const auto b = brickCoords(key);
        if (std::max({b[0], b[1], b[2]}) >> L)
            throw InvalidInput(fmt::format("brick at local ({}, {}, {}) lies outside the grid {} x {} x {}", b[0] * 8,
                                           b[1] * 8, b[2] * 8, grid.dims[0], grid.dims[1], grid.dims[2]));
    }
    std::vector<std::pair<uint64_t, size_t>> order(input.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, input.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const auto b = brickCoords(input[i].first);
            order[i] = {morton(b[0], b[1], b[2]), i};
        }
    });
    tbb::parallel_sort(order.begin(), order.end());
    std::vector<uint64_t> codes;
    codes.reserve(order.size());
    out.bricks.reserve(order.size());
    for (const auto& [code, i] : order) {
        const Brick& brick = input[i].second;
        if (brick.count() == 0) continue;
        if (!codes.empty() && codes.back() == code) {
            for (int w = 0; w < 8; ++w) out.bricks.back().words[w] |= brick.words[w];
        } else {
            codes.push_back(code);
            out.bricks.push_back(brick);
        }
    }
    input = {};
    order = {};
    if (out.bricks.size() >= 0xFFFFFFFFull)
        throw Unsupported(fmt::format("{} bricks are more than an octree indexes (32-bit)", out.bricks.size()));

    // The occupied node ids of each level are the distinct Morton prefixes,
    // found bottom-up from the bricks (each level from the one below, so the
    // work is about the brick count, not the brick count per level). Each
    // occupied node of level l owns the block of 8 children at
    // 8 * (its rank among the occupied nodes of its level).
    out.nodes.resize(1);
    out.levelStart = {0, 1};
    if (codes.empty()) {
        for (uint32_t l = 1; l <= L; ++l) out.levelStart.push_back(1);
        return out;
    }
    std::vector<std::vector<uint64_t>> ids(L + 1);
    ids[L] = std::move(codes);
    for (uint32_t l = L; l-- > 0;) {
        for (uint64_t id : ids[l + 1])
            if (ids[l].empty() || ids[l].back() != (id >> 3)) ids[l].push_back(id >> 3);
    }
    uint64_t total = 1;
    for (uint32_t l = 0; l < L; ++l) total += 8 * ids[l].size();
    if (total >= 0xFFFFFFFFull) throw Unsupported(fmt::format("{} octree nodes are more than 32-bit indices hold", total));
    out.nodes.resize(total);
    std::vector<uint32_t> parentNodes = {0}; // node index of each occupied id at the current level
    for (uint32_t l = 0; l < L; ++l) {
        const uint32_t base = out.levelStart.back();
        out.levelStart.push_back(base + uint32_t(8 * ids[l].size()));
        std::vector<uint32_t> childNodes(ids[l + 1].size());
        size_t rank = 0;
        for (size_t i = 0; i < ids[l + 1].size(); ++i) {
            const uint64_t id = ids[l + 1][i];
            while (ids[l][rank] != (id >> 3)) ++rank; // both sorted
            OctreeNode& parent = out.nodes[parentNodes[rank]];
            parent.child = base + uint32_t(8 * rank);
            parent.childMask |= 1u << (id & 7);
            childNodes[i] = parent.child + uint32_t(id & 7);
        }
        parentNodes = std::move(childNodes);
        ids[l] = {};
    }
    for (size_t b = 0; b < parentNodes.size(); ++b) out.nodes[parentNodes[b]] = {uint32_t(b), 1u};
    return out;
}

Octree buildOctree(const GridSpec& grid, const std::vector<uint64_t>& keys)
{
    std::vector<uint64_t> sorted = keys;
    tbb::parallel_sort(sorted.begin(), sorted.end());
    std::vector<std::pair<uint64_t, Brick>> bricks;
    for (uint64_t k : sorted) {
        if (bricks.empty() || bricks.back().first != brickOfKey(k)) bricks.push_back({brickOfKey(k), Brick{}});
        const uint32_t bit = uint32_t(k & 511);
        bricks.back().second.words[bit >> 6] |= uint64_t(1) << (bit & 63);
    }
    return buildOctreeFromBricks(grid, std::move(bricks));
}

Octree canonicalOrder(const Octree& src)
{
    Octree out;
    out.grid = src.grid;
    out.brickLevel = src.brickLevel;
    out.levelStart = {0, 1};
    out.nodes.push_back(src.nodes.at(0));
    std::vector<uint32_t> level = {0}; // source indices of the current level, in output order
    std::vector<uint32_t> order;       // source brick of each output brick
    for (uint32_t l = 0; l <= src.brickLevel; ++l) {
        const uint32_t first = out.levelStart[l];
        std::vector<uint32_t> next;
        for (size_t i = 0; i < level.size(); ++i) {
            const OctreeNode n = src.nodes[level[i]];
            OctreeNode& o = out.nodes[first + i];
            o = {0, n.childMask};
            if (!n.childMask) continue;
            if (l == src.brickLevel) {
                o.child = uint32_t(out.bricks.size());
                out.bricks.push_back(src.bricks.at(n.child));
                order.push_back(n.child);
            } else {
                o.child = uint32_t(out.nodes.size());
                for (uint32_t c = 0; c < 8; ++c) {
                    next.push_back(n.child + c);
                    out.nodes.push_back(src.nodes.at(n.child + c));
                }
            }
        }
        if (l < src.brickLevel) out.levelStart.push_back(uint32_t(out.nodes.size()));
        level = std::move(next);
    }
    // Attribute blocks follow their bricks.
    out.attributes.computed = src.attributes.computed;
    if (!src.attributes.empty()) {
        const auto offsets = brickVoxelOffsets(src);
        auto permute = [&](const auto& in, auto& result) {
            if (in.empty()) return;
            result.reserve(in.size());
            for (uint32_t b : order) result.insert(result.end(), in.begin() + long(offsets[b]), in.begin() + long(offsets[b + 1]));
        };
        permute(src.attributes.normals, out.attributes.normals);
        permute(src.attributes.triangles, out.attributes.triangles);
        permute(src.attributes.colors, out.attributes.colors);
    }
    return out;
}

bool sameOctree(const Octree& a, const Octree& b)
{
    auto nodesEqual = [](const OctreeNode& x, const OctreeNode& y) {
        return x.child == y.child && x.childMask == y.childMask;
    };
    return a.grid.voxelSize == b.grid.voxelSize && a.grid.shift == b.grid.shift && a.grid.anchor == b.grid.anchor &&
           a.grid.dims == b.grid.dims && a.brickLevel == b.brickLevel && a.levelStart == b.levelStart &&
           std::equal(a.nodes.begin(), a.nodes.end(), b.nodes.begin(), b.nodes.end(), nodesEqual) &&
           a.bricks == b.bricks && a.attributes == b.attributes;
}

std::vector<BrickRef> occupiedBricks(const Octree& o)
{
    // Breadth first, one level at a time; each level is expanded in parallel
    // (count children, prefix sum, fill), so children stay in order and the
    // bricks come out in Morton order.
    struct Item {
        uint32_t node, x, y, z;
    };
    std::vector<BrickRef> out;
    if (o.nodes.empty()) return out;
    std::vector<Item> level = {{0, 0, 0, 0}};
    // Where each item's outputs start: counted in parallel, then a prefix sum.
    auto offsetsOf = [&](auto&& countOf) {
        std::vector<uint64_t> offset(level.size() + 1, 0);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, level.size(), 2048), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) offset[i + 1] = countOf(o.nodes[level[i].node]);
        });
        for (size_t i = 0; i < level.size(); ++i) offset[i + 1] += offset[i];
        return offset;
    };
    auto forEachItem = [&](auto&& body) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, level.size(), 2048), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) body(i);
        });
    };
    for (uint32_t l = 0; l < o.brickLevel; ++l) {
        const auto offset = offsetsOf([](const OctreeNode& n) { return uint64_t(__builtin_popcount(n.childMask & 0xFFu)); });
        std::vector<Item> next(offset.back());
        forEachItem([&](size_t i) {
            const Item& it = level[i];
            const OctreeNode& n = o.nodes[it.node];
            uint64_t at = offset[i];
            for (uint32_t c = 0; c < 8; ++c)
                if (n.childMask >> c & 1)
                    next[at++] = {n.child + c, 2 * it.x + (c & 1), 2 * it.y + (c >> 1 & 1), 2 * it.z + (c >> 2)};
        });
        level = std::move(next);
    }
    const auto offset = offsetsOf([](const OctreeNode& n) { return uint64_t(n.childMask != 0); });
    out.resize(offset.back());
    forEachItem([&](size_t i) {
        const Item& it = level[i];
        if (o.nodes[it.node].childMask) out[offset[i]] = {{it.x * 8, it.y * 8, it.z * 8}, o.nodes[it.node].child};
    });
    return out;
}

OctreeLeaves octreeLeaves(const Octree& o)
{
    const std::vector<BrickRef> refs = occupiedBricks(o);
    OctreeLeaves out;
    out.origins.resize(refs.size());
    out.masks.resize(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) {
        const auto g = o.grid.toGlobal(refs[i].origin);
        out.origins[i] = {int32_t(g[0]), int32_t(g[1]), int32_t(g[2])};
        out.masks[i] = o.bricks[refs[i].index];
    }
    return out;
}

std::vector<uint64_t> octreeKeys(const Octree& o)
{
    auto refs = occupiedBricks(o);
    auto keyOf = [](const BrickRef& r) { return packVoxelKey(r.origin[0], r.origin[1], r.origin[2]); };
    std::sort(refs.begin(), refs.end(), [&](const auto& a, const auto& b) { return keyOf(a) < keyOf(b); });
    std::vector<uint64_t> keys;
    keys.reserve(o.voxelCount());
    for (const auto& r : refs) {
        const uint64_t base = keyOf(r);
        const Brick& b = o.bricks[r.index];
        for (uint32_t w = 0; w < 8; ++w)
            for (uint64_t bits = b.words[w]; bits; bits &= bits - 1)
                keys.push_back(base | (w * 64 + uint32_t(__builtin_ctzll(bits))));
    }
    return keys;
}

std::vector<std::string> checkOctree(const Octree& o, size_t limit)
{
    std::vector<std::string> problems;
    auto fail = [&](std::string msg) {
        if (problems.size() < limit) problems.push_back(std::move(msg));
    };
    const uint32_t L = o.brickLevel;
    if (L > 18) return {fmt::format("brick level {} exceeds 18", L)};
    if (L != brickLevelFor(o.grid)) fail(fmt::format("brick level {} but the grid needs {}", L, brickLevelFor(o.grid)));
    const auto& s = o.levelStart;
    if (s.size() != L + 2 || s[0] != 0 || s[1] != 1 || s.back() != o.nodes.size())
        return {fmt::format("level table has {} entries for {} levels and {} nodes", s.size(), L + 1, o.nodes.size())};
    for (uint32_t l = 1; l <= L; ++l)
        if (s[l + 1] < s[l] || (s[l + 1] - s[l]) % 8 != 0)
            return {fmt::format("level {} spans nodes [{}, {}), not whole blocks of 8", l, s[l], s[l + 1])};

    std::vector<uint8_t> blockRefs(o.nodes.size() / 8 + 1, 0), brickRefs(o.bricks.size(), 0);
    for (uint32_t l = 0; l <= L; ++l)
        for (uint32_t i = s[l]; i < s[l + 1]; ++i) {
            const OctreeNode& n = o.nodes[i];
            if (l == L) {
                if (n.childMask > 1) fail(fmt::format("brick node {} has mask {:#x}", i, n.childMask));
                if (n.childMask != 1) continue;
                if (n.child >= o.bricks.size()) {
                    fail(fmt::format("brick node {} points to brick {} of {}", i, n.child, o.bricks.size()));
                    continue;
                }
                if (brickRefs[n.child]++) fail(fmt::format("brick {} is referenced twice", n.child));
                if (o.bricks[n.child].count() == 0) fail(fmt::format("brick {} is empty but marked occupied", n.child));
                continue;
            }
            if (n.childMask > 0xFF) fail(fmt::format("node {} has mask {:#x}", i, n.childMask));
            if (!n.childMask) continue;
            if (n.child < s[l + 1] || uint64_t(n.child) + 8 > s[l + 2] || (n.child - s[l + 1]) % 8 != 0) {
                fail(fmt::format("node {} (level {}) points to {}, outside level {}'s blocks [{}, {})", i, l, n.child,
                                 l + 1, s[l + 1], s[l + 2]));
                continue;
            }
            if (blockRefs[n.child / 8]++) fail(fmt::format("child block at {} is referenced twice", n.child));
            for (uint32_t c = 0; c < 8; ++c) {
                const bool occupied = o.nodes[n.child + c].childMask != 0;
                if (occupied != bool(n.childMask >> c & 1))
                    fail(fmt::format("node {} mask bit {} is {} but its child is {}", i, c, n.childMask >> c & 1,
                                     occupied ? "occupied" : "empty"));
            }
        }
    for (uint32_t l = 1; l <= L; ++l)
        for (uint32_t i = s[l]; i < s[l + 1]; i += 8)
            if (!blockRefs[i / 8]) fail(fmt::format("child block at {} (level {}) is orphaned", i, l));
    for (size_t b = 0; b < o.bricks.size(); ++b)
        if (!brickRefs[b]) fail(fmt::format("brick {} is orphaned", b));
    const uint64_t voxels = o.voxelCount();
    // A channel computed holds a value for every voxel (none in an empty octree).
    for (auto [size, bit, name] : {std::tuple{o.attributes.normals.size(), kNormals, "normal"},
                                   std::tuple{o.attributes.triangles.size(), kTriangles, "triangle"},
                                   std::tuple{o.attributes.colors.size(), kColors, "colour"}})
        if ((o.channels() & bit) && size != voxels) fail(fmt::format("{} {} values for {} voxels", size, name, voxels));
    if (!problems.empty()) return problems;

    // Only voxels inside the grid's local range.
    for (const auto& r : occupiedBricks(o)) {
        const Brick& b = o.bricks[r.index];
        for (uint32_t bit = 0; bit < 512; ++bit) {
            if (!(b.words[bit >> 6] >> (bit & 63) & 1)) continue;
            const uint32_t v[3] = {r.origin[0] + (bit >> 6), r.origin[1] + (bit >> 3 & 7), r.origin[2] + (bit & 7)};
            if (v[0] >= o.grid.dims[0] || v[1] >= o.grid.dims[1] || v[2] >= o.grid.dims[2]) {
                fail(fmt::format("voxel ({}, {}, {}) lies outside the grid {} x {} x {}", v[0], v[1], v[2],
                                 o.grid.dims[0], o.grid.dims[1], o.grid.dims[2]));
                break;
            }
        }
    }
    return problems;
}

OctreeStats octreeStats(const Octree& o)
{
    OctreeStats st;
    for (uint32_t l = 0; l + 1 < o.levelStart.size(); ++l) {
        st.nodesPerLevel.push_back(o.levelStart[l + 1] - o.levelStart[l]);
        uint64_t occ = 0;
        for (uint32_t i = o.levelStart[l]; i < o.levelStart[l + 1]; ++i) occ += o.nodes[i].childMask != 0;
        st.occupiedPerLevel.push_back(occ);
    }
    st.bricks = o.bricks.size();
    st.voxels = o.voxelCount();
    st.bytes = o.bytes();
    return st;
}

} // namespace svo
