// Band distances on the CPU (svo/core/band_distances.h). Triangles are
// binned to the bricks their grown box spans; each brick then takes its
// triangles in one thread, so the least distance needs no atomics. The
// distance and the tests that skip centres are the shaders' own text
// (svo/core/triangle_distance.h), so each distance is the GPU's double, bit
// for bit (this file is compiled with -ffp-contract=off).
#include "svo/core/band_distances.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <tbb/blocked_range.h>
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

} // namespace

BandDistances bandDistances(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                            const std::vector<BrickCoord>& bricks, double band, bool closestTriangle,
                            const Checkpoint& checkpoint)
{
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (grid.dims[a] + 7) / 8;
    const BrickIndex index(bricks, limit);
    const size_t nb = bricks.size();
    const BrickTriangles bins = binTriangles(local, mesh, grid, index, nb, band);
    checkpoint(0.1, "band distance");

    const float bandF = float(band);
    const double band2 = double(bandF) * double(bandF);
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
            for (size_t i = r.begin(); i != r.end(); ++i) {
                float* d = &dist[(i - b0) * 512];
                int32_t* c = closestTriangle ? &near[(i - b0) * 512] : nullptr;
                std::fill(d, d + 512, std::numeric_limits<float>::infinity());
                if (c) std::fill(c, c + 512, -1);
                const std::array<uint32_t, 3> org{8 * bricks[i][0], 8 * bricks[i][1], 8 * bricks[i][2]};
                for (uint64_t k = bins.first[i]; k < bins.first[i + 1]; ++k) {
                    const uint32_t t = bins.triangles[k];
                    const auto& f = mesh.triangles[t];
                    const Vec3d &A = local[f[0]], &B = local[f[1]], &C = local[f[2]];
                    std::array<uint32_t, 3> lo{}, hi{};
                    grownBox(local, mesh, grid, t, band, lo, hi);
                    const Vec3d boxLo{std::min({A.x, B.x, C.x}), std::min({A.y, B.y, C.y}), std::min({A.z, B.z, C.z})};
                    const Vec3d boxHi{std::max({A.x, B.x, C.x}), std::max({A.y, B.y, C.y}), std::max({A.z, B.z, C.z})};
                    const td::svo_Triangle tri = td::svo_triangle_of(A, B, C);
                    const td::svo_Slab slab = td::svo_slab_of(A, B, C, double(bandF));
                    for (int a = 0; a < 3; ++a) {
                        lo[a] = std::max(lo[a], org[a]) - org[a];
                        hi[a] = std::min(hi[a], org[a] + 7) - org[a];
                    }
                    for (uint32_t x = lo[0]; x <= hi[0]; ++x)
                        for (uint32_t y = lo[1]; y <= hi[1]; ++y) {
                            const double px = double(org[0] + x), py = double(org[1] + y);
                            // The centres of this column near the triangle's
                            // box, then within its plane's slab, as
                            // band_distance_columns.comp narrows them.
                            double z0 = double(org[2] + lo[2]), z1 = double(org[2] + hi[2]);
                            if (!td::svo_box_run(boxLo, boxHi, px, py, band2, z0, z1) ||
                                !td::svo_slab_run(slab, px, py, z0, z1))
                                continue;
                            for (double pz = z0; pz <= z1; pz += 1.0) {
                                const Vec3d p{px, py, pz};
                                const float dd = float(std::sqrt(td::svo_prepared_distance2(p, tri)));
                                if (dd > bandF) continue;
                                const uint32_t v = x * 64 + y * 8 + uint32_t(pz) - org[2];
                                if (dd < d[v]) {
                                    d[v] = dd;
                                    if (c) c[v] = int32_t(t);
                                } else if (c && dd == d[v] && int32_t(t) < c[v]) {
                                    c[v] = int32_t(t);
                                }
                            }
                        }
                }
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
