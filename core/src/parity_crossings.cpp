// Parity crossings on the CPU (svo/core/parity_crossings.h): parity_flips.comp's
// column test and crossing height, one text (svo/core/column_crossing.h), a
// triangle per task, marks by atomic XOR.
#include "svo/core/parity_crossings.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "brick_index.h"
#include "column_crossings.h"

namespace svo {

ParityCrossings parityCrossings(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                                const std::vector<BrickCoord>& bricks)
{
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (grid.dims[a] + 7) / 8;
    const BrickIndex index(bricks, limit);
    ParityCrossings out;
    out.crossings.resize(bricks.size());
    std::atomic<uint64_t> lost{0};
    const double dimZ = double(grid.dims[2]);
    const uint32_t columns[2] = {grid.dims[0], grid.dims[1]};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
        uint64_t lostHere = 0;
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            const Vec3d &A = local[f[0]], &B = local[f[1]], &C = local[f[2]];
            // The triangle's columns (distance_field.cpp's workItems with no growth).
            forEachColumnCrossing(A, B, C, 0.0, 1.0, columns, [&](uint32_t x, uint32_t y, double zc, bool) {
                const double k = std::ceil(zc); // the first centre above the crossing
                if (k >= dimZ) return;          // nothing above it in the grid
                const auto kz = uint32_t(std::max(k, 0.0));
                const uint32_t i = index.find({x >> 3, y >> 3, kz >> 3});
                if (i == BrickIndex::kNone) {
                    ++lostHere;
                    return;
                }
                const uint32_t bit = ((x & 7) << 6) | ((y & 7) << 3) | (kz & 7);
                __atomic_fetch_xor(&out.crossings[i].words[bit >> 6], uint64_t(1) << (bit & 63), __ATOMIC_RELAXED);
            });
        }
        lost += lostHere;
    });
    out.lost = lost;
    return out;
}

} // namespace svo
