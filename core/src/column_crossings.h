#pragma once
// The crossings of a triangle with a lattice of z columns, at x = offset +
// spacing i and y = offset + spacing j (voxel columns: 0 and 1; brick centres:
// 3.5 and 8), by column_crossing.glsl's test and ties (internal to core; its
// includers are compiled without contraction, as that header asks).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "svo/core/column_crossing.h"

namespace svo {

/// Calls visit(i, j, zc, facingUp) for each column (i, j), from[0] <= i <
/// to[0] and from[1] <= j < to[1], that crosses triangle ABC at height zc;
/// facingUp: ABC is counter-clockwise seen from +z (the winding number falls
/// going up through it).
template <class Visit>
void forEachColumnCrossing(const Vec3d& A, const Vec3d& B, const Vec3d& C, double offset, double spacing,
                           const uint32_t (&from)[2], const uint32_t (&to)[2], Visit&& visit)
{
    uint32_t lo[2], hi[2];
    for (int a = 0; a < 2; ++a) { // clamped in double: a far corner's index fits no integer
        const double first = std::max(std::ceil((std::min({A[a], B[a], C[a]}) - offset) / spacing), double(from[a]));
        const double last = std::min(std::floor((std::max({A[a], B[a], C[a]}) - offset) / spacing), double(to[a]) - 1);
        if (!(first <= last)) return;
        lo[a] = uint32_t(first), hi[a] = uint32_t(last);
    }
    for (uint32_t j = lo[1]; j <= hi[1]; ++j)
        for (uint32_t i = lo[0]; i <= hi[0]; ++i) {
            const double qx = offset + spacing * double(i), qy = offset + spacing * double(j);
            double zc = 0;
            if (!column_crossing::svo_column_crossing(A, B, C, qx, qy, zc)) continue;
            // Left of every edge in projection: counter-clockwise.
            visit(i, j, zc, column_crossing::svo_edge_side(B, C, qx, qy) > 0);
        }
}

/// The same for the columns i < count[0], j < count[1].
template <class Visit>
void forEachColumnCrossing(const Vec3d& A, const Vec3d& B, const Vec3d& C, double offset, double spacing,
                           const uint32_t (&count)[2], Visit&& visit)
{
    const uint32_t from[2] = {0, 0};
    forEachColumnCrossing(A, B, C, offset, spacing, from, count, visit);
}

} // namespace svo
