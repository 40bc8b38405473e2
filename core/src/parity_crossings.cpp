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
#include "svo/core/column_crossing.h"

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
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
        uint64_t lostHere = 0;
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            const Vec3d &A = local[f[0]], &B = local[f[1]], &C = local[f[2]];
            // The triangle's columns (distance_field.cpp's workItems with no growth).
            uint32_t lo[2], hi[2];
            bool any = true;
            for (int a = 0; a < 2; ++a) {
                const double first = std::max(std::ceil(std::min({A[a], B[a], C[a]})), 0.0);
                const double last = std::min(std::floor(std::max({A[a], B[a], C[a]})), double(grid.dims[a]) - 1);
                any = any && first <= last;
                if (any) lo[a] = uint32_t(first), hi[a] = uint32_t(last);
            }
            if (!any) continue;
            for (uint32_t y = lo[1]; y <= hi[1]; ++y)
                for (uint32_t x = lo[0]; x <= hi[0]; ++x) {
                    double zc = 0;
                    if (!column_crossing::svo_column_crossing(A, B, C, double(x), double(y), zc)) continue;
                    const double k = std::ceil(zc); // the first centre above the crossing
                    if (k >= dimZ) continue;        // nothing above it in the grid
                    const auto kz = uint32_t(std::max(k, 0.0));
                    const uint32_t i = index.find({x >> 3, y >> 3, kz >> 3});
                    if (i == BrickIndex::kNone) {
                        ++lostHere;
                        continue;
                    }
                    const uint32_t bit = ((x & 7) << 6) | ((y & 7) << 3) | (kz & 7);
                    __atomic_fetch_xor(&out.crossings[i].words[bit >> 6], uint64_t(1) << (bit & 63), __ATOMIC_RELAXED);
                }
        }
        lost += lostHere;
    });
    out.lost = lost;
    return out;
}

} // namespace svo
