#pragma once
/// @file level_set_report.h
/// @brief One validation of a level set, start to end: what `svo validate --sdf`
/// and `svo.validate_level_set` print and return.
///
/// Method: checkLevelSet (level_set_check.h) holds the level set against
/// CGAL and gives the verdict; compareWithOpenVdb (level_set_peer.h), when
/// asked, runs OpenVDB's meshToLevelSet on the same mesh, transform and bands
/// and reports the differences, which do not change the verdict. The verdict
/// fails on a distance error above the tolerance, a sign disagreement with
/// CGAL farther than the tolerance from the surface (closed meshes), and a
/// missing or extra band voxel.
#include <functional>
#include <string>
#include <vector>

#include "svo/validate/level_set_check.h"
#include "svo/validate/level_set_peer.h"
#include "svo/validate/worst_cases.h"

namespace svo::validate {

/// @brief What validateLevelSet checks and how it reports progress.
struct LevelSetReportOptions {
    LevelSetCheckOptions check; ///< bands, tolerance, value unit, worst cases
    bool openvdb = true;  ///< also compare with OpenVDB's meshToLevelSet
    std::string sign;     ///< how the level set was signed (VoxelizeStats::sign), for the report
    /// Told the step now starting ("CGAL distances and sides", ...), for progress lines.
    std::function<void(const std::string& step)> onStep;
};

/// @brief The options of LevelSetReportOptions a caller chooses, each with
/// its names and doc, for every front end (svo/core/option_info.h). The
/// bands and the sign are the level set's own (LevelSetOptions, its run's
/// record), so they are not among them.
template <typename Visit>
void forEachOption(LevelSetReportOptions& o, Visit&& visit)
{
    visitWorst(o.check.worst, visit);
    visit(OptionInfo{"LevelSetReportOptions::openvdb", "openvdb", "Also compare with OpenVDB's meshToLevelSet"},
          o.openvdb);
}

/// @brief One level set's validation: the check, the comparison and the verdict.
struct LevelSetReport {
    LevelSetCheck check;       ///< against CGAL: the verdict's source
    bool compared = false; ///< `openvdb` holds a comparison
    OpenVdbComparison openvdb; ///< against OpenVDB's meshToLevelSet, when asked
    double exteriorBand = 0, interiorBand = 0; ///< voxels
    std::string sign;          ///< LevelSetReportOptions::sign
    double seconds = 0; ///< the check and the comparison
    bool passed = false;       ///< the verdict
    std::string reason; ///< why it failed, one line
};

/// @brief Checks a level set against CGAL and, when asked, compares it with
/// OpenVDB's (see the file comment).
/// @param mesh, grid as checkLevelSet
/// @param voxels the level set's active voxels (activeLevelSetVoxels)
/// @throw svo::InvalidInput as checkLevelSet
/// @throw svo::DeviceError as compareWithOpenVdb
LevelSetReport validateLevelSet(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<LevelSetVoxel>& voxels,
                                const LevelSetReportOptions& options = {});

/// @brief The report as JSON text (what `svo validate --sdf --json` holds of
/// it), so the CLI and Python give the same numbers.
std::string levelSetReportJson(const LevelSetReport& report);

} // namespace svo::validate
