// Error against time of the octree view's cone tracing: for each scene,
// resolution, cone count (and for AO the opacity source: the volume, or the
// octree with either filter), the picture is compared
// pixel by pixel with the path-traced reference of the same triangles, camera
// and lights (svo/reference/path_trace.h), and the frame is timed at the
// benchmark size.
//   --render ao: the AO image (AmbientOcclusion::only) against reference AO
//     with the same distance;
//   --render direct / gi: the lit voxels (Illumination, linear radiance)
//     against the reference's Direct / OneBounce radiance with the same
//     lights (defaultLights: a point light in the Cornell box, else a sun)
//     and albedo; frames are timed as they are, and again injecting the light
//     and mip-mapping each frame, as after a light moves.
//   svo-bench-ao cornell spheres MESH... --res 64 128 256 512 --cones 1 3 7 16 --md out.md [--render gi]
// Scenes: "cornell", "spheres" and "two_rooms" (the thin-wall leak scene,
// seen from inside its dark room, where the reference is black) are built
// in; anything else is a mesh file.
// The AO distance is a fraction of the scene's bounding-box diagonal, the
// same in world units at every resolution; the camera frames the mesh's box
// from the front, so every resolution is compared on the same pixels.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/core/default_scene.h"
#include "svo/core/mesh_io.h"
#include "svo/gl/context.h"
#include "svo/gl/octree_view.h"
#include "svo/reference/path_trace.h"
#include "svo/svo.h"

namespace {

double quantile(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, size_t(q * double(v.size())))];
}

svo::TriangleMesh scene(const std::string& name)
{
    if (name == "cornell") return svo::cornellBox();
    if (name == "spheres") return svo::sphereGrid();
    if (name == "two_rooms") return svo::twoRooms();
    return svo::loadMesh(name);
}

} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"svo AO benchmark: cone-traced ambient occlusion against a path-traced reference"};
    std::vector<std::string> scenes;
    std::vector<int> resolutions{64, 128, 256, 512}, coneCounts{1, 3, 5, 7, 16};
    int width = 320, height = 240, samples = 256, timeWidth = 1920, timeHeight = 1080, frames = 10;
    double distanceShare = 0.25;
    std::string mdPath, dumpDir, render = "ao";
    app.add_option("scenes", scenes, "cornell, spheres or mesh files")->required();
    app.add_option("--res", resolutions, "Resolutions");
    app.add_option("--cones", coneCounts, "Cone counts");
    app.add_option("--width", width, "Compared image width")->check(CLI::PositiveNumber);
    app.add_option("--height", height, "Compared image height")->check(CLI::PositiveNumber);
    app.add_option("--samples", samples, "Reference AO rays per pixel")->check(CLI::PositiveNumber);
    app.add_option("--distance", distanceShare, "AO distance, share of the bounding-box diagonal");
    app.add_option("--time-size", timeWidth, "Timed frame width (height 9/16 of it)")->check(CLI::PositiveNumber);
    app.add_option("--frames", frames, "Timed frames per point")->check(CLI::PositiveNumber);
    app.add_option("--md", mdPath, "Markdown table to write");
    app.add_option("--dump", dumpDir, "Write the reference and each image here as PGM (the compared pixels; 0 elsewhere)");
    app.add_option("--render", render, "ao, direct or gi")->check(CLI::IsMember({"ao", "direct", "gi"}));
    double offset = -1, step = 0.5, aperture = -1;
    app.add_option("--aperture", aperture, "Cone aperture, full angle in degrees (default: the option's)");
    app.add_option("--step", step, "Cone steps, share of the cone's width (svo's default 0.5)");
    app.add_option("--offset", offset, "Cones start this far out of the surface, voxels (default: the option's)");
    std::string aoSource = "volume";
    app.add_option("--ao-source", aoSource, "ao: opacity from the volume, the octree (both filters), or both")
        ->check(CLI::IsMember({"volume", "octree", "both"}));
    bool directional = false;
    app.add_flag("--directional", directional, "gi: emission by direction (Illumination::directional)");
    bool clearance = false;
    app.add_flag("--clearance", clearance, "gi: coarse levels only clear of voxels (Illumination::clearance)");
    std::string conePattern = "interleaved";
    app.add_option("--cone-pattern", conePattern,
                   "interleaved (each pixel of a 4x4 tile its own cones, averaged) or fixed (every pixel the same)")
        ->check(CLI::IsMember({"interleaved", "fixed"}));
    std::string surface = "mesh"; // as svo view --render ao|gi shades a mesh input
    app.add_option("--surface", surface, "Shade the mesh's triangles (svo view's default for a mesh) or the voxels camera "
                                         "rays hit (ViewLayers::surface)")
        ->check(CLI::IsMember({"voxels", "mesh"}));
    CLI11_PARSE(app, argc, argv);
    timeHeight = timeWidth * 9 / 16;
    try {
        svo::Voxelizer voxelizer;
        svo::gl::Context context;
        const bool ao = render == "ao";
        const double albedo = 0.75;
        std::string md =
            ao ? fmt::format(
                     "Cone-traced AO (svo view --render ao) against path-traced AO ({} rays per pixel, Embree), {} x "
                     "{} pixels compared where both see a surface; AO distance {} of the scene's diagonal; GPU ms per "
                     "frame at {} x {} on {}.\n\n",
                     samples, width, height, distanceShare, timeWidth, timeHeight, context.info().renderer) +
                     fmt::format("Shading the {} (ViewLayers::surface); cones {}.\n\n", surface, conePattern)
               : fmt::format("Cone-traced {} light (svo view --render {}) against the path-traced reference's {} "
                             "({} paths per pixel, Embree), linear radiance (albedo {}, svo's default lights), {} x {} "
                             "pixels compared where both see a surface, values clamped to [0, 1]; GPU ms per frame at "
                             "{} x {} on {}, and with the light injected and the volume mip-mapped again in each "
                             "frame (light moved); emission {}; shading the {}; cones {}{}.\n\n",
                             render == "gi" ? "one-bounce" : "direct", render,
                             render == "gi" ? "OneBounce" : "Direct", samples, albedo, width, height, timeWidth,
                             timeHeight, context.info().renderer, directional ? "by direction" : "isotropic", surface,
                             conePattern, clearance ? ", reading coarse texels only clear of voxels" : "");
        md += fmt::format("| scene | grid | opacity | cones | RMSE | p99 error | mean {} (svo) | mean {} (reference) | "
                          "pixels | GPU ms | GPU ms, light moved | wall ms |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                          ao ? "AO" : "radiance", ao ? "AO" : "radiance");
        for (const std::string& name : scenes) {
            const svo::TriangleMesh mesh = scene(name);
            const svo::Bounds b = mesh.bounds();
            const double diagonal = std::sqrt(svo::dot(b.extent(), b.extent()));
            const double distance = distanceShare * diagonal;
            // The two rooms are seen from inside the dark one, looking at the wall
            // with the light behind it; other scenes from the front.
            const bool rooms = name == "two_rooms";
            svo::gl::ViewCamera camera = svo::gl::namedView({b.min, b.max}, "front", double(width) / height);
            if (rooms) {
                camera.eye = {0.9, 0.7, 0.9};
                camera.target = {0.0, 0.35, -0.3};
                camera.fovYDegrees = 70;
            }
            svo::reference::RenderOptions ro;
            ro.mode = ao                 ? svo::reference::Mode::AmbientOcclusion
                      : render == "gi" ? svo::reference::Mode::OneBounce
                                       : svo::reference::Mode::Direct;
            ro.samples = samples;
            ro.aoDistance = distance;
            svo::reference::RenderStats rs;
            svo::reference::Material material;
            material.vertexColors = false;
            material.albedo = {albedo, albedo, albedo};
            // Lights from the mesh's box, the same for the reference and every resolution.
            svo::Lights lights = svo::gl::defaultLights({b.min, b.max}, name == "cornell");
            if (rooms) { // a point light in the left room
                lights = {};
                lights.point.push_back({{-0.5, 0.8, 0.0}, {M_PI, M_PI, M_PI}});
            }
            const svo::reference::FloatImage reference =
                svo::reference::render(mesh, material, camera, width, height, ao ? svo::Lights{} : lights, ro, &rs);
            fmt::print(stderr, "{}: reference {} in {:.0f} ms ({} rays)\n", name, render, rs.wallMs, rs.rays());
            for (int r : resolutions) {
                svo::VoxelizeOptions vo;
                vo.attributes = svo::kNormals; // lit modes need them; AO from the volume leaves along them
                const svo::Octree octree =
                    voxelizer.voxelize(mesh, svo::makeGrid(mesh, svo::GridRequest{r, 0}), vo);
                svo::gl::OctreeView view(context, octree, &mesh);
                using Filter = svo::gl::AmbientOcclusion::Filter;
                using Source = svo::gl::AmbientOcclusion::Source;
                std::vector<std::pair<Source, Filter>> opacities;
                if (!ao || aoSource != "octree") opacities.push_back({Source::Volume, Filter::Max});
                if (ao && aoSource != "volume")
                    opacities.insert(opacities.end(), {{Source::Octree, Filter::Max}, {Source::Octree, Filter::Average}});
                for (const auto& [source, filter] : opacities)
                    for (int cones : coneCounts) {
                        svo::gl::ViewLayers layers;
                        layers.outlines = false;
                        layers.surface = surface == "mesh" ? svo::gl::Surface::Mesh : svo::gl::Surface::Voxels;
                        if (ao) {
                            layers.ao.cones = cones;
                            layers.ao.source = source;
                            layers.ao.filter = filter;
                            if (offset >= 0) layers.ao.offset = offset;
                            if (aperture > 0) layers.ao.apertureDegrees = aperture;
                            layers.ao.step = step;
                            layers.ao.only = true;
                            layers.ao.interleave = conePattern == "interleaved";
                            layers.ao.distance = distance / octree.grid.voxelSize;
                        } else {
                            layers.light.mode = render == "gi" ? svo::gl::Illumination::Mode::Global
                                                               : svo::gl::Illumination::Mode::Direct;
                            layers.light.lights = lights;
                            layers.light.albedo = {albedo, albedo, albedo};
                            layers.light.cones = cones;
                            if (offset >= 0) layers.light.offset = offset;
                            if (aperture > 0) layers.light.apertureDegrees = aperture;
                            layers.light.step = step;
                            layers.light.directional = directional;
                            layers.light.clearance = clearance;
                            layers.light.interleave = conePattern == "interleaved";
                            layers.light.gamma = 1.0;
                        }
                        const svo::gl::Image image = view.render(camera, width, height, layers);
                        if (!dumpDir.empty()) {
                            std::string pgm = fmt::format("P5 {} {} 255\n", width, height), ref = pgm;
                            for (int y = 0; y < height; ++y)
                                for (int x = 0; x < width; ++x) { // as compared below; 0 where not compared
                                    const uint8_t* p = image.pixel(x, y);
                                    const bool compared = p[0] == p[1] && p[1] == p[2] &&
                                                          reference.covered[size_t(y) * size_t(width) + size_t(x)];
                                    pgm += char(compared ? p[1] : 0);
                                    ref += char(compared ? std::lround(255 * std::clamp(reference.at(x, y, ao ? 0 : 1),
                                                                                        0.0f, 1.0f))
                                                         : 0);
                                }
                            const std::string stem = std::filesystem::path(name).stem().string();
                            svo::writeFileAtomically(fmt::format("{}/{}_reference.pgm", dumpDir, stem), ref);
                            svo::writeFileAtomically(fmt::format("{}/{}_{}_{}_{}_{}.pgm", dumpDir, stem, r,
                                                                 int(source), int(filter), cones),
                                                     pgm);
                        }
                        std::vector<double> errors;
                        double sumSvo = 0, sumRef = 0;
                        for (int y = 0; y < height; ++y)
                            for (int x = 0; x < width; ++x) {
                                const uint8_t* p = image.pixel(x, y);
                                const bool grey = p[0] == p[1] && p[1] == p[2]; // the background is bluish
                                if (!grey || !reference.covered[size_t(y) * size_t(width) + size_t(x)]) continue;
                                const double a = p[1] / 255.0,
                                             ref = std::clamp(double(reference.at(x, y, ao ? 0 : 1)), 0.0, 1.0);
                                errors.push_back(std::abs(a - ref));
                                sumSvo += a, sumRef += ref;
                            }
                        double squares = 0;
                        for (double e : errors) squares += e * e;
                        const double n = double(std::max<size_t>(errors.size(), 1));
                        std::vector<double> gpu, wall, moved;
                        for (const auto& t : view.timeFrames(camera, timeWidth, timeHeight, layers, frames))
                            gpu.push_back(t.gpuMs), wall.push_back(t.wallMs);
                        if (!ao)
                            for (const auto& t : view.timeFrames(camera, timeWidth, timeHeight, layers, frames, true))
                                moved.push_back(t.gpuMs);
                        const std::string line = fmt::format(
                            "| {} | {}³ | {} | {} | {:.4f} | {:.3f} | {:.4f} | {:.4f} | {} | {:.2f} | {} | {:.2f} |\n",
                            std::filesystem::path(name).stem().string(), r,
                            !ao                        ? "–"
                            : source == Source::Volume ? "volume"
                            : filter == Filter::Max    ? "octree, max"
                                                       : "octree, average",
                            cones,
                            std::sqrt(squares / n), quantile(errors, 0.99), sumSvo / n, sumRef / n, errors.size(),
                            quantile(gpu, 0.5), ao ? "–" : fmt::format("{:.2f}", quantile(moved, 0.5)),
                            quantile(wall, 0.5));
                        fmt::print("{}", line);
                        std::fflush(stdout);
                        md += line;
                    }
            }
        }
        if (!mdPath.empty()) svo::writeFileAtomically(mdPath, md);
    } catch (const std::exception& e) {
        fmt::print(stderr, "svo-bench-ao: {}\n", e.what());
        return 1;
    }
    return 0;
}
