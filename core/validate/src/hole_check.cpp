#include "svo/validate/hole_check.h"

#include <CGAL/Side_of_triangle_mesh.h>
#include <atomic>
#include <deque>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "closed_surface.h"
#include "local_points.h"
#include "svo/core/error.h"
#include "svo/core/voxel_key.h"

namespace svo::validate {
namespace {

using K = detail::K;
using SurfaceMesh = detail::SurfaceMesh;

/// The 26 (or first 6) neighbour offsets; code n+1 in the parent array means
/// "reached from the voxel at minus offset n".
std::vector<std::array<int, 3>> offsets(int connectivity)
{
    std::vector<std::array<int, 3>> o = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    if (connectivity == 26)
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z)
                    if (std::abs(x) + std::abs(y) + std::abs(z) > 1) o.push_back({x, y, z});
    return o;
}

} // namespace

HoleCheck checkHoles(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<uint64_t>& voxels,
                     int connectivity, const std::function<void(uint64_t, uint64_t)>& progress)
{
    HoleCheck h;
    h.connectivity = connectivity;
    // A closed, orientable surface, or the check does not apply.
    detail::ClosedSurface closed = detail::closedSurface(mesh, detail::localPoints(mesh, grid));
    if (!closed.closed) {
        h.reason = closed.reason;
        return h;
    }
    const SurfaceMesh& sm = closed.surface;
    h.applies = true;

    // Padded grid: local voxel v sits at v + 1; the outer layer is empty.
    const uint64_t nx = grid.dims[0] + 2ull, ny = grid.dims[1] + 2ull, nz = grid.dims[2] + 2ull;
    const uint64_t cells = nx * ny * nz;
    if (cells > (uint64_t(1) << 33))
        throw OutOfMemory(fmt::format("{}: the hole check needs {:.1f} GB for a {} x {} x {} grid; validate at a coarser "
                                      "resolution or skip the hole check",
                                      mesh.source, double(cells) / 1e9, nx, ny, nz));
    auto at = [&](uint64_t x, uint64_t y, uint64_t z) { return (x * ny + y) * nz + z; };
    // state: 0 empty and unreached, 255 occupied, 1..26 reached via offset code-1, 254 the seed.
    std::vector<uint8_t> state(cells, 0);
    for (uint64_t k : voxels) {
        const auto p = unpackVoxelKey(k);
        if (p[0] >= grid.dims[0] || p[1] >= grid.dims[1] || p[2] >= grid.dims[2])
            throw InvalidInput(fmt::format("{}: voxel ({}, {}, {}) lies outside the {} x {} x {} grid", mesh.source, p[0], p[1],
                                           p[2], grid.dims[0], grid.dims[1], grid.dims[2]));
        state[at(p[0] + 1ull, p[1] + 1ull, p[2] + 1ull)] = 255;
    }
    const auto off = offsets(connectivity);
    std::deque<uint64_t> queue = {0};
    state[0] = 254;
    std::vector<uint64_t> frontier;
    const auto bounds = mesh.bounds();
    const Vec3d blo = grid.toLocal(bounds.min), bhi = grid.toLocal(bounds.max);
    while (!queue.empty()) {
        const uint64_t i = queue.front();
        queue.pop_front();
        ++h.filled;
        const int64_t x = int64_t(i / (ny * nz)), y = int64_t(i / nz % ny), z = int64_t(i % nz);
        bool touches = false;
        for (size_t n = 0; n < off.size(); ++n) {
            const int64_t a = x + off[n][0], b = y + off[n][1], c = z + off[n][2];
            if (a < 0 || b < 0 || c < 0 || a >= int64_t(nx) || b >= int64_t(ny) || c >= int64_t(nz)) continue;
            uint8_t& s = state[at(uint64_t(a), uint64_t(b), uint64_t(c))];
            if (s == 255) touches = true;
            if (s) continue;
            s = uint8_t(n + 1);
            queue.push_back(at(uint64_t(a), uint64_t(b), uint64_t(c)));
        }
        // Only centres inside the mesh's bounds can be inside the mesh.
        const double lx = double(x - 1), ly = double(y - 1), lz = double(z - 1);
        if (touches && lx >= blo.x && lx <= bhi.x && ly >= blo.y && ly <= bhi.y && lz >= blo.z && lz <= bhi.z)
            frontier.push_back(i);
    }
    h.frontier = frontier.size();

    // Inside tests on the frontier, in parallel after one serial call builds the tree.
    const CGAL::Side_of_triangle_mesh<SurfaceMesh, K> side(sm);
    auto centre = [&](uint64_t i) {
        return K::Point_3(double(int64_t(i / (ny * nz)) - 1), double(int64_t(i / nz % ny) - 1), double(int64_t(i % nz) - 1));
    };
    if (!frontier.empty()) (void)side(centre(frontier[0]));
    std::atomic<uint64_t> firstInside{~uint64_t(0)}, done{0};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, frontier.size(), 1024), [&](const auto& r) {
        for (size_t f = r.begin(); f != r.end(); ++f) {
            if (side(centre(frontier[f])) != CGAL::ON_BOUNDED_SIDE) continue;
            uint64_t cur = firstInside.load();
            while (f < cur && !firstInside.compare_exchange_weak(cur, f)) {
            }
        }
        const uint64_t d = done.fetch_add(r.size()) + r.size();
        if (progress) progress(d, frontier.size());
    });
    if (firstInside.load() == ~uint64_t(0)) return h;

    // The fill's path back to the seed, reversed: outside -> inside.
    h.leak = true;
    for (uint64_t i = frontier[firstInside.load()];;) {
        const int64_t x = int64_t(i / (ny * nz)), y = int64_t(i / nz % ny), z = int64_t(i % nz);
        h.leakPath.push_back({grid.anchor[0] + x - 1, grid.anchor[1] + y - 1, grid.anchor[2] + z - 1});
        const uint8_t s = state[i];
        if (s == 254) break;
        const auto& o = off[s - 1];
        i = at(uint64_t(x - o[0]), uint64_t(y - o[1]), uint64_t(z - o[2]));
    }
    std::reverse(h.leakPath.begin(), h.leakPath.end());
    return h;
}

} // namespace svo::validate
