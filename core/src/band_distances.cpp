// Band distances on the CPU (svo/core/band_distances.h). Triangles are
// binned to the bricks their grown box spans; each brick then takes its
// triangles in one thread, so the least distance needs no atomics, nearest
// first, leaving out where a triangle's box is farther than what a centre
// already has (BrickNearest). The distance and the slab test are the shaders' own text
// (svo/core/triangle_distance.h), so each distance is the GPU's double, bit
// for bit (this file is compiled with -ffp-contract=off).
#include "svo/core/band_distances.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "brick_index.h"
#include "svo/core/triangle_distance.h"

namespace svo {
namespace {

namespace td = triangle_distance;

/// Triangle t's voxel box grown by the band and clamped to the grid, as the
/// GPU's work items cut it (distance_field.cpp's workItems); false when empty.
bool grownBox(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid, size_t t, double grow,
              std::array<uint32_t, 3>& lo, std::array<uint32_t, 3>& hi)
{
    const auto& f = mesh.triangles[t];
    for (int a = 0; a < 3; ++a) {
        const double l = std::min({local[f[0]][a], local[f[1]][a], local[f[2]][a]});
        const double h = std::max({local[f[0]][a], local[f[1]][a], local[f[2]][a]});
        const double first = std::max(std::ceil(l - grow), 0.0);
        const double last = std::min(std::floor(h + grow), double(grid.dims[a]) - 1);
        if (last < first) return false;
        lo[a] = uint32_t(first), hi[a] = uint32_t(last);
    }
    return true;
}

/// Per brick of the list, the triangles whose grown box meets it (CSR:
/// first[i] .. first[i + 1] in `triangles`), in no particular order: ties
/// in distance go to the smaller index whatever the order.
struct BrickTriangles {
    std::vector<uint64_t> first;
    std::vector<uint32_t> triangles;
};

BrickTriangles binTriangles(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                            const BrickIndex& index, size_t nBricks, double grow)
{
    const size_t n = mesh.triangles.size();
    // Two passes over the triangles: count per brick, then fill.
    std::vector<std::atomic<uint32_t>> count(nBricks + 1);
    const auto forBricks = [&](size_t t, auto&& f) {
        std::array<uint32_t, 3> lo{}, hi{};
        if (!grownBox(local, mesh, grid, t, grow, lo, hi)) return;
        for (uint32_t bx = lo[0] / 8; bx <= hi[0] / 8; ++bx)
            for (uint32_t by = lo[1] / 8; by <= hi[1] / 8; ++by)
                for (uint32_t bz = lo[2] / 8; bz <= hi[2] / 8; ++bz) {
                    const uint32_t i = index.find({bx, by, bz});
                    if (i != BrickIndex::kNone) f(i);
                }
    };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t)
            forBricks(t, [&](uint32_t i) { count[i].fetch_add(1, std::memory_order_relaxed); });
    });
    BrickTriangles out;
    out.first.resize(nBricks + 1);
    uint64_t total = 0;
    for (size_t i = 0; i < nBricks; ++i) {
        out.first[i] = total;
        total += count[i].load(std::memory_order_relaxed);
        count[i].store(0, std::memory_order_relaxed);
    }
    out.first[nBricks] = total;
    out.triangles.resize(total);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t)
            forBricks(t, [&](uint32_t i) {
                out.triangles[out.first[i] + count[i].fetch_add(1, std::memory_order_relaxed)] = uint32_t(t);
            });
    });
    return out;
}

/// The next float above @a f (finite, not negative).
inline float floatAbove(float f)
{
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    ++bits;
    std::memcpy(&f, &bits, 4);
    return f;
}

/// svo_prepared_distance2 without branches: the face's and the edges'
/// squared distances both computed and one kept, by the same operations, so
/// the same bits; a loop over centres vectorizes.
inline double flatDistance2(const Vec3d& p, const td::svo_Triangle& t)
{
    const bool inside = (t.n2 > 0.0) & (dot(cross(t.ab, p - t.a), t.n) >= 0.0) &
                        (dot(cross(t.bc, p - t.b), t.n) >= 0.0) & (dot(cross(t.ca, p - t.c), t.n) >= 0.0);
    const double h = dot(p - t.a, t.n);
    const double face = h * h / t.n2;
    const double edges = std::min(td::svo_edge_distance2(p, t.a, t.ab, t.lab),
                                  std::min(td::svo_edge_distance2(p, t.b, t.bc, t.lbc),
                                           td::svo_edge_distance2(p, t.c, t.ca, t.lca)));
    return inside ? face : edges;
}

/// The squared distances from triangle @a t to the 8 centres (x, y, z0 + k)
/// of a column. AVX2 where the CPU has it: the same IEEE operations lane by
/// lane (no FMA: -ffp-contract=off), so the same bits.
__attribute__((target_clones("avx2", "default"))) void columnDistances2(const td::svo_Triangle& t, double x, double y,
                                                                        double z0, double* out)
{
    for (int k = 0; k < 8; ++k) out[k] = flatDistance2(Vec3d{x, y, z0 + double(k)}, t);
}

/// From how many centres of a column a triangle's distances are computed
/// for the whole column at once (columnDistances2).
constexpr int kColumnAtOnce = 2;

/// The least distances (and closest triangles) at the 512 centres of the
/// brick at voxel @a org, from the triangles of its bin, as the minimum over
/// every triangle, bit for bit, with less work:
///  - Each centre keeps a limit on the squared distance past which a
///    triangle cannot change its result. Without closest triangles that is
///    the least squared distance so far: sqrt and the rounding to float are
///    monotone, so the least float is the float of the least square, taken
///    once at the end. With them it is the square of the next float above
///    the least so far, since a triangle at that float may still tie.
///  - A triangle whose box is farther from a centre (or from a whole column)
///    than its limit is left out there; the relative margin of 1e-9 covers
///    the rounding of the box's gap and of the distance. Where two centres
///    of a column or more are left, the triangle's distances to all eight
///    are computed at once (vectorized), else one by one.
///  - The triangles are taken nearest the brick's centre first, so the
///    limits fall early.
class BrickNearest {
public:
    BrickNearest(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid, float band,
                 bool bandOnly)
        : local_(local), mesh_(mesh), grid_(grid), band_(band), bandOnly_(bandOnly)
    {
    }

    /// Fills d[512] (and c[512] when not null) for the brick at @a org, from
    /// the triangles [first, last); a centre at the band or past it gets the band.
    void operator()(const std::array<uint32_t, 3>& org, const uint32_t* first, const uint32_t* last, float* d,
                    int32_t* c)
    {
        const double band = double(band_);
        // The square of a float is exact in double, and its sqrt the float again.
        const double start = c ? double(floatAbove(band_)) * double(floatAbove(band_)) : band * band;
        std::fill(limit2_, limit2_ + 512, start);
        std::fill(columnLimit2_, columnLimit2_ + 64, start);
        if (c) {
            std::fill(d, d + 512, band_);
            std::fill(c, c + 512, -1);
        }
        nearestFirst(org, first, last);
        for (const auto& ordered : order_) {
            if (c) triangle<true>(org, ordered.second, d, c);
            else triangle<false>(org, ordered.second, d, c);
        }
        if (!c) // a centre known to be in (bandOnly) holds the least distance it was found at
            for (int v = 0; v < 512; ++v) d[v] = limit2_[v] < 0 ? in_[v] : float(std::sqrt(limit2_[v]));
    }

private:
    /// order_: the bin's triangles by their squared distance from the brick's centre.
    void nearestFirst(const std::array<uint32_t, 3>& org, const uint32_t* first, const uint32_t* last)
    {
        order_.clear();
        const Vec3d centre{org[0] + 3.5, org[1] + 3.5, org[2] + 3.5};
        for (const uint32_t* t = first; t != last; ++t) {
            const auto& f = mesh_.triangles[*t];
            order_.emplace_back(td::svo_triangle_distance2(centre, local_[f[0]], local_[f[1]], local_[f[2]]), *t);
        }
        std::sort(order_.begin(), order_.end());
    }

    /// Triangle t at the centres of the brick within its grown box and its
    /// plane's slab, as band_distance_columns.comp narrows them, less those
    /// its box is too far from.
    template <bool kClosest>
    void triangle(const std::array<uint32_t, 3>& org, uint32_t t, float* d, int32_t* c)
    {
        const auto& f = mesh_.triangles[t];
        const Vec3d &A = local_[f[0]], &B = local_[f[1]], &C = local_[f[2]];
        std::array<uint32_t, 3> lo{}, hi{};
        grownBox(local_, mesh_, grid_, t, double(band_), lo, hi);
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(lo[a], org[a]) - org[a];
            hi[a] = std::min(hi[a], org[a] + 7) - org[a];
        }
        const Vec3d boxLo{std::min({A.x, B.x, C.x}), std::min({A.y, B.y, C.y}), std::min({A.z, B.z, C.z})};
        const Vec3d boxHi{std::max({A.x, B.x, C.x}), std::max({A.y, B.y, C.y}), std::max({A.z, B.z, C.z})};
        const td::svo_Triangle tri = td::svo_triangle_of(A, B, C);
        const td::svo_Slab slab = td::svo_slab_of(A, B, C, double(band_));
        constexpr double kShrink = 1.0 - 1e-9; // a gap's square, made safely smaller
        for (uint32_t x = lo[0]; x <= hi[0]; ++x)
            for (uint32_t y = lo[1]; y <= hi[1]; ++y) {
                const double px = double(org[0] + x), py = double(org[1] + y);
                const double gx = std::max({boxLo.x - px, px - boxHi.x, 0.0});
                const double gy = std::max({boxLo.y - py, py - boxHi.y, 0.0});
                const double gxy2 = (gx * gx + gy * gy) * kShrink;
                const uint32_t column = x * 8 + y;
                if (gxy2 > columnLimit2_[column]) continue;
                double z0 = double(org[2] + lo[2]), z1 = double(org[2] + hi[2]);
                if (!td::svo_slab_run(slab, px, py, z0, z1)) continue;
                // The centres the triangle's box is near enough to change, a bit each.
                const uint32_t first = column * 8 + uint32_t(z0) - org[2];
                uint32_t want = 0;
                for (uint32_t k = 0; k <= uint32_t(z1 - z0); ++k) {
                    const double pz = z0 + double(k);
                    const double gz = std::max({boxLo.z - pz, pz - boxHi.z, 0.0});
                    if (gxy2 + gz * gz * kShrink <= limit2_[first + k]) want |= 1u << k;
                }
                if (!want) continue;
                // A few alone, more all eight at once (the same bits either way).
                alignas(64) double column2[8];
                if (__builtin_popcount(want) >= kColumnAtOnce) {
                    columnDistances2(tri, px, py, z0, column2);
                } else {
                    for (uint32_t m = want; m; m &= m - 1) {
                        const int k = __builtin_ctz(m);
                        column2[k] = td::svo_prepared_distance2(Vec3d{px, py, z0 + double(k)}, tri);
                    }
                }
                bool nearer = false;
                for (uint32_t m = want; m; m &= m - 1) {
                    const int k = __builtin_ctz(m);
                    const uint32_t v = first + uint32_t(k);
                    const double d2 = column2[k];
                    if (d2 >= limit2_[v]) continue; // its float can neither win nor tie
                    if (!kClosest) {
                        limit2_[v] = d2;
                        nearer = true;
                        // Only the set asked: a centre nearer than the band is in, whatever
                        // its other triangles give; a negative limit leaves them all out.
                        if (bandOnly_ && float(std::sqrt(d2)) < band_) {
                            in_[v] = float(std::sqrt(d2));
                            limit2_[v] = -1.0;
                        }
                        continue;
                    }
                    const float dd = float(std::sqrt(d2));
                    if (dd < d[v]) {
                        d[v] = dd;
                        c[v] = int32_t(t);
                        limit2_[v] = double(floatAbove(dd)) * double(floatAbove(dd));
                        nearer = true;
                    } else if (dd == d[v] && int32_t(t) < c[v]) {
                        c[v] = int32_t(t);
                    }
                }
                if (nearer) columnLimit2_[column] = *std::max_element(limit2_ + column * 8, limit2_ + column * 8 + 8);
            }
    }

    const std::vector<Vec3d>& local_;
    const TriangleMesh& mesh_;
    const GridSpec& grid_;
    const float band_;
    const bool bandOnly_;
    float in_[512];           ///< bandOnly: the distance a centre was found in the band at
    double limit2_[512];      ///< per centre: the squared distance past which a triangle changes nothing
    double columnLimit2_[64]; ///< per column: the largest of its centres' limits
    std::vector<std::pair<double, uint32_t>> order_;
};

} // namespace

BandDistances bandDistances(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                            const std::vector<BrickCoord>& bricks, double band, bool closestTriangle,
                            const Checkpoint& checkpoint, bool bandOnly)
{
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (grid.dims[a] + 7) / 8;
    const BrickIndex index(bricks, limit);
    const size_t nb = bricks.size();
    const BrickTriangles bins = binTriangles(local, mesh, grid, index, nb, band);
    checkpoint(0.1, "band distance");

    const float bandF = float(band);
    // Made from a function: the exemplar form would copy the mesh and positions into the container.
    tbb::enumerable_thread_specific<BrickNearest> perThread(
        [&] { return BrickNearest(local, mesh, grid, bandF, bandOnly && !closestTriangle); });
    BandDistances out;
    out.near.resize(nb);
    out.offsets.resize(nb);
    // Batches of bricks: all 512 values of a batch's bricks, then packed at
    // offsets counted from the masks; the checkpoint runs between batches.
    constexpr size_t kBatch = 4096;
    std::vector<float> dist(std::min(nb, kBatch) * 512);
    std::vector<int32_t> near(closestTriangle ? dist.size() : 0);
    for (size_t b0 = 0; b0 < nb; b0 += kBatch) {
        const size_t b1 = std::min(nb, b0 + kBatch);
        tbb::parallel_for(tbb::blocked_range<size_t>(b0, b1, 4), [&](const tbb::blocked_range<size_t>& r) {
            BrickNearest& nearest = perThread.local();
            for (size_t i = r.begin(); i != r.end(); ++i) {
                float* d = &dist[(i - b0) * 512];
                int32_t* c = closestTriangle ? &near[(i - b0) * 512] : nullptr;
                const std::array<uint32_t, 3> org{8 * bricks[i][0], 8 * bricks[i][1], 8 * bricks[i][2]};
                const uint32_t* binned = bins.triangles.data();
                nearest(org, binned + bins.first[i], binned + bins.first[i + 1], d, c);
                Brick m;
                for (uint32_t v = 0; v < 512; ++v)
                    if (d[v] < bandF) m.words[v >> 6] |= uint64_t(1) << (v & 63);
                out.near[i] = m;
            }
        });
        uint64_t at = out.distances.size();
        for (size_t i = b0; i < b1; ++i) {
            out.offsets[i] = uint32_t(at);
            at += out.near[i].count();
        }
        out.distances.resize(at);
        if (closestTriangle) out.closest.resize(at);
        tbb::parallel_for(tbb::blocked_range<size_t>(b0, b1, 64), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) {
                uint32_t o = out.offsets[i];
                for (int w = 0; w < 8; ++w)
                    for (uint64_t m = out.near[i].words[w]; m; m &= m - 1) {
                        const size_t v = (i - b0) * 512 + 64 * size_t(w) + size_t(__builtin_ctzll(m));
                        out.distances[o] = dist[v];
                        if (closestTriangle) out.closest[o] = near[v];
                        ++o;
                    }
            }
        });
        checkpoint(0.1 + 0.9 * double(b1) / double(nb), "band distance");
    }
    return out;
}

} // namespace svo
