// The mesh in a grid's local frame (svo/core/local_positions.h).
#include "svo/core/local_positions.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace svo {

std::vector<Vec3d> localPositions(const TriangleMesh& mesh, const GridSpec& grid)
{
    std::vector<Vec3d> local(mesh.positions.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, local.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) local[i] = grid.toLocal(mesh.positions[i]);
    });
    return local;
}

} // namespace svo
