#include "svo/validate/level_set_report.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace svo::validate {
namespace {

/// A number JSON can hold: NaN and infinities become null.
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json casesJson(const std::vector<LevelSetCase>& cases)
{
    nlohmann::json out = nlohmann::json::array();
    for (const auto& c : cases)
        out.push_back({{"voxel", c.index},
                       {"value", number(c.value)},
                       {"exact", c.exact},
                       {"side", c.side == 1 ? "inside" : c.side == 0 ? "outside" : "unknown"},
                       {"triangle", c.triangle}});
    return out;
}

} // namespace

LevelSetReport validateLevelSet(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<LevelSetVoxel>& voxels,
                                const LevelSetReportOptions& options)
{
    auto step = [&](const std::string& s) {
        if (options.onStep) options.onStep(s);
    };
    LevelSetReport r;
    r.exteriorBand = options.check.exteriorBand;
    r.interiorBand = options.check.interiorBand;
    r.sign = options.sign;
    const auto t0 = std::chrono::steady_clock::now();
    step(fmt::format("CGAL distances and sides for {} active voxels", voxels.size()));
    r.check = checkLevelSet(mesh, grid, voxels, options.check);
    if (options.openvdb) {
        step("OpenVDB meshToLevelSet on the same mesh and transform");
        r.openvdb = compareWithOpenVdb(mesh, grid, voxels, options.check);
        r.compared = true;
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    const LevelSetCheck& c = r.check;
    if (!(c.maxError <= c.tolerance))
        r.reason += fmt::format("{} distances off by more than {:.3g} voxels (up to {:.3g}); ", c.overTolerance,
                                c.tolerance, c.maxError);
    if (c.signDisagreements)
        r.reason += fmt::format("{} signs differ from CGAL's farther than {:.3g} voxels from the surface; ",
                                c.signDisagreements, c.tolerance);
    if (c.missing) r.reason += fmt::format("{} band voxels missing; ", c.missing);
    if (c.extra) r.reason += fmt::format("{} active voxels beyond the band; ", c.extra);
    if (!r.reason.empty()) r.reason.resize(r.reason.size() - 2);
    r.passed = r.reason.empty() && c.passed();
    return r;
}

std::string levelSetReportJson(const LevelSetReport& r)
{
    const LevelSetCheck& c = r.check;
    nlohmann::json j = {
        {"kind", "sdf"},
        {"exterior_band", r.exteriorBand},
        {"interior_band", r.interiorBand},
        {"sign", r.sign},
        {"tolerance", c.tolerance},
        {"voxels", c.voxels},
        {"candidates", c.candidates},
        {"max_error", number(c.maxError)},
        {"rms_error", number(c.rmsError)},
        {"over_tolerance", c.overTolerance},
        {"sign_checked", c.signChecked},
        {"sign_reason", c.signReason},
        {"sign_disagreements", c.signDisagreements},
        {"sign_near_surface", c.signNearSurface},
        {"missing", c.missing},
        {"extra", c.extra},
        {"band_unjudged", c.bandUnjudged},
        {"worst_error", casesJson(c.worstError)},
        {"worst_sign", casesJson(c.worstSign)},
        {"worst_missing", casesJson(c.worstMissing)},
        {"worst_extra", casesJson(c.worstExtra)},
        {"validation_seconds", r.seconds},
        {"passed", r.passed},
        {"reason", r.reason}};
    if (r.compared) {
        const OpenVdbComparison& o = r.openvdb;
        j["openvdb"] = {{"active", o.openvdb},
                        {"common", o.common},
                        {"only_svo", o.onlyOurs},
                        {"only_openvdb", o.onlyOpenVdb},
                        {"sign_disagreements", o.signDisagreements},
                        {"sign_judged", o.signJudged},
                        {"sign_svo_right", o.signOursRight},
                        {"sign_farthest", o.signFarthest},
                        {"max_difference", o.maxDifference},
                        {"max_error_svo", number(o.maxErrorOurs)},
                        {"max_error_openvdb", o.maxErrorOpenVdb},
                        {"svo_farther", o.oursFarther},
                        {"only_svo_exact", o.onlyOursExact},
                        {"only_openvdb_exact", o.onlyOpenVdbExact},
                        {"seconds", o.openvdbSeconds}};
    } else {
        j["openvdb"] = nullptr;
    }
    return j.dump(2);
}

} // namespace svo::validate
