#pragma once
/// @file triangle_voxels.h (internal)
/// The CPU reference's per-triangle loop, shared by the voxelizer and the
/// attribute reference.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "svo/core/grid.h"
#include "svo/core/overlap.h"
#include "svo/core/voxel_key.h"
#include "svo/core/voxel_mode.h"

namespace svo::detail {

/// The triangle's column rectangle along its projection axis w
/// (svo_projection_axis): rows along
/// u = (w + 1) % 3 and columns along v = (w + 2) % 3, clamped to the grid
/// (empty when hi < lo). The same bounds voxelizeTriangle walks.
struct ColumnBounds {
    int64_t u0, u1, v0, v1;
};
inline ColumnBounds columnBounds(const Vec3d& a, const Vec3d& b, const Vec3d& c, const GridSpec& grid, double guard)
{
    using namespace overlap_double;
    const double half = 0.5 + guard;
    const int w = svo_projection_axis(a, b, c, std::ldexp(1.0, -53));
    ColumnBounds r{};
    auto range = [&](int axis, int64_t& lo, int64_t& hi) {
        const double mn = std::min({a[axis], b[axis], c[axis]}), mx = std::max({a[axis], b[axis], c[axis]});
        lo = std::max<int64_t>(0, int64_t(std::ceil(mn - half)));
        hi = std::min<int64_t>(int64_t(grid.dims[axis]) - 1, int64_t(std::floor(mx + half)));
    };
    range((w + 1) % 3, r.u0, r.u1);
    range((w + 2) % 3, r.v0, r.v1);
    return r;
}

/// Calls emit(key) for every voxel whose cube, grown by `guard`, meets the
/// triangle (a, b, c) in local coordinates: along the projection axis, the
/// guarded column range of each column of the 2D bounds, then the overlap
/// test. Thin mode tests the voxel's centre segments instead (half length
/// 0.5 + guard, thickness max(guard, 0)); they lie inside the cube, so the
/// cube's candidates hold every voxel they can keep.
/// Rows (the first of the two column axes) outside [rowFirst, rowLast] are
/// skipped, so that one large triangle can be shared out in slabs of rows.
template <typename Emit>
inline void voxelizeTriangle(const Vec3d& a, const Vec3d& b, const Vec3d& c, const GridSpec& grid, double guard,
                             VoxelMode mode, Emit&& emit, int64_t rowFirst = 0, int64_t rowLast = INT64_MAX)
{
    using namespace overlap_double;
    const double half = 0.5 + guard;
    const bool thin = mode == VoxelMode::Thin;
    const double thickness = std::max(guard, 0.0);
    const double ulp = std::ldexp(1.0, -53);
    const int w = svo_projection_axis(a, b, c, ulp);
    const int u = (w + 1) % 3, v = (w + 2) % 3;
    auto range = [&](int axis, int64_t& lo, int64_t& hi) {
        const double mn = std::min({a[axis], b[axis], c[axis]}), mx = std::max({a[axis], b[axis], c[axis]});
        lo = std::max<int64_t>(0, int64_t(std::ceil(mn - half)));
        hi = std::min<int64_t>(int64_t(grid.dims[axis]) - 1, int64_t(std::floor(mx + half)));
    };
    int64_t u0, u1, v0, v1, w0, w1;
    range(u, u0, u1);
    u0 = std::max(u0, rowFirst);
    u1 = std::min(u1, rowLast);
    range(v, v0, v1);
    range(w, w0, w1);
    const svo_ColumnPlan plan = svo_column_plan(a, b, c, w, half, ulp); // once, not per column
    for (int64_t i = u0; i <= u1; ++i)
        for (int64_t j = v0; j <= v1; ++j) {
            const Vec3d r = svo_plan_range(plan, double(i), double(j));
            const int64_t k0 = std::max(w0, int64_t(std::ceil(r.x))), k1 = std::min(w1, int64_t(std::floor(r.y)));
            for (int64_t k = k0; k <= k1; ++k) {
                Vec3d centre;
                centre[u] = double(i);
                centre[v] = double(j);
                centre[w] = double(k);
                if (thin ? svo_triangle_thin_overlap(a, b, c, centre, half, thickness)
                         : svo_triangle_box_overlap(a, b, c, centre, half))
                    emit(packVoxelKey(uint32_t(centre.x), uint32_t(centre.y), uint32_t(centre.z)));
            }
        }
}


} // namespace svo::detail
