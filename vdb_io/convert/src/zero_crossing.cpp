#include "svo/vdb_io/zero_crossing.h"

#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "svo/core/voxel_key.h"

namespace svo::vdb {
namespace {

/// Whether a float or double grid not of class level set holds an unsigned
/// field: a positive background, every active value in [0, background].
template <typename GridT>
bool unsignedField(const GridT& grid)
{
    const auto background = grid.background();
    if (grid.getGridClass() != openvdb::GRID_UNKNOWN || !(background > 0)) return false;
    for (auto it = grid.cbeginValueOn(); it; ++it)
        if (!(*it >= 0 && *it <= background)) return false;
    return true;
}

template <typename GridT>
DistanceKind kindOf(const GridT& grid)
{
    if (grid.getGridClass() == openvdb::GRID_LEVEL_SET) return DistanceKind::Signed;
    return unsignedField(grid) ? DistanceKind::Unsigned : DistanceKind::None;
}

/// Each brick's voxels narrowed to the zero crossing, in parallel; an
/// accessor per task (OpenVDB's accessors are not shared between threads).
template <typename GridT>
void narrow(const GridT& grid, DistanceKind kind, VdbBricks& vb)
{
    using Value = typename GridT::ValueType;
    const Value half = Value(0.5 * grid.voxelSize()[0]);
    const std::array<int64_t, 3> anchor = vb.grid.anchor;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vb.bricks.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        auto acc = grid.getConstAccessor();
        for (size_t i = r.begin(); i != r.end(); ++i) {
            auto& [key, brick] = vb.bricks[i];
            const auto local = unpackVoxelKey(key);
            const openvdb::Coord origin(int(anchor[0] + local[0]), int(anchor[1] + local[1]), int(anchor[2] + local[2]));
            Brick kept;
            for (uint32_t w = 0; w < 8; ++w)
                for (uint64_t m = brick.words[w]; m; m &= m - 1) {
                    const uint32_t bit = 64 * w + uint32_t(__builtin_ctzll(m));
                    const openvdb::Coord c = origin.offsetBy(int(bit >> 6), int((bit >> 3) & 7), int(bit & 7));
                    const Value v = acc.getValue(c);
                    bool at = false;
                    if (kind == DistanceKind::Unsigned) {
                        at = std::abs(v) <= half;
                    } else if (v < 0) {
                        for (int axis = 0; axis < 3 && !at; ++axis)
                            for (int step : {-1, 1}) {
                                openvdb::Coord n = c;
                                n[axis] += step;
                                if (!(acc.getValue(n) < 0)) at = true;
                            }
                    }
                    if (at) kept.words[w] |= uint64_t(1) << (bit & 63);
                }
            brick = kept;
        }
    });
    size_t out = 0;
    for (auto& b : vb.bricks)
        if (b.second.count()) vb.bricks[out++] = b;
    vb.bricks.resize(out);
}

/// Calls f(typed grid) for float and double grids; false for others.
template <typename F>
bool withFloatGrid(const openvdb::GridBase& grid, F&& f)
{
    if (const auto* g = dynamic_cast<const openvdb::FloatGrid*>(&grid)) return f(*g), true;
    if (const auto* g = dynamic_cast<const openvdb::DoubleGrid*>(&grid)) return f(*g), true;
    return false;
}

} // namespace

DistanceKind distanceKind(const openvdb::GridBase& grid)
{
    DistanceKind kind = DistanceKind::None;
    withFloatGrid(grid, [&](const auto& g) { kind = kindOf(g); });
    return kind;
}

uint64_t keepZeroCrossing(const openvdb::GridBase& grid, VdbBricks& bricks)
{
    uint64_t before = 0;
    for (const auto& b : bricks.bricks) before += b.second.count();
    withFloatGrid(grid, [&](const auto& g) {
        const DistanceKind kind = kindOf(g);
        if (kind != DistanceKind::None) narrow(g, kind, bricks);
    });
    return before;
}

} // namespace svo::vdb
