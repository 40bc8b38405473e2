// svo-mesh-to-volume MESH -r N: the benchmark's library peer. OpenVDB's own
// mesh-to-volume on the same mesh and the same grid as `svo voxelize -r N`:
// an unsigned distance field with a one-voxel band, whose voxels within half a
// voxel diagonal of the surface are its surface voxels. Prints one JSON line.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <sys/resource.h>

#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/vdb_io/grid_builder.h"

int main(int argc, char** argv)
{
    CLI::App app{"OpenVDB meshToVolume on svo's grid, for benchmarks"};
    std::string path;
    int64_t resolution = 256;
    app.add_option("mesh", path, fmt::format("Mesh file ({})", svo::supportedMeshExtensions()))->required();
    app.add_option("-r,--resolution", resolution, "Voxels along the longest bounding-box side")->capture_default_str();
    float levelSet = 0;
    app.add_option("--level-set", levelSet, "Time meshToLevelSet with this half width (voxels) instead");
    CLI11_PARSE(app, argc, argv);
    try {
        openvdb::initialize();
        const svo::TriangleMesh mesh = svo::loadMesh(path);
        const svo::GridSpec grid = svo::makeGrid(mesh, {resolution, 0});
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<openvdb::Vec3s> points;
        std::vector<openvdb::Vec3I> triangles;
        points.reserve(mesh.positions.size());
        for (const auto& p : mesh.positions) points.emplace_back(float(p.x), float(p.y), float(p.z));
        for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
        const auto xform = svo::vdb::makeTransform(grid);
        if (levelSet > 0) {
            auto ls = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, triangles, levelSet);
            const double lsMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            fmt::print("{{\"peer\": \"openvdb meshToLevelSet\", \"half_width\": {}, \"ms\": {:.3f}, "
                       "\"active_voxels\": {}}}\n",
                       levelSet, lsMs, ls->activeVoxelCount());
            return 0;
        }
        auto udf = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(
            *xform, points, triangles, std::vector<openvdb::Vec4I>{}, 1.0f);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        // Distances are in world units; surface voxels lie within half a diagonal.
        const float limit = float(0.5 * std::sqrt(3.0) * grid.voxelSize);
        uint64_t surface = 0;
        for (auto it = udf->cbeginValueOn(); it; ++it) surface += *it <= limit;
        rusage ru{};
        getrusage(RUSAGE_SELF, &ru);
        fmt::print("{{\"peer\": \"openvdb meshToUnsignedDistanceField\", \"ms\": {:.3f}, \"band_voxels\": {}, "
                   "\"surface_voxels\": {}, \"peak_rss_mb\": {:.1f}}}\n",
                   ms, udf->activeVoxelCount(), surface, double(ru.ru_maxrss) / 1024.0);
    } catch (const svo::Error& e) {
        fmt::print(stderr, "svo-mesh-to-volume: error: {}\n", e.what());
        return 1;
    }
    return 0;
}
