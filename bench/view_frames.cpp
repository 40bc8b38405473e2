// Frame time of the octree view, offscreen with nothing read back: GPU
// milliseconds per frame (GL timestamp queries) and wall milliseconds from
// issue to glFinish (the only meaningful figure on llvmpipe, which draws at
// the flush), for meshes voxelized at several resolutions, seen from the front.
//   svo-bench-view MESH... --res 256 512 1024 2048 --size 1920x1080 --frames 30 --md out.md
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/core/mesh_io.h"
#include "svo/gl/context.h"
#include "svo/gl/octree_view.h"
#include "svo/svo.h"

namespace {

double quantile(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, size_t(q * double(v.size())))];
}

} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"svo view benchmark: GPU frame time of the ray-marched octree"};
    std::vector<std::string> meshes;
    std::vector<int> resolutions{256, 512, 1024, 2048};
    int width = 1920, height = 1080, frames = 30;
    std::string mdPath, layers = "voxels";
    app.add_option("meshes", meshes, "Mesh files")->required();
    app.add_option("--res", resolutions, "Resolutions");
    app.add_option("--width", width, "Frame width")->check(CLI::PositiveNumber);
    app.add_option("--height", height, "Frame height")->check(CLI::PositiveNumber);
    app.add_option("--frames", frames, "Timed frames per point")->check(CLI::PositiveNumber);
    app.add_option("--layers", layers, "voxels, or voxels+outlines");
    app.add_option("--md", mdPath, "Markdown table to write");
    CLI11_PARSE(app, argc, argv);
    try {
        svo::Voxelizer voxelizer;
        svo::gl::Context context;
        svo::gl::ViewLayers l;
        l.outlines = layers == "voxels+outlines";
        std::string md = fmt::format("Octree view frame time at {} x {}, {} ({}), from the front, perspective; GPU "
                                     "ms per frame from timestamp queries and wall ms to glFinish, over {} "
                                     "frames.\n\n"
                                     "| mesh | grid | voxels | bricks | octree MB | upload ms | GPU ms median | GPU ms p90 | wall ms "
                                     "median | fps (wall) |\n"
                                     "|---|---|---|---|---|---|---|---|---|---|\n",
                                     width, height, context.info().renderer, layers, frames);
        for (const std::string& path : meshes) {
            const svo::TriangleMesh mesh = svo::loadMesh(path);
            for (int r : resolutions) {
                const svo::Octree octree = voxelizer.voxelize(mesh, svo::makeGrid(mesh, svo::GridRequest{r, 0}));
                // The one host-to-GPU copy of a build's octree the view makes.
                const auto t0 = std::chrono::steady_clock::now();
                svo::gl::OctreeView view(context, octree);
                const double uploadMs =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                const svo::gl::ViewCamera camera = svo::gl::frameBox(
                    svo::gl::gridWorldBox(octree.grid), svo::Vec3d{-0.35, -0.3, -1.0}, false, double(width) / height);
                std::vector<double> gpu, wall;
                for (const auto& t : view.timeFrames(camera, width, height, l, frames))
                    gpu.push_back(t.gpuMs), wall.push_back(t.wallMs);
                const double w = quantile(wall, 0.5);
                const std::string line = fmt::format(
                    "| {} | {}³ | {} | {} | {:.2f} | {:.1f} | {:.2f} | {:.2f} | {:.2f} | {:.0f} |\n",
                    std::filesystem::path(path).stem().string(), r, octree.voxelCount(), octree.bricks.size(),
                    double(octree.bytes()) / 1e6, uploadMs, quantile(gpu, 0.5), quantile(gpu, 0.9), w, w > 0 ? 1000.0 / w : 0.0);
                fmt::print("{}", line);
                std::fflush(stdout);
                md += line;
            }
        }
        if (!mdPath.empty()) svo::writeFileAtomically(mdPath, md);
    } catch (const std::exception& e) {
        fmt::print(stderr, "svo-bench-view: {}\n", e.what());
        return 1;
    }
    return 0;
}
