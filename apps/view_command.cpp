// svo view [INPUT] [--screenshot out.png] [--size WxH] [--camera ...] [--view ...] [--layers ...] [--levels a:b]
// The renderer is the library's (svo/gl/octree_view.h); this file parses, calls
// and prints, and view_window.cpp runs the window.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <fmt/format.h>
#include <memory>
#include <optional>
#include <sstream>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "png_file.h"
#include "view_keys.h"
#ifdef SVO_WITH_WINDOW
#include "view_window.h"
#endif
#include "svo/core/atomic_file.h"
#include "svo/core/camera.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/gl/context.h"
#include "svo/gl/octree_view.h"
#include "svo/gl/view_request.h"
#include "svo/load_octree.h"
#include "svo/vdb_io/octree_files.h"
#include "svo/core/mesh_io.h"

namespace svo::app {
namespace {

struct ViewArgs {
    std::string input, screenshot, size = "1280x960", camera, view = "front", layers = "voxels,outlines", levels,
                                     gridName, keys, save, conePattern = "interleaved";
    int frames = 0;
    /// The declared options (svo/gl/view_request.h) bound here: --render,
    /// --surface, --color, --ao*, --gi-*, ...; the layers, levels, lights,
    /// colours and cone pattern are parsed into it by viewRequest.
    gl::ViewRequest request;
    std::vector<std::string> lights;
    std::string albedo, specular;
    double fov = 40.0;
    std::optional<double> ortho; ///< --ortho: the height an orthographic view spans
    GridRequest grid; ///< -r/--resolution or --voxel-size
    BackendArgs backend;
    OutputHabits habits; ///< -q, -v, --no-clobber
};

std::vector<std::string> split(const std::string& text, char sep)
{
    std::vector<std::string> parts;
    std::stringstream s(text);
    std::string part;
    while (std::getline(s, part, sep)) parts.push_back(part);
    if (!text.empty() && text.back() == sep) parts.emplace_back();
    return parts;
}

double number(const std::string& text, const std::string& option)
{
    try {
        size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    throw InvalidInput(fmt::format("{} '{}': not a finite number", option, text));
}

std::pair<int, int> parseSize(const std::string& text)
{
    const auto parts = split(text, 'x');
    if (parts.size() == 2) {
        const double w = number(parts[0], "--size"), h = number(parts[1], "--size");
        if (w >= 1 && h >= 1 && w <= 16384 && h <= 16384 && w == int(w) && h == int(h)) return {int(w), int(h)};
    }
    throw InvalidInput(fmt::format("--size '{}': expected WxH, 1 to 16384 pixels each", text));
}

/// "a:b", "a:", ":b" or "a".
void parseLevels(const std::string& text, gl::ViewLayers& layers)
{
    if (text.empty()) return;
    auto level = [&](const std::string& s) {
        const double v = number(s, "--levels");
        if (v < 0 || v > 63 || v != int(v)) throw InvalidInput(fmt::format("--levels '{}': expected a:b with levels from 0", text));
        return uint32_t(v);
    };
    const auto colon = text.find(':');
    if (colon == std::string::npos) {
        layers.firstLevel = layers.lastLevel = level(text);
    } else {
        if (colon > 0) layers.firstLevel = level(text.substr(0, colon));
        if (colon + 1 < text.size()) layers.lastLevel = level(text.substr(colon + 1));
    }
    if (layers.firstLevel > layers.lastLevel)
        throw InvalidInput(fmt::format("--levels '{}': the first level is past the last", text));
}

/// --layers: which of the voxel, outline, brick and mesh layers are drawn.
void parseLayers(const std::string& text, gl::ViewLayers& l)
{
    l.voxels = l.outlines = l.mesh = l.bricks = false;
    for (const std::string& name : split(text, ',')) {
        if (name == "voxels") l.voxels = true;
        else if (name == "outlines") l.outlines = true;
        else if (name == "mesh") l.mesh = true;
        else if (name == "bricks") l.bricks = true;
        else throw InvalidInput(fmt::format("--layers '{}': layers are voxels, outlines, bricks and mesh", text));
    }
}

/// "r,g,b" or one value for all three.
Vec3d parseColor(const std::string& text, const std::string& option)
{
    const auto parts = split(text, ',');
    if (parts.size() == 1) {
        const double v = number(parts[0], option);
        return {v, v, v};
    }
    if (parts.size() == 3) return {number(parts[0], option), number(parts[1], option), number(parts[2], option)};
    throw InvalidInput(fmt::format("{} '{}': expected one value or r,g,b", option, text));
}

/// "sun:dx,dy,dz[:E]" (a directional light travelling along d, irradiance E)
/// or "point:x,y,z[:I]" (a point light at x,y,z, intensity I); E and I are
/// one value or r,g,b, π by default.
void parseLight(const std::string& text, Lights& lights)
{
    const auto parts = split(text, ':');
    const bool sun = !parts.empty() && parts[0] == "sun", point = !parts.empty() && parts[0] == "point";
    if ((!sun && !point) || parts.size() < 2 || parts.size() > 3)
        throw InvalidInput(fmt::format("--light '{}': expected sun:dx,dy,dz[:E] or point:x,y,z[:I]", text));
    const auto xyz = split(parts[1], ',');
    if (xyz.size() != 3) throw InvalidInput(fmt::format("--light '{}': expected three coordinates after '{}:'", text, parts[0]));
    const Vec3d v{number(xyz[0], "--light"), number(xyz[1], "--light"), number(xyz[2], "--light")};
    const Vec3d power = parts.size() == 3 ? parseColor(parts[2], "--light") : Vec3d{M_PI, M_PI, M_PI};
    if (sun) lights.directional.push_back({v, power});
    else lights.point.push_back({v, power});
}

/// The input as errors name it.
std::string inputName(const ViewArgs& a) { return a.input.empty() ? "cornell_box" : a.input; }

bool haveDisplay()
{
    for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"})
        if (const char* d = std::getenv(name); d && *d) return true;
    return false;
}

/// Window or screenshot: refuses the flags of the other, and a window without a display.
void checkOutputKind(const ViewArgs& a)
{
    // The viewer and its lighting draw with OpenGL: without it, one line and no other work.
    if (const std::string why = gl::openGlMissing(); !why.empty())
        throw DeviceError("svo view needs OpenGL, which cannot be loaded here: " + why);
    if (a.screenshot.empty()) {
#ifndef SVO_WITH_WINDOW
        throw Unsupported("this svo was built without its window (SVO_WITH_WINDOW=OFF); give --screenshot PNG to render "
                          "offscreen");
#endif
        if (!haveDisplay())
            throw DeviceError("no display for svo view's window (DISPLAY and WAYLAND_DISPLAY are unset); give --screenshot PNG "
                              "to render offscreen");
    } else if (!a.keys.empty() || a.frames != 0 || !a.save.empty()) {
        throw InvalidInput("--keys, --frames and --save drive the window; --screenshot renders one frame without it");
    }
    if (a.frames < 0) throw InvalidInput(fmt::format("--frames {}: expected 0 (until closed) or more", a.frames));
}

/// The lights, albedo and glossy colour of a lit picture, into the request.
void parseLighting(const ViewArgs& a, gl::ViewRequest& asked)
{
    gl::ViewLayers& layers = asked.layers;
    if (!gl::isLit(asked.render)) {
        if (!a.lights.empty() || !a.albedo.empty() || !a.specular.empty())
            throw InvalidInput("--light, --albedo and --specular light the voxels of --render direct or gi");
        return;
    }
    if (!a.lights.empty()) {
        asked.lights.emplace();
        for (const std::string& l : a.lights) parseLight(l, *asked.lights);
    }
    if (!a.albedo.empty()) layers.light.albedo = parseColor(a.albedo, "--albedo");
    if (!a.specular.empty()) {
        if (asked.render != gl::RenderMode::Global)
            throw InvalidInput("--specular: the glossy cone is part of --render gi");
        layers.light.specular = parseColor(a.specular, "--specular");
    }
}

/// What the flags ask for; the view policy (svo/gl/view_request.h) makes the
/// layers from it once the octree is loaded. Checked before any voxelizing.
gl::ViewRequest viewRequest(const ViewArgs& a)
{
    gl::ViewRequest asked = a.request; // the declared options, read and checked as they were parsed
    asked.room = a.input.empty(); // the Cornell box, lit from under its ceiling
    gl::ViewLayers& layers = asked.layers;
    parseLayers(a.layers, layers);
    parseLevels(a.levels, layers);
    layers.ao.volumeResolution = layers.light.volumeResolution; // --light-volume: one volume for AO and light
    layers.ao.interleave = layers.light.interleave = a.conePattern == "interleaved";
    parseLighting(a, asked);
    gl::checkViewRequest(asked); // out-of-range options (the default lights come with the octree's box)
    return asked;
}

/// --camera: eye and target, and optionally up (6 or 9 numbers); empty when not given.
std::vector<double> parseCamera(const std::string& text)
{
    std::vector<double> cam;
    if (text.empty()) return cam;
    for (const std::string& part : split(text, ',')) cam.push_back(number(part, "--camera"));
    if (cam.size() != 6 && cam.size() != 9)
        throw InvalidInput(fmt::format("--camera '{}': expected eye x,y,z, target x,y,z and optionally up x,y,z", text));
    return cam;
}

/// The camera: --view of the grid's box (the Cornell box's front: the
/// classic view through its open side), then --camera, --fov and --ortho.
gl::ViewCamera viewCamera(const ViewArgs& a, const GridSpec& grid, double aspect, const std::vector<double>& cam)
{
    const auto box = gl::gridWorldBox(grid);
    gl::ViewCamera camera =
        a.input.empty() && a.view == "front" ? gl::roomView(box, aspect, a.fov) : gl::namedView(box, a.view, aspect);
    if (!cam.empty()) {
        camera.eye = {cam[0], cam[1], cam[2]};
        camera.target = {cam[3], cam[4], cam[5]};
        if (cam.size() == 9) camera.up = {cam[6], cam[7], cam[8]};
        camera.orthographic = false;
    }
    camera.fovYDegrees = a.fov;
    if (a.ortho) {
        camera.orthographic = true;
        camera.height = *a.ortho;
    }
    return camera;
}

/// The octree to show: the built-in Cornell box voxelized, or the input
/// loaded (a level set or unsigned distance field: its zero crossing).
LoadedOctree loadInput(const ViewArgs& a, const GridRequest& request, LibraryCall& call)
{
    LoadedOctree lo;
    if (a.input.empty()) {
        lo.mesh = cornellBox();
        lo.kind = LoadedOctree::Kind::Mesh;
        lo.octree = call.voxelizer.voxelize(*lo.mesh, makeGrid(*lo.mesh, request), call.options);
    } else {
        lo = loadOctree(call.voxelizer, a.input, a.gridName, request, call.options, FieldVoxels::ZeroCrossing);
    }
    if (lo.mesh) printWarnings(lo.mesh->warnings);
    printWarnings(call.stats.warnings);
    return lo;
}

#ifdef SVO_WITH_WINDOW
/// The window until it closes, then what it did.
void showWindow(const ViewArgs& a, ViewWindowInput in, LibraryCall& call, const std::string& inputLine)
{
    const ViewWindowResult r = runViewWindow(std::move(in), call.voxelizer);
    if (!a.save.empty()) writeOctree(a.save, r.octree);
    for (const std::string& e : r.errors) fmt::print(stderr, "svo: warning: {}\n", e);
    if (!summaryShown()) return;
    fmt::print("svo view\n");
    fmt::print("  {:<8} {}\n", "input", inputLine);
    fmt::print("  {:<8} {} voxels, {} bricks, {} levels, resolution {}\n", "octree", thousands(r.octree.voxelCount()),
               thousands(r.octree.bricks.size()), r.octree.brickLevel + 1, r.resolution);
    fmt::print("  {:<8} {} frames, {:.2f} ms a frame on {}\n", "window", r.frames, r.meanFrameMs, r.renderer);
    for (const std::string& shot : r.screenshots) fmt::print("  {:<8} {}\n", "picture", shot);
    if (!a.save.empty()) fmt::print("  {:<8} {}\n", "saved", a.save);
}
#endif

/// One picture offscreen, written to --screenshot when the batch commits.
void renderScreenshot(const ViewArgs& a, const LoadedOctree& lo, const gl::ViewCamera& camera,
                      const gl::ViewLayers& shown, int width, int height, const std::string& inputLine,
                      OutputBatch& outputs)
{
    gl::ContextOptions co;
    co.device = a.backend.device.device;
    co.debug = a.backend.device.glDebug;
    gl::Context context(co);
    gl::OctreeView view(context, lo.octree, lo.mesh ? &*lo.mesh : nullptr);
    {
        Progress p("rendering " + a.screenshot);
        writePng(a.screenshot, view.render(camera, width, height, shown));
    }
    outputs.commit();
    if (!reportShown()) {
        if (summaryShown())
            fmt::print("svo view: wrote {} ({} x {} picture, {} voxels) on {}\n", a.screenshot, width, height,
                       thousands(lo.octree.voxelCount()), context.info().renderer);
        return;
    }
    fmt::print("svo view\n");
    fmt::print("  {:<8} {}\n", "input", inputLine);
    fmt::print("  {:<8} {} voxels, {} bricks, {} levels\n", "octree", thousands(lo.octree.voxelCount()),
               thousands(lo.octree.bricks.size()), lo.octree.brickLevel + 1);
    fmt::print("  {:<8} eye {:.6g},{:.6g},{:.6g} target {:.6g},{:.6g},{:.6g} up {:.6g},{:.6g},{:.6g} {}\n", "camera",
               camera.eye.x, camera.eye.y, camera.eye.z, camera.target.x, camera.target.y, camera.target.z,
               camera.up.x, camera.up.y, camera.up.z,
               camera.orthographic ? fmt::format("orthographic {:.6g}", camera.height)
                                   : fmt::format("fov {:.6g}", camera.fovYDegrees));
    fmt::print("  {:<8} {} ({} x {}) on {}\n", "picture", a.screenshot, width, height, context.info().renderer);
}

/// The built-in Cornell box as it opens unless the flags say otherwise: its
/// walls' colours (--color) on the voxels alone (--layers; the outlines of
/// every level would cover the red wall with red lines). True when the
/// colours were chosen here, so the box is voxelized with them.
bool roomDefaults(const ViewArgs& a, const CLI::App& cmd, gl::ViewRequest& asked)
{
    if (!a.input.empty()) return false;
    if (cmd.count("--layers") == 0) asked.layers.outlines = false;
    if (cmd.count("--color") != 0) return false;
    asked.layers.voxelColor = gl::VoxelColor::Color;
    return true;
}

void runView(const ViewArgs& a, const CLI::App& cmd)
{
    checkOutputKind(a);
    const auto [width, height] = parseSize(a.size);
    gl::ViewRequest asked = viewRequest(a);
    const bool roomColors = roomDefaults(a, cmd, asked);
    gl::namedView({Vec3d{0, 0, 0}, Vec3d{1, 1, 1}}, a.view, 1.0); // the view's name, checked before any work (--view)
    const std::vector<double> cam = parseCamera(a.camera);
    const bool window = a.screenshot.empty();
    if (!window) checkWritable(a.screenshot);
    if (!a.save.empty()) checkWritable(a.save);
    checkOutputs({a.input}, {a.screenshot, a.save});
    checkClobber(a.habits, {a.screenshot, a.save});
    // The screenshot is put in place at the very end (atomic_file.h); the
    // window's own pictures (key p, --save) are written as they are taken.
    OutputBatch outputs({a.screenshot});

    BackendArgs backend = a.backend;
    // The channels the picture reads: lit pictures the normals and the vertex
    // colours as the albedo (a mesh without colours gets no colour channel),
    // AO from the volume the normals. (The window voxelizes again with them
    // when either is turned on.)
    backend.settings.attributes |= gl::channelsFor(asked) | (roomColors ? uint32_t(kColors) : 0u);
    LibraryCall call(backend, "building the octree");
    const GridRequest request = gridRequest(a.grid);
    LoadedOctree lo = loadInput(a, request, call);
    if (asked.layers.mesh && !lo.mesh) fmt::print(stderr, "svo: warning: the input has no mesh to draw (--layers mesh)\n");
    gl::ViewLayers shown;
    try {
        shown = gl::viewLayers(asked, lo.octree, lo.mesh.has_value());
    } catch (const InvalidInput& e) { // named after the input, as it is about it
        throw InvalidInput(fmt::format("{}: {}", inputName(a), errorMessage(e)));
    }
    const gl::ViewCamera camera = viewCamera(a, lo.octree.grid, double(width) / double(height), cam);
    std::string inputLine = describeInput(inputName(a), lo, call.stats);
    if (lo.fieldVoxels)
        inputLine += fmt::format(", drawn at its zero crossing: {} of its {} active voxels",
                                 thousands(lo.octree.voxelCount()), thousands(lo.fieldVoxels));
    if (!window) return renderScreenshot(a, lo, camera, shown, width, height, inputLine, outputs);
#ifdef SVO_WITH_WINDOW
    ViewWindowInput in;
    in.title = inputName(a);
    in.resolution = request.resolution > 0
                        ? request.resolution
                        : int64_t(*std::max_element(lo.octree.grid.dims.begin(), lo.octree.grid.dims.end()));
    in.loaded = std::move(lo);
    in.stats = call.stats;
    in.backend = backend;
    in.camera = camera;
    in.layers = shown;
    in.autoSurface = asked.surface == gl::SurfaceChoice::Auto;
    in.room = asked.room;
    in.width = width;
    in.height = height;
    in.frames = a.frames;
    in.keys = a.keys;
    in.save = a.save;
    showWindow(a, std::move(in), call, inputLine);
#endif
}


} // namespace

void addViewCommand(CLI::App& app)
{
    auto args = std::make_shared<ViewArgs>();
    CLI::App* cmd = app.add_subcommand(
        "view", "Draw an octree (of a mesh, .vdb or .svo; none: the Cornell box) on the GPU: voxels, node outlines, mesh");
    cmd->add_option("input", args->input,
                    fmt::format("A mesh ({}; voxelized first), .vdb, .nvdb or .svo (a level set or unsigned distance "
                                "field: drawn at its zero crossing); none: the built-in Cornell box",
                                supportedMeshExtensions()))
        ->check(nonEmptyMeshPath, "INPUT");
    addOutputPath(*cmd, "--screenshot", args->screenshot, "Render one frame offscreen to this PNG and exit", {".png"});
    cmd->add_option("--size", args->size, "Picture size WxH in pixels")->capture_default_str();
    cmd->add_option("--camera", args->camera, "eye_x,eye_y,eye_z,target_x,target_y,target_z[,up_x,up_y,up_z] (world units)");
    cmd->add_option("--view", args->view,
                    "Framed view when no --camera: front (perspective from above-right-front; the Cornell box: "
                    "straight through its open side), or along an axis from +x, -x, +y, -y, +z, -z (orthographic)")
        ->capture_default_str();
    // Checked as they are parsed, by the camera's rules (svo/core/camera.h).
    cmd->add_option_function<double>(
           "--fov",
           [args](double v) {
               checkFieldOfView(v, "--fov");
               args->fov = v;
           },
           "Vertical field of view in degrees (perspective), between 0 and 180")
        ->default_str("40");
    cmd->add_option_function<double>(
        "--ortho",
        [args](double v) {
            checkOrthographicHeight(v, "--ortho");
            args->ortho = v;
        },
        "Orthographic, spanning this many world units vertically (a positive number)");
    cmd->add_option("--layers", args->layers, "Comma-separated: voxels, outlines, bricks, mesh (the Cornell box: voxels)")
        ->capture_default_str();
    addOptions(*cmd, args->request, {"color"});
    cmd->add_option("--levels", args->levels, "Outline levels a:b (0 = root; a, a: or :b)");
    addGridNameOption(*cmd, args->gridName);
    addOptions(*cmd, args->request.layers.ao); // --ao, --ao-aperture, ... --ao-filter
    addOptions(*cmd, args->request, {"surface"});
    cmd->add_option("--cone-pattern", args->conePattern,
                    "AO from the volume, and gi's bounce: interleaved (each pixel of a 4x4 tile turns its cones and "
                    "shifts their steps its own way, and the tile's pixels on one surface are averaged: smoother, "
                    "closer to a path tracer) or fixed (every pixel the same cones)")
        ->check(CLI::IsMember({"interleaved", "fixed"}))
        ->capture_default_str();
    addOptions(*cmd, args->request, {"render"});
    cmd->add_option("--light", args->lights,
                    "direct/gi: sun:dx,dy,dz[:E] (travelling along d) or point:x,y,z[:I], world units, E and I one "
                    "value or r,g,b (default pi); repeatable. None: a point light under the Cornell box's ceiling, "
                    "else a sun from above-left-front");
    cmd->add_option("--albedo", args->albedo, "direct/gi: surface albedo, one value or r,g,b in [0, 1], where the "
                                              "octree has no colour channel (default 0.75)");
    cmd->add_option("--specular", args->specular, "gi: glossy reflectance, one value or r,g,b in [0, 1]: one more "
                                                  "cone along the mirrored view ray (default 0: none)");
    addOptions(*cmd, args->request.layers.light); // --specular-aperture, --gi-*, ... --gamma
    cmd->add_option("--frames", args->frames, "Window: close after this many frames (0: when closed)");
    cmd->add_option("--keys", args->keys,
                    "Window: keys to press, one a frame from the second frame (the window keys below)");
    addOutputPath(*cmd, "--save", args->save, "Window: write the octree shown last to this .svo, .vdb or .nvdb on exit",
                  {".svo", ".vdb", ".nvdb"});
    addGridOptions(*cmd, args->grid);
    addBackendOptions(*cmd, args->backend);
    addOptions(*cmd, args->backend.settings, {"mode", "attributes"});
    cmd->footer(viewKeysHelp());
    addOutputHabits(*cmd, args->habits);
    cmd->callback([args, cmd] { runView(*args, *cmd); });
}

} // namespace svo::app
