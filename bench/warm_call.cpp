// Warm-call latency through the public API: one svo::Voxelizer reused for N
// calls on one mesh, each call split into mapping + upload, GPU work, and leaf
// building, medians after the first (cold) call.
//   svo-bench-warm-call MESH --res 256 1024 --calls 100 --json out.json --md out.md
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "svo/core/atomic_file.h"
#include "svo/svo.h"

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

double stageWall(const svo::VoxelizeStats& s, const std::string& name)
{
    for (const auto& st : s.stages)
        if (st.name == name) return st.wallMs;
    return 0.0;
}

} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"svo warm-call benchmark: a Voxelizer reused for many calls"};
    std::string meshPath, jsonPath, mdPath, machine = "this machine";
    std::vector<int> resolutions{256, 1024};
    int calls = 100;
    app.add_option("mesh", meshPath, "Mesh file")->required();
    app.add_option("--res", resolutions, "Voxels along the longest side")->capture_default_str();
    app.add_option("--calls", calls, "Calls per resolution (the first is the cold one)")->capture_default_str();
    app.add_option("--json", jsonPath, "Write the results as JSON");
    app.add_option("--md", mdPath, "Write the results as a markdown table");
    app.add_option("--machine", machine, "Machine name for the table");
    CLI11_PARSE(app, argc, argv);
    try {
        openvdb::initialize();
        const svo::TriangleMesh mesh = svo::loadMesh(meshPath);
        std::vector<openvdb::Vec3s> points; // what a pipeline hands over: float points
        for (const auto& p : mesh.positions) points.emplace_back(float(p.x), float(p.y), float(p.z));
        std::vector<openvdb::Vec3I> triangles;
        for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
        const svo::Bounds b = mesh.bounds();
        const double longest = std::max({b.extent().x, b.extent().y, b.extent().z});

        const auto coldStart = Clock::now();
        svo::Voxelizer voxelizer;
        const std::string device = voxelizer.deviceDescription();
        const double contextMs = msSince(coldStart);

        nlohmann::json results = nlohmann::json::array();
        std::string table = fmt::format(
            "| resolution | voxels | cold call ms | warm call ms | mapping ms | upload ms | GPU ms | GPU stages wall ms | "
            "leaf building ms | voxelize outside its stages ms | warm - GPU ms | warm - GPU stages wall ms |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (int res : resolutions) {
            const auto xform = openvdb::math::Transform::createLinearTransform(longest / res);
            std::vector<double> total, mapping, upload, gpu, gpuWall, leaves, outside;
            double cold = 0;
            uint64_t voxels = 0;
            for (int i = 0; i < calls; ++i) {
                svo::VoxelizeStats stats;
                svo::VoxelizeOptions options;
                options.stats = &stats;
                const auto t0 = Clock::now();
                // meshToMask, step by step: the same calls it makes.
                const svo::IndexSpaceMesh m = svo::prepareMesh(points, triangles, {}, *xform);
                const double mapMs = msSince(t0);
                const auto tv = Clock::now();
                const svo::Octree octree = voxelizer.voxelize(m.mesh, m.grid, options);
                const double voxelizeMs = msSince(tv);
                const auto t1 = Clock::now();
                svo::GridOptions g;
                g.attributes = false;
                const auto grid = svo::octreeToGrids(octree, g, xform->copy()).front();
                const double leafMs = msSince(t1);
                const double wall = msSince(t0);
                voxels = grid->activeVoxelCount();
                if (i == 0) {
                    cold = wall + (res == resolutions.front() ? contextMs : 0.0);
                    continue;
                }
                double stagesWall = 0;
                for (const auto& s : stats.stages) stagesWall += s.wallMs;
                total.push_back(wall);
                mapping.push_back(mapMs);
                upload.push_back(stageWall(stats, "upload"));
                gpu.push_back(stats.gpuMs());
                gpuWall.push_back(stagesWall - stageWall(stats, "upload"));
                leaves.push_back(leafMs);
                outside.push_back(voxelizeMs - stagesWall); // making the context current and back, checks
            }
            const double warm = median(total), g = median(gpu);
            results.push_back({{"resolution", res},
                               {"voxels", voxels},
                               {"calls", calls},
                               {"cold_call_ms", cold},
                               {"warm_call_ms", warm},
                               {"mapping_ms", median(mapping)},
                               {"upload_ms", median(upload)},
                               {"gpu_ms", g},
                               {"gpu_stages_wall_ms", median(gpuWall)},
                               {"leaf_building_ms", median(leaves)},
                               {"voxelize_outside_stages_ms", median(outside)},
                               {"warm_minus_gpu_ms", warm - g},
                               {"warm_minus_gpu_stages_wall_ms", warm - median(gpuWall)}});
            table += fmt::format(
                "| {}³ | {} | {:.1f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n",
                res, voxels, cold, warm, median(mapping), median(upload), g, median(gpuWall), median(leaves),
                median(outside), warm - g, warm - median(gpuWall));
            fmt::print(stderr, "{}³ done\n", res);
        }
        const std::string header = fmt::format(
            "Warm-call latency on {}: `{}` ({} triangles), one Voxelizer reused for {} calls per resolution; "
            "medians of calls 2..{} (call 1 is the cold one, with EGL set-up and shader compilation: {:.0f} ms "
            "before the first resolution). Device: {}.\n\n",
            machine, meshPath.substr(meshPath.find_last_of('/') + 1), triangles.size(), calls, calls, contextMs,
            device);
        fmt::print("{}{}", header, table);
        if (!jsonPath.empty())
            svo::writeFileAtomically(jsonPath, nlohmann::json({{"machine", machine},
                                                               {"mesh", meshPath},
                                                               {"triangles", triangles.size()},
                                                               {"device", device},
                                                               {"context_ms", contextMs},
                                                               {"results", results}})
                                                       .dump(2) +
                                                   "\n");
        if (!mdPath.empty()) svo::writeFileAtomically(mdPath, "# Warm-call latency\n\n" + header + table);
    } catch (const std::exception& e) {
        fmt::print(stderr, "svo-bench-warm-call: {}\n", e.what());
        return 1;
    }
    return 0;
}
