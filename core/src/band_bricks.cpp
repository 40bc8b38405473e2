// The band's bricks (svo/core/band_bricks.h).
#include "svo/core/band_bricks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include "svo/core/error.h"

namespace svo {
namespace {

/// The box of a non-empty brick's set bits: lowest x, y, z, then highest.
/// Word x holds bits 8y + z, so the words give x, their OR's bytes y, and
/// the OR of those bytes z.
std::array<uint32_t, 6> occupiedBox(const Brick& m)
{
    uint32_t x0 = 8, x1 = 0;
    uint64_t all = 0;
    for (uint32_t x = 0; x < 8; ++x)
        if (m.words[x]) x0 = std::min(x0, x), x1 = x, all |= m.words[x];
    uint32_t y0 = 8, y1 = 0, zBits = 0;
    for (uint32_t y = 0; y < 8; ++y)
        if (const uint32_t byte = uint32_t(all >> (8 * y)) & 0xFFu) y0 = std::min(y0, y), y1 = y, zBits |= byte;
    const uint32_t z0 = uint32_t(__builtin_ctz(zBits)), z1 = 31u - uint32_t(__builtin_clz(zBits));
    return {x0, y0, z0, x1, y1, z1};
}

/// A bit per brick of a grid `limit` + 1 bricks wide, in x-major order:
/// set from many threads, then read in order, the set bits are the bricks
/// sorted and unique, without a sort. Used up to 2^33 bricks (1 GiB).
struct BrickBitmap {
    uint64_t ny, nz;
    std::vector<std::atomic<uint64_t>> bits;

    static uint64_t cells(const std::array<uint32_t, 3>& limit)
    {
        return uint64_t(limit[0] + 1) * (limit[1] + 1) * (limit[2] + 1);
    }
    static bool fits(const std::array<uint32_t, 3>& limit) { return cells(limit) <= (uint64_t(1) << 33); }
    explicit BrickBitmap(const std::array<uint32_t, 3>& limit)
        : ny(limit[1] + 1), nz(limit[2] + 1), bits((cells(limit) + 63) / 64)
    {
    }
    void set(const BrickCoord& b)
    {
        const uint64_t i = (b[0] * ny + b[1]) * nz + b[2];
        bits[i >> 6].fetch_or(uint64_t(1) << (i & 63), std::memory_order_relaxed);
    }
    std::vector<BrickCoord> sorted() const
    {
        std::vector<BrickCoord> all;
        for (uint64_t w = 0; w < bits.size(); ++w)
            for (uint64_t m = bits[w].load(std::memory_order_relaxed); m; m &= m - 1) {
                const uint64_t i = 64 * w + uint64_t(__builtin_ctzll(m));
                all.push_back({uint32_t(i / (ny * nz)), uint32_t(i / nz % ny), uint32_t(i % nz)});
            }
        return all;
    }
};

/// `all` sorted in x-major order and unique: for grids too large for a BrickBitmap.
std::vector<BrickCoord> sortedUnique(std::vector<BrickCoord> all)
{
    tbb::parallel_sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
}

} // namespace

/// The bricks holding every voxel within `reach` voxels (Chebyshev) of an
/// occupied voxel of the octree: each brick's occupied box grown by reach.
std::vector<BrickCoord> grownBricks(const Octree& octree, uint32_t reach)
{
    const auto refs = occupiedBricks(octree);
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (octree.grid.dims[a] + 7) / 8 - 1;
    std::vector<std::vector<BrickCoord>> parts(refs.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, refs.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t n = r.begin(); n != r.end(); ++n) {
            const std::array<uint32_t, 6> box = occupiedBox(octree.bricks[refs[n].index]);
            const std::array<uint32_t, 3> lo{box[0], box[1], box[2]}, hi{box[3], box[4], box[5]};
            std::array<uint32_t, 3> b0{}, b1{};
            for (int a = 0; a < 3; ++a) {
                const int64_t o = refs[n].origin[a];
                b0[a] = uint32_t(std::max<int64_t>(o + lo[a] - reach, 0) / 8);
                b1[a] = std::min(uint32_t((o + hi[a] + reach) / 8), limit[a]);
            }
            for (uint32_t x = b0[0]; x <= b1[0]; ++x)
                for (uint32_t y = b0[1]; y <= b1[1]; ++y)
                    for (uint32_t z = b0[2]; z <= b1[2]; ++z) parts[n].push_back({x, y, z});
        }
    });
    if (!BrickBitmap::fits(limit)) {
        std::vector<BrickCoord> all;
        for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
        return sortedUnique(std::move(all));
    }
    BrickBitmap bitmap(limit);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, parts.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t n = r.begin(); n != r.end(); ++n)
            for (const BrickCoord& b : parts[n]) bitmap.set(b);
    });
    return bitmap.sorted();
}

/// The bricks holding every voxel centre within `grow` voxels of a
/// triangle (local coordinates: centres at integers): per triangle, the
/// bricks its box grown by `grow` spans that also meet the slab of centres
/// within `grow` of its plane, found a column of bricks at a time. Both
/// tests hold every centre whose distance to the triangle is at most `grow`,
/// widened by 1e-6 relative and absolute against rounding (and the slab as
/// band_distance.glsl's for needles), so no centre the distance pass keeps
/// is left out, and a slanted triangle's box costs only its slab.
/// @throw svo::Error when the boxes span more than 2^32 bricks in all, what
///        the distance pass refuses too (a band far wider than the mesh's features).
std::vector<BrickCoord> bricksNearTriangles(const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                                            const GridSpec& g, double grow)
{
    return bricksNearTriangles(local, mesh, g, grow, VoxelBox{{0, 0, 0}, g.dims});
}

std::vector<BrickCoord> bricksNearTriangles(const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                                            const GridSpec& g, double grow, const VoxelBox& within)
{
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (g.dims[a] + 7) / 8 - 1;
    // The bricks that meet `within`, as voxel bounds: a brick is listed or not
    // as the whole grid lists it, and a triangle far from them costs nothing.
    std::array<double, 3> first{}, last{};
    for (int a = 0; a < 3; ++a) {
        first[a] = double(within.lo[a] / 8 * 8);
        last[a] = double(std::min<uint64_t>((uint64_t(within.hi[a]) + 7) / 8 * 8, g.dims[a])) - 1;
    }
    if (within.empty()) return {};
    const double reach = grow * (1 + 1e-6) + 1e-6;
    // Triangle t's centres within reach of its box, clamped to those bricks
    // (and one past them) before converting; false when none is in them.
    const auto boxOf = [&](size_t t, std::array<int64_t, 3>& lo, std::array<int64_t, 3>& hi) {
        const auto& f = mesh.triangles[t];
        bool any = true;
        for (int k = 0; k < 3; ++k) {
            const double a = local[f[0]][k], b = local[f[1]][k], c = local[f[2]][k];
            lo[k] = int64_t(std::clamp(std::ceil(std::min({a, b, c}) - reach), first[k], last[k] + 1));
            hi[k] = int64_t(std::clamp(std::floor(std::max({a, b, c}) + reach), first[k] - 1, last[k]));
            any &= lo[k] <= hi[k];
        }
        return any;
    };
    const size_t n = mesh.triangles.size();
    const uint64_t spanned = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 4096), uint64_t(0),
        [&](const tbb::blocked_range<size_t>& r, uint64_t sum) {
            std::array<int64_t, 3> lo{}, hi{};
            for (size_t t = r.begin(); t != r.end(); ++t)
                if (boxOf(t, lo, hi))
                    sum += uint64_t(hi[0] / 8 - lo[0] / 8 + 1) * uint64_t(hi[1] / 8 - lo[1] / 8 + 1) *
                           uint64_t(hi[2] / 8 - lo[2] / 8 + 1);
            return sum;
        },
        std::plus<uint64_t>());
    if (spanned > (uint64_t(1) << 32))
        throw Unsupported(fmt::format("the distance field needs {} brick work items, more than one pass holds (2^32); use "
                                "a coarser grid or a narrower band",
                                spanned));
    // Calls emit(brick) for every brick near triangle t.
    const auto forEachBrick = [&](size_t t, auto&& emit) {
        std::array<int64_t, 3> lo{}, hi{};
        if (!boxOf(t, lo, hi)) return;
        const auto& f = mesh.triangles[t];
        const Vec3d& a = local[f[0]];
        const Vec3d& b = local[f[1]];
        const Vec3d& c = local[f[2]];
        // The plane: h(p) = n . (p - a), within the slab when |h| <= slab,
        // widened as band_distance.glsl's slabOf for needles, whose normal
        // is rounding noise.
        const Vec3d nrm = cross(b - a, c - a);
        const double e1 = std::sqrt(dot(b - a, b - a)), e2 = std::sqrt(dot(c - a, c - a));
        const double slab = reach * std::sqrt(dot(nrm, nrm)) + 1e-10 * e1 * e2 * (e1 + e2 + reach);
        for (int64_t bx = lo[0] / 8; bx <= hi[0] / 8; ++bx)
            for (int64_t by = lo[1] / 8; by <= hi[1] / 8; ++by) {
                // This brick column's centres in x and y, and h over them at z = 0.
                const double x0 = double(std::max(lo[0], 8 * bx)), x1 = double(std::min(hi[0], 8 * bx + 7));
                const double y0 = double(std::max(lo[1], 8 * by)), y1 = double(std::min(hi[1], 8 * by + 7));
                const double h0 = nrm.x * (0.5 * (x0 + x1) - a.x) + nrm.y * (0.5 * (y0 + y1) - a.y) - nrm.z * a.z;
                const double spread = std::abs(nrm.x) * 0.5 * (x1 - x0) + std::abs(nrm.y) * 0.5 * (y1 - y0);
                double z0 = double(lo[2]), z1 = double(hi[2]);
                if (nrm.z != 0) {
                    // n.z z + h0 within [-slab - spread, slab + spread].
                    const double below = (-slab - spread - h0) / nrm.z, above = (slab + spread - h0) / nrm.z;
                    z0 = std::max(z0, std::ceil(std::min(below, above) - 1e-6));
                    z1 = std::min(z1, std::floor(std::max(below, above) + 1e-6));
                } else if (std::abs(h0) > slab + spread) {
                    continue;
                }
                if (!(z0 <= z1)) continue;
                for (int64_t bz = int64_t(z0) / 8; bz <= int64_t(z1) / 8; ++bz)
                    emit(BrickCoord{uint32_t(bx), uint32_t(by), uint32_t(bz)});
            }
    };
    if (BrickBitmap::fits(limit)) {
        BrickBitmap bitmap(limit);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t t = r.begin(); t != r.end(); ++t) forEachBrick(t, [&](const BrickCoord& b) { bitmap.set(b); });
        });
        return bitmap.sorted();
    }
    tbb::enumerable_thread_specific<std::vector<BrickCoord>> lists;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
        auto& list = lists.local();
        for (size_t t = r.begin(); t != r.end(); ++t) forEachBrick(t, [&](const BrickCoord& b) { list.push_back(b); });
    });
    std::vector<BrickCoord> all;
    for (auto& list : lists) all.insert(all.end(), list.begin(), list.end());
    return sortedUnique(std::move(all));
}

} // namespace svo
