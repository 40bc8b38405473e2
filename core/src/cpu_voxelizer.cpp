#include "svo/core/cpu_voxelizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "svo/core/overlap.h"
#include "svo/core/voxel_key.h"

namespace svo {
namespace {

template <typename Emit>
void voxelizeTriangle(const Vec3d& a, const Vec3d& b, const Vec3d& c, const GridSpec& grid, double guard, Emit&& emit)
{
    using namespace overlap_double;
    const double half = 0.5 + guard;
    const double ulp = std::ldexp(1.0, -53);
    const int w = svo_dominant_axis(cross(b - a, c - a));
    const int u = (w + 1) % 3, v = (w + 2) % 3;
    auto range = [&](int axis, int64_t& lo, int64_t& hi) {
        const double mn = std::min({a[axis], b[axis], c[axis]}), mx = std::max({a[axis], b[axis], c[axis]});
        lo = std::max<int64_t>(0, int64_t(std::ceil(mn - half)));
        hi = std::min<int64_t>(int64_t(grid.dims[axis]) - 1, int64_t(std::floor(mx + half)));
    };
    int64_t u0, u1, v0, v1, w0, w1;
    range(u, u0, u1);
    range(v, v0, v1);
    range(w, w0, w1);
    for (int64_t i = u0; i <= u1; ++i)
        for (int64_t j = v0; j <= v1; ++j) {
            const Vec3d r = svo_column_range(a, b, c, w, double(i), double(j), half, ulp);
            const int64_t k0 = std::max(w0, int64_t(std::ceil(r.x))), k1 = std::min(w1, int64_t(std::floor(r.y)));
            for (int64_t k = k0; k <= k1; ++k) {
                Vec3d centre;
                centre[u] = double(i);
                centre[v] = double(j);
                centre[w] = double(k);
                if (svo_triangle_box_overlap(a, b, c, centre, half))
                    emit(packVoxelKey(uint32_t(centre.x), uint32_t(centre.y), uint32_t(centre.z)));
            }
        }
}

} // namespace

Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, double guard)
{
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Vec3d> local(mesh.positions.size());
    for (size_t i = 0; i < local.size(); ++i) local[i] = grid.toLocal(mesh.positions[i]);

    tbb::enumerable_thread_specific<std::vector<uint64_t>> perThread;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 256), [&](const auto& r) {
        auto& out = perThread.local();
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            voxelizeTriangle(local[f[0]], local[f[1]], local[f[2]], grid, guard,
                             [&](uint64_t key) { out.push_back(key); });
        }
    });
    Voxelization result;
    result.grid = grid;
    for (auto& part : perThread) {
        result.listEntries += part.size();
        result.keys.insert(result.keys.end(), part.begin(), part.end());
    }
    sortUniqueKeys(result.keys);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    result.stages.push_back({"voxelize (cpu)", -1.0, ms});
    return result;
}

} // namespace svo
