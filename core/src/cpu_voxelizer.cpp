#include "svo/core/cpu_voxelizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "triangle_voxels.h"

namespace svo {
Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, double guard, VoxelMode mode)
{
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Vec3d> local(mesh.positions.size());
    for (size_t i = 0; i < local.size(); ++i) local[i] = grid.toLocal(mesh.positions[i]);

    tbb::enumerable_thread_specific<std::vector<uint64_t>> perThread;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 256), [&](const auto& r) {
        auto& out = perThread.local();
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            detail::voxelizeTriangle(local[f[0]], local[f[1]], local[f[2]], grid, guard, mode,
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
