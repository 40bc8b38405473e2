#include "svo/validate/report.h"

#include <chrono>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "svo/validate/exact_reference.h"

namespace svo::validate {
namespace {

/// Structure, then every level against the octree the run's voxel list implies.
std::string octreeConsistency(const Octree& octree, const std::vector<uint64_t>& listKeys)
{
    const auto problems = checkOctree(octree, 1);
    if (!problems.empty()) return "structure: " + problems.front();
    if (!sameOctree(canonicalOrder(octree), buildOctree(octree.grid, listKeys)))
        return "the octree's levels differ from those the voxel list implies";
    return "";
}

std::string indexText(const std::array<int64_t, 3>& p) { return fmt::format("[{}, {}, {}]", p[0], p[1], p[2]); }

nlohmann::json casesJson(const std::vector<VoxelCase>& cases)
{
    nlohmann::json out = nlohmann::json::array();
    for (const auto& c : cases) out.push_back({{"voxel", c.index}, {"triangle", c.triangle}, {"distance", c.distance}});
    return out;
}

} // namespace

Report validateVoxelization(const TriangleMesh& mesh, const Octree& octree, const std::vector<uint64_t>& voxelList,
                            const ReportOptions& options)
{
    auto step = [&](const std::string& s) {
        if (options.onStep) options.onStep(s);
    };
    Report r;
    const GridSpec& grid = octree.grid;
    step("checking the octree against the voxel list");
    r.consistency = octreeConsistency(octree, voxelList);
    const std::vector<uint64_t> voxels = octreeKeys(octree);

    const auto t0 = std::chrono::steady_clock::now();
    r.epsilon = grid.epsilon();
    step(fmt::format("exact CGAL reference for {} triangles", mesh.triangles.size()));
    r.mode = options.mode;
    const ReferenceSets ref = exactReference(mesh, grid, r.epsilon, options.mode);
    r.degenerate = ref.degenerate;
    step("classifying the voxels");
    r.classification = classify(mesh, grid, voxels, ref, options.worst);
    if (options.holes) {
        step("flood-filling the empty voxels");
        r.holes = checkHoles(mesh, grid, voxels, separatingConnectivity(options.mode));
    } else {
        r.holes.reason = "skipped";
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    const Classification& c = r.classification;
    // R ⊆ E, so a voxel missed against R is missed against E too; both are named.
    if (!c.missedExact.empty())
        r.reason += c.missed.empty()
                        ? fmt::format("{} voxels of the exact {} set missed (all within the guard band); ",
                                      c.missedExact.size(), voxelModeName(options.mode))
                        : fmt::format("{} voxels missed ({} of the exact {} set); ", c.missed.size(),
                                      c.missedExact.size(), voxelModeName(options.mode));
    if (r.holes.leak) r.reason += fmt::format("the flood fill leaks inside through {}; ", indexText(r.holes.leakPath.front()));
    if (!r.consistency.empty()) r.reason += "octree inconsistent; ";
    if (options.strict && !c.extra.empty()) r.reason += fmt::format("{} extra voxels (strict); ", c.extra.size());
    if (!r.reason.empty()) r.reason.resize(r.reason.size() - 2);
    r.passed = r.reason.empty();
    return r;
}

std::string reportJson(const Report& r)
{
    const Classification& c = r.classification;
    const nlohmann::json j = {
        {"mode", voxelModeName(r.mode)},
        {"degenerate", r.degenerate},
        {"epsilon", r.epsilon},
        {"voxels", c.voxels},
        {"required", c.required},
        {"exact", c.exact},
        {"allowed", c.allowed},
        {"missed", c.missed.size()},
        {"missed_exact", c.missedExact.size()},
        {"boundary", c.boundary.size()},
        {"extra", c.extra.size()},
        {"worst_missed", casesJson(c.worstMissed)},
        {"worst_extra", casesJson(c.worstExtra)},
        {"holes",
         {{"applies", r.holes.applies},
          {"reason", r.holes.reason},
          {"connectivity", r.holes.connectivity},
          {"leak", r.holes.leak},
          {"filled", r.holes.filled},
          {"frontier", r.holes.frontier},
          {"path", r.holes.leakPath}}},
        {"octree_consistent", r.consistency.empty()},
        {"validation_seconds", r.seconds},
        {"passed", r.passed},
        {"reason", r.reason}};
    return j.dump(2);
}

} // namespace svo::validate
