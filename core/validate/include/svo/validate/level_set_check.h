#pragma once
/// @file level_set_check.h
/// @brief A narrow-band level set (svo's, or anyone's) held against CGAL:
/// exact distances, exact sides, and the exact band.
///
/// @details Method. The mesh goes to the grid's double local coordinates (the
/// frame the GPU starts from). For every active voxel, the distance from its
/// centre to the closest triangle comes from CGAL's AABB tree
/// (`squared_distance` of Epick, correct to ~1e-15 relative), and, when the
/// mesh is closed, its side from CGAL's `Side_of_triangle_mesh`. The band is
/// checked both ways: every active voxel must lie within the band on its
/// side, and every voxel centre that does must be active. The voxels whose
/// centres can lie within the band are found brick by brick: a box of 8^3
/// centres is skipped when the distance from its middle, less its half
/// diagonal, exceeds the wider band (the triangle inequality), so the work
/// follows the surface. Queries run in parallel (TBB).
///
/// Terms, with d the exact distance in voxels, W the band on the voxel's side
/// (interior when inside, exterior otherwise) and tau the tolerance:
/// - distance error: | |value| / voxel size - d |, over the active voxels;
/// - sign disagreement: the value's sign (negative = inside) is not CGAL's
///   side; counted as a failure only where d > tau (a centre closer to the
///   surface than the allowed distance error may take either side), and
///   apart, as `signNearSurface`, where d <= tau;
/// - missing: not active though d < W - tau; extra: active though d > W + tau.
///   Centres within tau of the band's edge may be either, since a distance
///   that is right to within tau may fall on either side of W.
///
/// Sides come from CGAL only on closed meshes (closed_surface: as given, or
/// after welding coincident vertices and dropping degenerate faces). On other
/// meshes no sign is checked (`signChecked` false, `signReason` says why),
/// an active voxel's band is the one on the side its value gives, and an
/// inactive voxel whose d lies between the two bands cannot be judged
/// (`bandUnjudged`); with equal bands there are none.
///
/// Guarantees: every count is exact for the given tolerance (up to CGAL's
/// double rounding of d, ~1e-15 voxel at the grid sizes svo allows); a
/// defect is never hidden (a voxel listed twice or a non-finite value is an
/// error or a distance error of infinity, never skipped).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "svo/core/error.h"
#include "svo/core/grid.h"
#include "svo/core/mesh.h"

namespace svo::validate {

/// @brief One active voxel of a level set: its OpenVDB index coordinate and
/// its value (world units unless LevelSetCheckOptions::voxelSize says
/// otherwise; negative inside).
struct LevelSetVoxel {
    std::array<int32_t, 3> index{}; ///< OpenVDB index coordinate
    float value = 0;                ///< signed distance, negative inside
};

/// @brief The bands, tolerance and value unit checkLevelSet works with.
struct LevelSetCheckOptions {
    double exteriorBand = 3.0; ///< band outside the surface, in voxels (> 0)
    double interiorBand = 3.0; ///< band inside, in voxels (> 0)
    /// tau, in voxels: the distance error allowed, the sign margin and the
    /// band-edge slack (see the file comment). 1e-4 is 100 times svo's own
    /// float rounding in a band of 8 voxels, and stays above the rounding of
    /// a float value up to ~800 voxels from the surface.
    double tolerance = 1e-4;
    /// World units per voxel of the values; 0 means grid.voxelSize. (A grid of
    /// a caller's transform has voxel size 1 while the values are in world units.)
    double voxelSize = 0;
    size_t worst = 5; ///< worst cases kept of each kind
};

/// @brief A voxel worth a look.
struct LevelSetCase {
    std::array<int64_t, 3> index{}; ///< OpenVDB index coordinate
    double value = 0;               ///< the level set's, voxels; NaN where it has no active voxel
    double exact = 0;               ///< CGAL's distance, voxels; negative inside when the side is known
    int side = -1;                  ///< 1 inside, 0 outside, -1 unknown
    int64_t triangle = -1; ///< the closest triangle
};

/// @brief What checkLevelSet found, and its verdict (passed()).
struct LevelSetCheck {
    uint64_t voxels = 0;     ///< active voxels checked
    uint64_t candidates = 0; ///< inactive voxels whose distance was computed to look for missing ones
    double maxError = 0;     ///< largest distance error, voxels
    double rmsError = 0;     ///< root mean square distance error, voxels
    uint64_t overTolerance = 0; ///< active voxels whose distance error exceeds tau
    double tolerance = 0;    ///< tau used, voxels
    bool signChecked = false;       ///< the mesh is closed, so sides were checked
    std::string signReason;         ///< why signs were not checked (open mesh, ...)
    uint64_t signDisagreements = 0; ///< wrong side, farther than tau from the surface
    uint64_t signNearSurface = 0;   ///< wrong side, within tau of the surface: allowed
    uint64_t missing = 0;           ///< in the band by exact distance, not active
    uint64_t extra = 0;             ///< active, beyond the band by exact distance
    uint64_t bandUnjudged = 0;      ///< open meshes with unequal bands: side unknown, not judged
    std::vector<LevelSetCase> worstError;  ///< largest distance errors first
    std::vector<LevelSetCase> worstSign;   ///< sign disagreements beyond tau, farthest from the surface first
    std::vector<LevelSetCase> worstMissing; ///< missing, deepest in the band first
    std::vector<LevelSetCase> worstExtra;   ///< extra, farthest beyond the band first
    /// @brief Whether the level set meets every criterion: max error <= tau,
    /// no sign disagreement beyond tau (when checked), nothing missing or extra.
    bool passed() const
    {
        return maxError <= tolerance && signDisagreements == 0 && missing == 0 && extra == 0;
    }
};

/// @brief Checks a level set's active voxels against CGAL (see the file comment).
/// @param mesh   the mesh the level set was made from (world units, as `grid` maps them)
/// @param grid   the grid whose index space the voxels' coordinates are in
///               (makeGrid's, or prepareMesh's for a caller's transform)
/// @param voxels every active voxel, each once, in any order
/// @param options bands, tolerance, value unit, worst cases kept
/// @return the counts, worst cases and verdict
/// @throw svo::InvalidInput for a band that is not positive and finite, a
///        negative or non-finite tolerance, a voxel size that is not positive,
///        a voxel listed twice, or a mesh that fails validateMesh
LevelSetCheck checkLevelSet(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<LevelSetVoxel>& voxels,
                            const LevelSetCheckOptions& options = {});

/// @brief The active voxels of an OpenVDB FloatGrid (any type with OpenVDB's
/// grid interface), without including OpenVDB here.
/// @throw svo::InvalidInput for an active tile: a level set has active voxels only.
template <typename FloatGridT>
std::vector<LevelSetVoxel> activeLevelSetVoxels(const FloatGridT& grid)
{
    std::vector<LevelSetVoxel> out;
    out.reserve(size_t(grid.activeVoxelCount()));
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue())
            throw InvalidInput("grid '" + grid.getName() + "' has an active tile; a level set's band is active voxels only");
        const auto c = it.getCoord();
        out.push_back({{c.x(), c.y(), c.z()}, float(*it)});
    }
    return out;
}

} // namespace svo::validate
