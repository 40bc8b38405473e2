#include "svo/core/cpu_voxelizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "svo/core/voxel_key.h"
#include "triangle_voxels.h"

namespace svo {
namespace {

/// A triangle, or a slab of its rows: at most kColumnsPerItem columns.
struct WorkItem {
    uint32_t triangle;
    int64_t rowFirst, rowLast;
};
constexpr int64_t kColumnsPerItem = 4096;
constexpr int64_t kColumnsPerBatch = int64_t(1) << 20; // between polls

} // namespace

Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, double guard, VoxelMode mode,
                         const std::function<void(double)>& poll, RunStats* report)
{
    return voxelizeCpu(mesh, grid, VoxelBox{{0, 0, 0}, grid.dims}, guard, mode, poll, report);
}

namespace {

/// Whether the triangle's voxels can meet the box: its bounds, grown by a
/// voxel's half width, the guard and a voxel for rounding, overlap it.
bool mayMeet(const Vec3d& a, const Vec3d& b, const Vec3d& c, const VoxelBox& box, double guard)
{
    const double grow = 1.5 + std::max(guard, 0.0);
    const double lo[3] = {std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::min({a.z, b.z, c.z})};
    const double hi[3] = {std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y}), std::max({a.z, b.z, c.z})};
    for (int k = 0; k < 3; ++k)
        if (hi[k] + grow < double(box.lo[k]) || lo[k] - grow > double(box.hi[k]) - 1.0) return false;
    return true;
}

} // namespace

Voxelization voxelizeCpu(const TriangleMesh& mesh, const GridSpec& grid, const VoxelBox& box, double guard,
                         VoxelMode mode, const std::function<void(double)>& poll, RunStats* report)
{
    const bool whole = box.lo == std::array<uint32_t, 3>{0, 0, 0} && box.hi == grid.dims;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Vec3d> local(mesh.positions.size());
    for (size_t i = 0; i < local.size(); ++i) local[i] = grid.toLocal(mesh.positions[i]);

    // Work items and their columns, in triangle order.
    std::vector<WorkItem> items;
    std::vector<int64_t> columns;
    items.reserve(mesh.triangles.size());
    columns.reserve(mesh.triangles.size());
    int64_t total = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& f = mesh.triangles[t];
        if (!whole && !mayMeet(local[f[0]], local[f[1]], local[f[2]], box, guard)) continue;
        const detail::ColumnBounds b = detail::columnBounds(local[f[0]], local[f[1]], local[f[2]], grid, guard);
        if (b.u1 < b.u0 || b.v1 < b.v0) continue;
        const int64_t width = b.v1 - b.v0 + 1;
        const int64_t rows = std::max<int64_t>(1, kColumnsPerItem / width);
        for (int64_t r = b.u0; r <= b.u1; r += rows) {
            items.push_back({uint32_t(t), r, std::min(b.u1, r + rows - 1)});
            columns.push_back((items.back().rowLast - r + 1) * width);
            total += columns.back();
        }
    }

    tbb::enumerable_thread_specific<std::vector<uint64_t>> perThread;
    int64_t done = 0;
    for (size_t first = 0; first < items.size();) {
        if (poll) poll(total ? double(done) / double(total) : 0.0);
        size_t last = first;
        int64_t batch = 0;
        while (last < items.size() && batch < kColumnsPerBatch) batch += columns[last++];
        tbb::parallel_for(tbb::blocked_range<size_t>(first, last, 16), [&](const auto& r) {
            auto& out = perThread.local();
            for (size_t i = r.begin(); i != r.end(); ++i) {
                const WorkItem& item = items[i];
                const auto& f = mesh.triangles[item.triangle];
                detail::voxelizeTriangle(local[f[0]], local[f[1]], local[f[2]], grid, guard, mode,
                                         [&](uint64_t key) { out.push_back(key); }, item.rowFirst, item.rowLast);
            }
        });
        done += batch;
        first = last;
    }
    Voxelization result;
    result.grid = grid;
    uint64_t listEntries = 0;
    for (auto& part : perThread) {
        listEntries += part.size();
        if (whole) {
            result.keys.insert(result.keys.end(), part.begin(), part.end());
            continue;
        }
        for (const uint64_t key : part) {
            const auto [x, y, z] = unpackVoxelKey(key);
            if (box.contains(x, y, z)) result.keys.push_back(key);
        }
    }
    sortUniqueKeys(result.keys);
    if (report) {
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        *report = RunStats{};
        report->listEntries = listEntries;
        report->stages.push_back({"voxelize (cpu)", -1.0, ms});
    }
    return result;
}

} // namespace svo
