// svo's sparse results as NanoVDB grids without an OpenVDB tree (svo/vdb_io/nanovdb_grids.h).
#include "svo/vdb_io/nanovdb_grids.h"

#include <cmath>
#include <map>
#include <tbb/parallel_for.h>

#include "svo/vdb_io/nanovdb_checksum.h"
#include "svo/vdb_io/nanovdb_layout.h"

namespace svo::vdb {
namespace {

using Origin = std::array<int32_t, 3>;

bool bitOf(const Brick& b, uint32_t bit) { return (b.words[bit >> 6] >> (bit & 63)) & 1u; }

Origin brickOrigin(const GridSpec& g, const BrickCoord& b)
{
    return {int32_t(g.anchor[0] + 8 * int64_t(b[0])), int32_t(g.anchor[1] + 8 * int64_t(b[1])),
            int32_t(g.anchor[2] + 8 * int64_t(b[2]))};
}

NanoGridInfo infoFor(const GridSpec& lattice, const std::string& name, nanovdb::GridClass cls, bool checksum)
{
    NanoGridInfo info;
    info.name = name;
    info.gridClass = cls;
    info.voxelSize = lattice.voxelSize;
    info.translation = lattice.translation();
    info.checksum = checksum;
    return info;
}

/// The octree's bricks as leaves; `value(brick, n)` gives the n-th active voxel's value.
template <typename V, typename Value>
SparseVoxels<V> octreeLeaves(const Octree& o, V background, bool withValues, Value&& value)
{
    const std::vector<BrickRef> refs = occupiedBricks(o);
    SparseVoxels<V> s;
    s.background = background;
    s.origins.resize(refs.size());
    s.masks.resize(refs.size());
    if (withValues) s.values.assign(refs.size() * 512, background);
    tbb::parallel_for(size_t(0), refs.size(), [&](size_t i) {
        const auto g = o.grid.toGlobal(refs[i].origin);
        s.origins[i] = {int32_t(g[0]), int32_t(g[1]), int32_t(g[2])};
        const Brick& b = o.bricks[refs[i].index];
        s.masks[i] = b;
        if (!withValues) return;
        uint32_t n = 0;
        for (uint32_t v = 0; v < 512; ++v)
            if (bitOf(b, v)) s.values[i * 512 + v] = value(refs[i].index, n++);
    });
    return s;
}

nanovdb::Vec3f vec(const Vec3f& v) { return nanovdb::Vec3f(v.x, v.y, v.z); }

/// Leaves by origin, so that later passes can reach a leaf made earlier.
template <typename V>
struct LeafIndex {
    SparseVoxels<V>& s;
    bool withValues;
    std::map<Origin, size_t> at;
    LeafIndex(SparseVoxels<V>& voxels, bool values) : s(voxels), withValues(values)
    {
        for (size_t i = 0; i < s.origins.size(); ++i) at[s.origins[i]] = i;
    }
    /// The leaf at `o`, made (background, nothing active) when absent.
    size_t touch(const Origin& o)
    {
        auto [it, made] = at.emplace(o, s.origins.size());
        if (made) {
            s.origins.push_back(o);
            s.masks.push_back(Brick{});
            if (withValues) s.values.resize(s.origins.size() * 512, s.background);
        }
        return it->second;
    }
};

/// Parity's runs of whole bricks inside between band bricks of a column, as
/// OpenVDB's tree.fill makes them (field_grids.cpp's fillRuns): whole bricks
/// become 8³ tiles; partial ones leaves with the runs' columns set.
template <typename V>
void fillRuns(SparseVoxels<V>& s, const GridSpec& g, const std::vector<InsideRun>& runs, const V& value, bool active,
              bool withValues)
{
    LeafIndex<V> leaves(s, withValues);
    for (const auto& run : runs)
        for (uint32_t k = 0; k < run.bricks; ++k) {
            const BrickCoord b{run.first[0], run.first[1], run.first[2] + k};
            const Origin o = brickOrigin(g, b);
            if (run.columns == ~uint64_t(0) && !leaves.at.count(o)) {
                s.tiles.push_back({o, 1, value, active});
                continue;
            }
            const size_t i = leaves.touch(o);
            for (uint32_t c = 0; c < 64; ++c)
                if ((run.columns >> c) & 1u)
                    for (uint32_t z = 0; z < 8; ++z) {
                        const uint32_t v = c * 8 + z; // (x = c / 8, y = c % 8, z)
                        if (withValues) s.values[i * 512 + v] = value;
                        if (active) s.masks[i].words[v >> 6] |= uint64_t(1) << (v & 63);
                    }
        }
}


template <typename MaskT>
bool isOn(const MaskT& m, uint32_t n)
{
    return (m.template getWord<uint64_t>(int(n >> 6)) >> (n & 63)) & 1u;
}

template <typename MaskT>
uint32_t firstOn(const MaskT& m, uint32_t size)
{
    for (uint32_t n = 0; n < size; ++n)
        if (isOn(m, n)) return n;
    return size;
}

/// OpenVDB's signed flood fill (tools::signedFloodFill, which the OpenVDB
/// path runs on parity level sets), on the NanoVDB layout, bottom up: in a
/// node with active voxels (leaves) or children (internal nodes), every
/// other value takes the sign of the last active value or child end met
/// along x, then y, then z, starting from the first one's; a node with none
/// takes the sign of its first value. Magnitudes become the background.
/// Root tiles between upper nodes (grids past 4096 voxels with a gap
/// between nodes along z) are not added.
template <uint32_t Log2Dim, typename Inside, typename Set>
void floodNode(uint32_t first, uint32_t size, Inside&& endInside, Set&& set, bool firstInside)
{
    if (first >= size) {
        for (uint32_t n = 0; n < size; ++n) set(n, firstInside);
        return;
    }
    bool x = endInside(first, true), y = x, z = x;
    for (uint32_t i = 0; i < (1u << Log2Dim); ++i) {
        const uint32_t i00 = i << (2 * Log2Dim);
        endInside(i00, false, &x);
        y = x;
        for (uint32_t j = 0; j < (1u << Log2Dim); ++j) {
            const uint32_t ij0 = i00 + (j << Log2Dim);
            endInside(ij0, false, &y);
            z = y;
            for (uint32_t k = 0; k < (1u << Log2Dim); ++k) {
                const uint32_t ijk = ij0 + k;
                if (!endInside(ijk, false, &z)) set(ijk, z);
            }
        }
    }
}

} // namespace

void signedFloodFill(nanovdb::NanoGrid<float>& grid)
{
    using LeafT = nanovdb::NanoLeaf<float>;
    using LowerT = nanovdb::NanoLower<float>;
    using UpperT = nanovdb::NanoUpper<float>;
    auto& tree = grid.tree();
    const float outside = std::abs(tree.background()), minus = -outside;
    auto* leaves = tree.getFirstNode<0>();
    tbb::parallel_for(uint32_t(0), tree.nodeCount(0), [&](uint32_t i) {
        auto& d = *leaves[i].data();
        // endInside(n, first, &inside): for an active voxel, sets `inside` from its value.
        auto end = [&](uint32_t n, bool first, bool* inside = nullptr) {
            if (first) return d.mValues[n] < 0;
            if (!isOn(d.mValueMask, n)) return false;
            *inside = d.mValues[n] < 0;
            return true;
        };
        floodNode<3>(firstOn(d.mValueMask, 512), 512, end, [&](uint32_t n, bool in) { d.mValues[n] = in ? minus : outside; },
                     d.mValues[0] < 0);
    });
    // A child's first and last values, leaves or lower nodes.
    auto leafFirst = [](const uint8_t* c) { return reinterpret_cast<const LeafT*>(c)->data()->mValues[0]; };
    auto leafLast = [](const uint8_t* c) { return reinterpret_cast<const LeafT*>(c)->data()->mValues[511]; };
    auto floodInternal = [&](auto& d, uint32_t size, auto childFirst, auto childLast) {
        const uint8_t* base = reinterpret_cast<const uint8_t*>(&d);
        auto end = [&](uint32_t n, bool first, bool* inside = nullptr) {
            if (first) return childFirst(base + d.mTable[n].child) < 0;
            if (!isOn(d.mChildMask, n)) return false;
            *inside = childLast(base + d.mTable[n].child) < 0;
            return true;
        };
        const uint32_t first = firstOn(d.mChildMask, size);
        const bool firstInside = first < size ? false : d.mTable[0].value < 0;
        auto set = [&](uint32_t n, bool in) { d.mTable[n].value = in ? minus : outside; };
        if (size == 4096) floodNode<4>(first, size, end, set, firstInside);
        else floodNode<5>(first, size, end, set, firstInside);
    };
    auto* lowers = tree.getFirstNode<1>();
    tbb::parallel_for(uint32_t(0), tree.nodeCount(1), [&](uint32_t i) {
        floodInternal(*lowers[i].data(), 4096u, leafFirst, leafLast);
    });
    // A lower node's first and last values: its first (last) child's, or its tile's.
    auto lowerEnd = [&](const uint8_t* c, uint32_t n) {
        const auto& d = *reinterpret_cast<const LowerT*>(c)->data();
        if (!isOn(d.mChildMask, n)) return d.mTable[n].value;
        const uint8_t* child = c + d.mTable[n].child;
        return n == 0 ? leafFirst(child) : leafLast(child);
    };
    auto* uppers = tree.getFirstNode<2>();
    for (uint32_t i = 0; i < tree.nodeCount(2); ++i)
        floodInternal(*uppers[i].data(), 32768u, [&](const uint8_t* c) { return lowerEnd(c, 0); },
                      [&](const uint8_t* c) { return lowerEnd(c, 4095); });
    static_assert(UpperT::DataType::FIXED_SIZE, "");
}

std::vector<NanoHandle> octreeToNanoGrids(const Octree& o, const GridOptions& options, bool checksum)
{
    std::vector<NanoHandle> out;
    const GridSpec& g = o.grid;
    const SparseVoxels<bool> leaves = octreeLeaves<bool>(o, false, false, [](uint32_t, uint32_t) { return true; });
    if (options.topology == GridOptions::Topology::Bool)
        out.push_back(buildNanoGrid<bool>(leaves, infoFor(g, options.name, nanovdb::GridClass::Unknown, checksum)));
    else
        out.push_back(buildNanoGrid<nanovdb::ValueMask>(leaves, infoFor(g, options.name, nanovdb::GridClass::Topology, checksum)));
    if (options.fog) { // the same leaves, 1.0 where active, the values never written out
        SparseVoxels<float> fog;
        fog.origins = leaves.origins;
        fog.masks = leaves.masks;
        fog.activeValue = 1.0f;
        out.push_back(buildNanoGrid<float>(fog, infoFor(g, "density", nanovdb::GridClass::FogVolume, checksum)));
    }
    for (auto& channel : octreeChannelNanoGrids(o, options, checksum)) out.push_back(std::move(channel));
    return out;
}

std::vector<OctreeChannel> octreeChannelVoxels(const Octree& o, const GridOptions& options)
{
    std::vector<OctreeChannel> out;
    if (!options.attributes) return out;
    const std::vector<uint64_t> offsets = brickVoxelOffsets(o);
    const VoxelAttributes& a = o.attributes;
    auto vectors = [&](const char* name, const std::vector<Vec3f>& values) {
        OctreeChannel c;
        c.name = name;
        c.vectors = octreeLeaves<nanovdb::Vec3f>(o, nanovdb::Vec3f(0.0f), true,
                                                 [&](uint32_t b, uint32_t n) { return vec(values[offsets[b] + n]); });
        out.push_back(std::move(c));
    };
    // Every channel computed, an empty grid where no voxel holds it.
    const uint32_t channels = o.channels();
    if (channels & kNormals) vectors("normal", a.normals);
    if (channels & kTriangles) {
        OctreeChannel c;
        c.name = "triangle_id";
        c.vector = false;
        c.ints = octreeLeaves<int32_t>(o, -1, true, [&](uint32_t b, uint32_t n) { return a.triangles[offsets[b] + n]; });
        out.push_back(std::move(c));
    }
    if (channels & kColors) vectors("color", a.colors);
    return out;
}

std::vector<NanoHandle> octreeChannelNanoGrids(const Octree& o, const GridOptions& options, bool checksum)
{
    std::vector<NanoHandle> out;
    for (const OctreeChannel& c : octreeChannelVoxels(o, options)) {
        const NanoGridInfo info = infoFor(o.grid, c.name, nanovdb::GridClass::Unknown, checksum);
        out.push_back(c.vector ? buildNanoGrid<nanovdb::Vec3f>(c.vectors, info) : buildNanoGrid<int32_t>(c.ints, info));
    }
    return out;
}

std::vector<NanoHandle> levelSetNanoGrids(const DistanceBricks& field, double exteriorBand, double interiorBand,
                                          const GridSpec& lattice, bool checksum)
{
    const GridSpec& g = field.grid;
    const FieldSigns& signs = field.signs;
    const bool signedField = field.signedField, winding = field.winding;
    const bool keepInside = winding || (signedField && field.region); // as levelSetGrids: no flood fill there
    const double scale = lattice.voxelSize;
    const float exterior = float(exteriorBand), interior = float(interiorBand);
    const float background = float(exteriorBand * scale);
    SparseVoxels<float> dist;
    SparseVoxels<int32_t> closest;
    dist.background = background;
    closest.background = -1;
    const size_t nb = field.bricks.size();
    // Per band brick, as levelSetGrids makes its leaves: kept when any voxel is
    // active, or (winding, a parity region) when it holds inside values. First each brick's
    // active voxels, then, once the kept bricks are counted, its values
    // written where its leaf goes (no copy of the band per brick).
    std::vector<Brick> active(nb);
    std::vector<uint8_t> keep(nb, 0);
    tbb::parallel_for(size_t(0), nb, [&](size_t i) {
        const Brick& near = field.near[i];
        size_t packed = field.offsets[i];
        for (uint32_t k = 0; k < 512; ++k) {
            if (!bitOf(near, k)) continue;
            const bool inside = signedField && bitOf(signs.inside[i], k);
            if (field.distances[packed++] < (inside ? interior : exterior))
                active[i].words[k >> 6] |= uint64_t(1) << (k & 63);
        }
        keep[i] = active[i].count() || (keepInside && signs.inside[i].count());
    });
    constexpr uint32_t kNone = UINT32_MAX;
    std::vector<uint32_t> leafAt(nb, kNone), closestAt(nb, kNone);
    for (size_t i = 0; i < nb; ++i) {
        if (!keep[i]) continue;
        const Origin o = brickOrigin(g, field.bricks[i]);
        leafAt[i] = uint32_t(dist.origins.size());
        dist.origins.push_back(o);
        dist.masks.push_back(active[i]);
        if (!field.closestTriangle || !active[i].count()) continue;
        closestAt[i] = uint32_t(closest.origins.size());
        closest.origins.push_back(o);
        closest.masks.push_back(active[i]);
    }
    dist.values.resize(dist.origins.size() * 512);
    closest.values.assign(closest.origins.size() * 512, -1);
    tbb::parallel_for(size_t(0), nb, [&](size_t i) {
        if (leafAt[i] == kNone) return;
        float* v = dist.values.data() + size_t(leafAt[i]) * 512;
        int32_t* c = closestAt[i] == kNone ? nullptr : closest.values.data() + size_t(closestAt[i]) * 512;
        size_t packed = field.offsets[i];
        for (uint32_t k = 0; k < 512; ++k) {
            float value = background;
            if (bitOf(field.near[i], k)) {
                if (bitOf(active[i], k)) {
                    value = float(double(field.distances[packed]) * scale);
                    if (c) c[k] = field.closest[packed];
                }
                ++packed;
            }
            v[k] = signedField && bitOf(signs.inside[i], k) ? -value : value;
        }
    });
    if (winding) {
        // Beyond the band: inactive values, negative where the winding number says inside.
        LeafIndex<float> leaves(dist, true);
        for (const auto& [b, m] : signs.partial) {
            const size_t i = leaves.touch(brickOrigin(g, b));
            for (uint32_t k = 0; k < 512; ++k)
                if (bitOf(m, k)) dist.values[i * 512 + k] = -background;
        }
        for (const BrickCoord& b : signs.insideBricks) dist.tiles.push_back({brickOrigin(g, b), 1, -background, false});
    } else if (signedField && field.region) {
        // A region's band is cut at its sides, so a flood fill would guess
        // beyond them; the parity runs say what the whole grid's fill says.
        fillRuns(dist, g, signs.runs, -background, false, true);
    }
    std::vector<NanoHandle> out;
    // Parity: OpenVDB's signed flood fill, as the OpenVDB path runs it, on the layout; then the checksum.
    const bool flood = signedField && !winding && !field.region;
    out.push_back(buildNanoGrid<float>(dist, infoFor(lattice, signedField ? "surface" : "distance",
                                                     signedField ? nanovdb::GridClass::LevelSet : nanovdb::GridClass::Unknown,
                                                     checksum && !flood)));
    if (flood) {
        signedFloodFill(*out.back().grid<float>());
        if (checksum) updateFullChecksum(*out.back().grid<float>());
    }
    if (field.closestTriangle)
        out.push_back(buildNanoGrid<int32_t>(closest, infoFor(lattice, "closest_triangle", nanovdb::GridClass::Unknown, checksum)));
    return out;
}

SparseVoxels<bool> solidVoxels(const SolidBricks& solid)
{
    const GridSpec& g = solid.grid;
    const FieldSigns& signs = solid.signs;
    SparseVoxels<bool> s;
    for (size_t i = 0; i < solid.bricks.size(); ++i) {
        if (!signs.inside[i].count()) continue;
        s.origins.push_back(brickOrigin(g, solid.bricks[i]));
        s.masks.push_back(signs.inside[i]);
    }
    {
        LeafIndex<bool> leaves(s, false);
        for (const auto& [b, m] : signs.partial) {
            Brick& mask = s.masks[leaves.touch(brickOrigin(g, b))];
            for (int w = 0; w < 8; ++w) mask.words[w] |= m.words[w];
        }
    }
    for (const BrickCoord& b : signs.insideBricks) s.tiles.push_back({brickOrigin(g, b), 1, true, true});
    fillRuns(s, g, signs.runs, true, true, false);
    return s;
}

NanoHandle bandNanoGrid(const DistanceBricks& field, double band, const GridSpec& lattice,
                        GridOptions::Topology topology, bool checksum)
{
    // levelSetNanoGrids' leaves of an unsigned field, their masks only.
    const float limit = float(band);
    SparseVoxels<bool> s;
    for (size_t i = 0; i < field.bricks.size(); ++i) {
        const Brick& near = field.near[i];
        Brick active;
        size_t packed = field.offsets[i];
        for (uint32_t k = 0; k < 512; ++k)
            if (bitOf(near, k) && field.distances[packed++] < limit) active.words[k >> 6] |= uint64_t(1) << (k & 63);
        if (!active.count()) continue;
        s.origins.push_back(brickOrigin(field.grid, field.bricks[i]));
        s.masks.push_back(active);
    }
    if (topology == GridOptions::Topology::Mask)
        return buildNanoGrid<nanovdb::ValueMask>(s, infoFor(lattice, "band", nanovdb::GridClass::Topology, checksum));
    return buildNanoGrid<bool>(s, infoFor(lattice, "band", nanovdb::GridClass::Unknown, checksum));
}

NanoHandle solidNanoGrid(const SolidBricks& solid, const GridSpec& lattice, GridOptions::Topology topology, bool checksum)
{
    SparseVoxels<bool> s = solidVoxels(solid);
    if (topology == GridOptions::Topology::Mask)
        return buildNanoGrid<nanovdb::ValueMask>(s, infoFor(lattice, "solid", nanovdb::GridClass::Topology, checksum));
    // NanoVDB keeps class Topology for ValueMask grids (nanovdb::isValid).
    // Bool: true exactly where active, as a topology copy of the mask gives
    // it, which is what the layout makes of bool leaves without values.
    return buildNanoGrid<bool>(s, infoFor(lattice, "solid", nanovdb::GridClass::Unknown, checksum));
}

} // namespace svo::vdb
