#pragma once
/// @file level_set_peer.h
/// @brief A level set against OpenVDB's own meshToLevelSet on the same mesh,
/// transform and bands, with CGAL's exact distance as the judge where they
/// differ.
///
/// @details Method. openvdb::tools::meshToSignedDistanceField (what
/// meshToLevelSet calls, with separate exterior and interior bands) is run on
/// the mesh as float points in the grid's frame with the grid's transform
/// (voxel size and whole-voxel translation). Its active voxels are matched
/// with the given ones by index. On the common voxels the signs and the
/// distances are compared, and both distances are held against CGAL's exact
/// distance (AABB tree), so a difference can be put down to one side.
///
/// What to expect. OpenVDB computes exact float distances only next to the
/// surface and carries the closest triangle outward to fill the rest of the
/// band, so farther from the surface its distances can exceed the exact ones
/// by a fraction of a voxel and its band edge moves with them; it also
/// rounds the mesh to float. Neither is a defect of the level set under test:
/// this comparison informs, and checkLevelSet (level_set_check.h) judges.
///
/// OpenVDB headers stay in the implementation.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/validate/level_set_check.h"

namespace svo::validate {

/// @brief How a level set and OpenVDB's differ, and who is right where they do.
struct OpenVdbComparison {
    uint64_t ours = 0;        ///< active voxels given
    uint64_t openvdb = 0;     ///< OpenVDB's active voxels
    uint64_t common = 0;      ///< active in both
    uint64_t onlyOurs = 0;    ///< active only in the given level set
    uint64_t onlyOpenVdb = 0; ///< active only in OpenVDB's
    /// Common voxels whose signs differ, both values farther than the
    /// tolerance from zero.
    uint64_t signDisagreements = 0;
    /// Closed meshes: of those, the ones where CGAL's Side_of_triangle_mesh
    /// gives ours (the rest give OpenVDB's); `signJudged` false otherwise.
    bool signJudged = false;
    uint64_t signOursRight = 0; ///< sign disagreements where CGAL gives ours
    double signFarthest = 0; ///< the largest exact distance (voxels) of a sign disagreement
    double maxDifference = 0; ///< largest | |ours| - |OpenVDB's| | on common voxels, voxels
    double maxErrorOurs = 0;  ///< largest distance error against CGAL on common voxels, voxels
    double maxErrorOpenVdb = 0; ///< the same for OpenVDB's values
    /// Common voxels where ours is farther from CGAL's distance than
    /// OpenVDB's by more than the tolerance.
    uint64_t oursFarther = 0;
    /// The exact distance (voxels) of the voxels active in only one level
    /// set, least and largest; 0 when there are none. Near the band's width,
    /// they are band-edge differences.
    std::array<double, 2> onlyOursExact{}, onlyOpenVdbExact{};
    double openvdbSeconds = 0; ///< meshToSignedDistanceField's wall time
};

/// @brief Runs OpenVDB's meshToSignedDistanceField on the mesh and compares (see the file comment).
/// @param mesh, grid, voxels  as checkLevelSet; the bands, tolerance and
///        value unit come from @a options (OpenVDB is given the bands as floats)
/// @throw svo::InvalidInput for a band that is not positive and finite, or a
///        mesh that fails validateMesh
/// @throw svo::DeviceError for an exception from OpenVDB
OpenVdbComparison compareWithOpenVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                     const std::vector<LevelSetVoxel>& voxels, const LevelSetCheckOptions& options = {});

} // namespace svo::validate
