#include "svo/validate/classify.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "local_points.h"
#include "triangle_distances.h"
#include "svo/core/voxel_key.h"

namespace svo::validate {
namespace {

using K = detail::K;

/// Nearest-triangle distances for a few voxels.
class Distances {
public:
    Distances(const TriangleMesh& mesh, const GridSpec& grid) : d_(mesh, detail::localPoints(mesh, grid)) {}

    VoxelCase at(const GridSpec& grid, uint64_t key) const
    {
        const auto l = unpackVoxelKey(key);
        const auto n = d_.nearest(K::Point_3(l[0], l[1], l[2]));
        VoxelCase v;
        v.index = grid.toGlobal(l);
        v.triangle = n.triangle;
        v.distance = std::sqrt(n.squared);
        return v;
    }

private:
    detail::TriangleDistances d_;
};

std::vector<VoxelCase> worstOf(const std::vector<uint64_t>& keys, const Distances& d, const GridSpec& grid,
                               size_t worst, bool nearestFirst)
{
    // Distances for a bounded sample: every key when few, else an even stride.
    const size_t limit = 20000;
    const size_t stride = std::max<size_t>(1, keys.size() / limit);
    std::vector<VoxelCase> cases;
    for (size_t i = 0; i < keys.size(); i += stride) cases.push_back(d.at(grid, keys[i]));
    std::sort(cases.begin(), cases.end(), [&](const auto& a, const auto& b) {
        return nearestFirst ? a.distance < b.distance : a.distance > b.distance;
    });
    if (cases.size() > worst) cases.resize(worst);
    return cases;
}

} // namespace

Classification classify(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<uint64_t>& gpu,
                        const ReferenceSets& ref, size_t worst)
{
    Classification c;
    c.voxels = gpu.size();
    c.required = ref.required.size();
    c.exact = ref.exact.size();
    c.allowed = ref.allowed.size();
    std::set_difference(ref.required.begin(), ref.required.end(), gpu.begin(), gpu.end(), std::back_inserter(c.missed));
    std::set_difference(ref.exact.begin(), ref.exact.end(), gpu.begin(), gpu.end(), std::back_inserter(c.missedExact));
    std::set_difference(gpu.begin(), gpu.end(), ref.allowed.begin(), ref.allowed.end(), std::back_inserter(c.extra));
    std::vector<uint64_t> inA;
    std::set_intersection(gpu.begin(), gpu.end(), ref.allowed.begin(), ref.allowed.end(), std::back_inserter(inA));
    std::set_difference(inA.begin(), inA.end(), ref.required.begin(), ref.required.end(), std::back_inserter(c.boundary));
    if (!c.missedExact.empty() || !c.extra.empty()) {
        const Distances d(mesh, grid);
        c.worstMissed = worstOf(c.missedExact, d, grid, worst, true);
        c.worstExtra = worstOf(c.extra, d, grid, worst, false);
    }
    return c;
}

} // namespace svo::validate
