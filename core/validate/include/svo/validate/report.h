#pragma once
/// @file report.h
/// @brief One validation of a voxelization, start to end: what `svo validate` and
/// `svo.validate` print and return.
///
/// Method: the octree is checked for structure and against the voxel list of
/// the same run (every level must be what the list's voxels imply); the exact
/// reference (exact_reference.h) gives R and A; the octree's voxels are
/// classified (classify.h); closed meshes get the flood-fill hole check
/// (hole_check.h), 26-connected for conservative and 6-connected for thin.
/// The verdict fails on voxels missed against the guarded set R or against
/// the exact set E of the mode, a leak, an inconsistent octree, and (strict)
/// extra voxels.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_mode.h"
#include "svo/validate/classify.h"
#include "svo/validate/hole_check.h"
#include "svo/validate/worst_cases.h"

namespace svo::validate {

/// @brief What validateVoxelization checks and how it reports progress.
struct ReportOptions {
    /// The voxelization under test: conservative (cubes, 26-connected hole
    /// fill) or thin (centre segments, 6-connected fill).
    VoxelMode mode = VoxelMode::Conservative;
    bool holes = true;   ///< run the hole check (closed meshes)
    bool strict = false; ///< extra voxels fail too
    size_t worst = 5;    ///< worst cases kept of each kind
    /// Told the step now starting ("exact CGAL reference", ...), for progress lines.
    std::function<void(const std::string& step)> onStep;
};

/// @brief The options of ReportOptions a caller chooses, each with its
/// names and doc, for every front end (svo/core/option_info.h). `mode` is the
/// voxelization's own (VoxelizeOptions::mode), so it is not one of them.
template <typename Visit>
void forEachOption(ReportOptions& o, Visit&& visit)
{
    visit(OptionInfo{"ReportOptions::holes", "holes", "Run the flood-fill hole check (closed meshes)", "--no-holes"},
          o.holes);
    visit(OptionInfo{"ReportOptions::strict", "strict", "Fail on extra voxels too"}, o.strict);
    visitWorst(o.worst, visit);
}

/// @brief One voxelization's validation: the sets, the hole check, the octree's
/// consistency, and the verdict.
struct Report {
    VoxelMode mode = VoxelMode::Conservative; ///< the mode the sets and the hole check used
    double epsilon = 0;            ///< the guard band R and A use, in voxels
    uint64_t degenerate = 0;       ///< triangles routed to segment or point tests
    Classification classification; ///< the octree's voxels against R, E and A
    HoleCheck holes;               ///< the flood fill (closed meshes, when asked)
    std::string consistency;       ///< empty when the octree agrees with the voxel list
    double seconds = 0;            ///< reference, classification and hole check
    bool passed = false;           ///< the verdict
    std::string reason;            ///< why it failed, one line
};

/// @brief Validates a voxelization of @a mesh (see the file comment).
/// @param octree    the voxelization under test, on its own grid
/// @param voxelList the run's own voxel list (sorted, unique keys), from
///        Voxelizer::voxelize(..., voxelList), to check the octree against.
/// @return the sets, hole check, consistency and verdict
/// @throw svo::OutOfMemory when the hole check's grid does not fit host memory
Report validateVoxelization(const TriangleMesh& mesh, const Octree& octree, const std::vector<uint64_t>& voxelList,
                            const ReportOptions& options = {});

/// @brief The report as JSON text (the fields of `svo validate --json` that
/// the report holds), so the CLI and Python give the same numbers.
std::string reportJson(const Report& report);

} // namespace svo::validate
