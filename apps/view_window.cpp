// svo view's window: input, camera and panel. Drawing is the library's
// OctreeView, in the window's own context (gl::ContextOptions::adoptCurrent).
#include "view_window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <optional>

#include "png_file.h"
#include "view_keys.h"
#include "svo/core/error.h"
#include "svo/gl/context.h"

namespace svo::app {
namespace {

Vec3d cross(const Vec3d& a, const Vec3d& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }
Vec3d unit(const Vec3d& a) { return (1.0 / length(a)) * a; }

/// v rotated by `angle` radians about the unit axis k (Rodrigues).
Vec3d rotate(const Vec3d& v, const Vec3d& k, double angle)
{
    const double c = std::cos(angle), s = std::sin(angle);
    return c * v + s * cross(k, v) + ((1 - c) * dot(k, v)) * k;
}

/// A combo box over an enum's names (svo/core/enum_names.h), in its table's order.
template <typename E>
bool enumCombo(const char* label, E& value)
{
    const auto& table = enumNames(E{});
    int at = 0;
    for (int i = 0; i < int(std::size(table)); ++i)
        if (table[i].value == value) at = i;
    const auto item = [](void* data, int i, const char** text) {
        *text = static_cast<const EnumName<E>*>(data)[i].name.data();
        return true;
    };
    if (!ImGui::Combo(label, &at, item, const_cast<EnumName<E>*>(std::data(table)), int(std::size(table)))) return false;
    value = table[at].value;
    return true;
}

/// The value after @a value in its enum's table, the first after the last (keys that cycle).
template <typename E>
E nextValue(E value)
{
    const auto& table = enumNames(E{});
    for (size_t i = 0; i < std::size(table); ++i)
        if (table[i].value == value) return table[(i + 1) % std::size(table)].value;
    return table[0].value;
}

/// The last GLFW error, for one-line messages.
std::string glfwReason()
{
    const char* what = nullptr;
    glfwGetError(&what);
    return what ? what : "unknown GLFW error";
}

/// Orbit, pan and zoom on a ViewCamera, keeping its up vector.
struct Orbit {
    gl::ViewCamera camera;

    void turn(double dx, double dy) // pixels dragged
    {
        const Vec3d up = unit(camera.up);
        Vec3d offset = camera.eye - camera.target;
        offset = rotate(offset, up, -dx * 0.008);
        const Vec3d right = unit(cross(-1.0 * offset, up));
        const Vec3d tilted = rotate(offset, right, -dy * 0.008);
        // Stop short of the poles, where up and the view direction meet.
        if (std::abs(dot(unit(tilted), up)) < 0.995) offset = tilted;
        camera.eye = camera.target + offset;
    }
    void pan(double dx, double dy, int viewportHeight)
    {
        const Vec3d forward = unit(camera.target - camera.eye);
        const Vec3d right = unit(cross(forward, camera.up)), up = cross(right, forward);
        const double span = camera.orthographic
                                ? camera.height
                                : 2 * length(camera.target - camera.eye) * std::tan(camera.fovYDegrees * M_PI / 360);
        const Vec3d move = (span / std::max(viewportHeight, 1)) * ((-dx) * right + dy * up);
        camera.eye = camera.eye + move;
        camera.target = camera.target + move;
    }
    void zoom(double steps)
    {
        const double f = std::pow(0.85, steps);
        if (camera.orthographic) camera.height *= f;
        camera.eye = camera.target + f * (camera.eye - camera.target);
    }
};

/// Everything the window changes as it runs.
struct ViewerState {
    ViewWindowInput in;
    Voxelizer& voxelizer;
    std::optional<gl::Context> context;
    std::optional<gl::OctreeView> view;
    Octree octree;
    VoxelizeStats stats;
    int64_t resolution = 0;
    VoxelizeSettings chosen; ///< the backend, dilation and mode the panel (keys B, C, T) asks for
    Orbit orbit;
    int width = 0, height = 0;               // framebuffer pixels
    std::string perLevel;                    // occupied nodes per level, for the panel
    std::string message;                     // the last error or note, shown in the panel
    bool loopCutReported = false;            // rays cut by the driver's loop limit: warned once on exit
    bool quit = false;
    int screenshotCount = 0;
    ViewWindowResult result;
    double lastX = 0, lastY = 0;


    ViewerState(ViewWindowInput input, Voxelizer& v) : in(std::move(input)), voxelizer(v) {}

    bool canRevoxelize() const { return in.loaded.mesh.has_value(); }

    void setOctree(Octree next)
    {
        octree = std::move(next);
        const VoxelAttributes& a = octree.attributes;
        const gl::VoxelColor c = in.layers.voxelColor;
        if ((c == gl::VoxelColor::Normal && a.normals.empty()) || (c == gl::VoxelColor::Color && a.colors.empty()) ||
            (c == gl::VoxelColor::Triangle && a.triangles.empty()))
            in.layers.voxelColor = gl::VoxelColor::Flat;
        perLevel.clear();
        for (uint64_t n : octreeStats(octree).occupiedPerLevel) perLevel += (perLevel.empty() ? "" : " ") + thousands(n);
    }

    /// Voxelizes the mesh again at `r` with the panel's backend, dilation and
    /// mode, and swaps the octree in; on an error the previous one stays.
    void revoxelize(int64_t r)
    {
        if (!canRevoxelize()) {
            message = "re-voxelization needs a mesh input";
            return;
        }
        r = std::clamp<int64_t>(r, 1, int64_t(kMaxGridDim) - 1);
        BackendArgs args = in.backend;
        args.settings.backend = chosen.backend;
        args.settings.dilation = chosen.dilation;
        args.settings.mode = chosen.mode;
        try {
            VoxelizeOptions options = args.voxelizeOptions();
            VoxelizeStats s;
            options.stats = &s;
            const TriangleMesh& mesh = *in.loaded.mesh;
            Octree next = voxelizer.voxelize(mesh, makeGrid(mesh, GridRequest{r, 0.0}), options);
            view->setOctree(next, &mesh);
            setOctree(std::move(next));
            stats = std::move(s);
            resolution = r;
            message.clear();
        } catch (const std::exception& e) {
            message = fmt::format("kept the previous octree: {}", errorMessage(e));
            result.errors.push_back(message);
        }
    }

    void frameAll(const Vec3d& direction, bool orthographic)
    {
        orbit.camera = gl::frameBox(gl::gridWorldBox(octree.grid), direction, orthographic,
                                    double(std::max(width, 1)) / double(std::max(height, 1)));
    }

    void screenshot()
    {
        std::string path;
        do path = fmt::format("svo-view-{}.png", ++screenshotCount);
        while (std::filesystem::exists(path));
        try {
            writePng(path, view->render(orbit.camera, width, height, in.layers));
            result.screenshots.push_back(path);
            message = "wrote " + path;
        } catch (const std::exception& e) {
            message = errorMessage(e);
            result.errors.push_back(message);
        }
    }

    /// The next voxel colouring the octree has a channel for. A mesh input
    /// voxelized without the triangle ids (or with the normals alone, for AO
    /// and lighting) is voxelized again with every channel it can give
    /// (normals, triangle ids, colours when it has vertex colours).
    void nextColor()
    {
        if (octree.attributes.triangles.empty() && canRevoxelize()) {
            in.backend.settings.attributes = kNormals | kTriangles | (in.loaded.mesh->colors.empty() ? 0u : uint32_t(kColors));
            revoxelize(resolution);
        }
        const VoxelAttributes& a = octree.attributes;
        const bool have[4] = {true, !a.normals.empty(), !a.colors.empty(), !a.triangles.empty()};
        int c = int(in.layers.voxelColor);
        do c = (c + 1) % 4;
        while (!have[c]);
        in.layers.voxelColor = gl::VoxelColor(c);
    }

    /// Lighting reads the normal channel and the colours (its albedo, when the
    /// mesh has vertex colours), AO from the volume the normals: a mesh input
    /// voxelized without them is voxelized again with them (once; a failure
    /// shows in the panel and keeps the octree).
    void ensureChannels(uint32_t wanted)
    {
        if (!canRevoxelize()) return;
        if (in.loaded.mesh->colors.empty()) wanted &= ~uint32_t(kColors);
        if ((octree.channels() & wanted) == wanted || (in.backend.settings.attributes & wanted) == wanted) return;
        in.backend.settings.attributes |= wanted;
        revoxelize(resolution);
    }

    /// A render mode turned on or off (keys L, R and G, the panel), with the
    /// panel's layers as they are: the view policy (svo/gl/view_request.h)
    /// gives the layers as svo view --render gets them (no outlines or brick
    /// boxes while lit or AO alone, default cones and lights, the mesh's
    /// surface under --surface auto), after the channels it reads are
    /// voxelized. A request the octree cannot meet (lighting an octree file
    /// without normals) leaves the layers as they were and says why in the
    /// panel.
    void follow(gl::RenderMode render)
    {
        gl::ViewRequest r;
        r.render = render;
        r.surface = in.autoSurface                          ? gl::SurfaceChoice::Auto
                    : in.layers.surface == gl::Surface::Mesh ? gl::SurfaceChoice::Mesh
                                                             : gl::SurfaceChoice::Voxels;
        r.room = in.room;
        r.layers = in.layers;
        ensureChannels(gl::channelsFor(r));
        r.layers = in.layers; // as a re-voxelization left them
        try {
            in.layers = gl::viewLayers(r, octree, in.loaded.mesh.has_value());
        } catch (const InvalidInput& e) {
            message = errorMessage(e);
        }
    }

    /// Lighting off, direct, or direct and one bounce; AO alone as it was.
    void setLighting(gl::Illumination::Mode m)
    {
        follow(m == gl::Illumination::Mode::Global   ? gl::RenderMode::Global
               : m == gl::Illumination::Mode::Direct ? gl::RenderMode::Direct
               : in.layers.ao.only                   ? gl::RenderMode::AmbientOcclusion
                                                     : gl::RenderMode::Layers);
    }

    /// AO alone on or off, lighting as it was.
    void setAoOnly(bool only)
    {
        in.layers.ao.only = only;
        setLighting(in.layers.light.mode);
    }

    /// One key, from the keyboard or the --keys script (view_keys.h's table).
    void press(unsigned key)
    {
        if (key >= 128) return;
        if (const ViewKey* k = viewKeyOf(char(key))) act(k->action);
    }

    void act(ViewAction action)
    {
        gl::ViewLayers& l = in.layers;
        switch (action) {
        case ViewAction::Voxels: l.voxels = !l.voxels; break;
        case ViewAction::Outlines: l.outlines = !l.outlines; break;
        case ViewAction::Mesh: l.mesh = !l.mesh; break;
        case ViewAction::Bricks: l.bricks = !l.bricks; break;
        case ViewAction::Color: nextColor(); break;
        case ViewAction::Lighting: setLighting(gl::Illumination::Mode((int(l.light.mode) + 1) % 3)); break;
        case ViewAction::AmbientOcclusion:
            l.ao.cones = l.ao.cones ? 0 : gl::AmbientOcclusion::kDefaultCones;
            if (!l.ao.cones) setAoOnly(false);
            break;
        case ViewAction::AoOnly: setAoOnly(!l.ao.only); break;
        case ViewAction::Finer: revoxelize(resolution * 2); break;
        case ViewAction::Coarser: revoxelize(std::max<int64_t>(resolution / 2, 1)); break;
        case ViewAction::Backend: chosen.backend = nextValue(chosen.backend); revoxelize(resolution); break;
        case ViewAction::Dilation: chosen.dilation = nextValue(chosen.dilation); revoxelize(resolution); break;
        case ViewAction::Mode: chosen.mode = nextValue(chosen.mode); revoxelize(resolution); break;
        case ViewAction::Frame: frameAll(unit(orbit.camera.target - orbit.camera.eye), orbit.camera.orthographic); break;
        case ViewAction::AlongX: frameAll({-1, 0, 0}, true); break;
        case ViewAction::AlongY: frameAll({0, -1, 0}, true); break;
        case ViewAction::AlongZ: frameAll({0, 0, -1}, true); break;
        case ViewAction::Screenshot: screenshot(); break;
        case ViewAction::Quit: quit = true; break;
        }
    }

    /// A checkbox labelled with its key.
    void toggle(const char* name, ViewAction a, bool& value)
    {
        ImGui::Checkbox(viewKeyLabel(name, a).c_str(), &value);
    }

    /// The key table (view_keys.h), folded away until opened.
    void keysPanel()
    {
        if (!ImGui::CollapsingHeader("keys and mouse")) return;
        for (const ViewKey& k : kViewKeys) ImGui::Text("%-20s %s", viewKeyNames(k).c_str(), std::string(k.does).c_str());
        for (const auto& [what, does] : kViewMouse)
            ImGui::Text("%-20s %s", std::string(what).c_str(), std::string(does).c_str());
    }

    /// The lighting controls: mode, the first light, exposure, the cones.
    /// A moved light re-injects the volume on the next frame.
    void lightingPanel()
    {
        gl::Illumination& li = in.layers.light;
        static constexpr const char* kLighting[] = {"off", "direct", "direct + one bounce"};
        int m = int(li.mode);
        if (ImGui::Combo(viewKeyLabel("lighting", ViewAction::Lighting).c_str(), &m, kLighting, IM_ARRAYSIZE(kLighting))) setLighting(gl::Illumination::Mode(m));
        if (li.mode == gl::Illumination::Mode::Off) return;
        if (!li.lights.directional.empty()) {
            // The sun by where it comes from: azimuth around +y, elevation above the horizon.
            Vec3d& d = li.lights.directional[0].direction;
            const Vec3d from = -1.0 * unit(d);
            float angles[2] = {float(std::atan2(from.z, from.x) * 180 / M_PI),
                               float(std::asin(std::clamp(from.y, -1.0, 1.0)) * 180 / M_PI)};
            if (ImGui::SliderFloat2("sun azimuth, elevation", angles, -180.0f, 180.0f, "%.0f deg")) {
                const double az = angles[0] * M_PI / 180, el = std::clamp(double(angles[1]), -89.0, 89.0) * M_PI / 180;
                d = -1.0 * Vec3d{std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az)};
            }
        } else if (!li.lights.point.empty()) {
            const auto box = gl::gridWorldBox(octree.grid);
            Vec3d& p = li.lights.point[0].position;
            float xyz[3] = {float(p.x), float(p.y), float(p.z)};
            const float lo = float(std::min({box[0].x, box[0].y, box[0].z})),
                        hi = float(std::max({box[1].x, box[1].y, box[1].z}));
            if (ImGui::SliderFloat3("point light", xyz, lo, hi, "%.3f")) p = {xyz[0], xyz[1], xyz[2]};
        }
        float exposure = float(li.exposure);
        if (ImGui::SliderFloat("exposure", &exposure, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
            li.exposure = exposure;
        if (li.mode != gl::Illumination::Mode::Global) return;
        ImGui::SliderInt("GI cones", &li.cones, 1, 16);
        float aperture = float(li.apertureDegrees), offset = float(li.offset), specular = float(li.specular.x),
              glossy = float(li.specularApertureDegrees);
        if (ImGui::SliderFloat("GI aperture", &aperture, 10.0f, 120.0f, "%.0f deg")) li.apertureDegrees = aperture;
        if (ImGui::SliderFloat("GI offset", &offset, 0.0f, 8.0f, "%.2f texels")) li.offset = offset;
        float step = float(li.step);
        if (ImGui::SliderFloat("GI step", &step, 0.05f, 1.0f, "%.2f of the cone")) li.step = step;
        ImGui::Checkbox("six-way radiance", &li.directional);
        ImGui::Checkbox("GI cones clear of voxels (thin walls)", &li.clearance);
        ImGui::Checkbox("GI cones interleaved over 4x4 pixels", &li.interleave);
        if (ImGui::SliderFloat("specular", &specular, 0.0f, 1.0f, "%.2f")) li.specular = {specular, specular, specular};
        if (li.specular.x > 0 && ImGui::SliderFloat("specular aperture", &glossy, 2.0f, 90.0f, "%.0f deg"))
            li.specularApertureDegrees = glossy;
    }

    void panel(double frameMs)
    {
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.85f);
        ImGui::Begin("svo view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::Text("%s", in.title.c_str());
        ImGui::Text("%s", result.renderer.c_str());
        ImGui::Text("frame %.2f ms (%.0f fps), %d x %d", frameMs, frameMs > 0 ? 1000.0 / frameMs : 0.0, width, height);
        ImGui::Separator();
        gl::ViewLayers& l = in.layers;
        toggle("voxels", ViewAction::Voxels, l.voxels);
        ImGui::SameLine();
        toggle("outlines", ViewAction::Outlines, l.outlines);
        ImGui::SameLine();
        toggle("bricks", ViewAction::Bricks, l.bricks);
        if (in.loaded.mesh) {
            ImGui::SameLine();
            toggle("mesh", ViewAction::Mesh, l.mesh);
            // Light, AO and colours on the triangles instead of the voxels (--surface).
            bool shadeMesh = l.surface == gl::Surface::Mesh;
            if (ImGui::Checkbox("shade the mesh, not the voxels", &shadeMesh)) {
                l.surface = shadeMesh ? gl::Surface::Mesh : gl::Surface::Voxels;
                in.autoSurface = false;
            }
        }
        static constexpr const char* kColors[] = {"flat", "normal", "colour", "triangle id"};
        ImGui::Text("%s: %s", viewKeyLabel("voxel colour", ViewAction::Color).c_str(), kColors[int(l.voxelColor)]);
        if (octree.attributes.empty()) {
            ImGui::SameLine();
            ImGui::TextDisabled("(no attribute channels; --attributes)");
        }
        // Ambient occlusion, cone-traced through the volume or the octree.
        ImGui::SliderInt(viewKeyLabel("AO cones", ViewAction::AmbientOcclusion).c_str(), &l.ao.cones, 0, 16);
        if (l.ao.cones > 0) {
            ImGui::SameLine();
            bool only = l.ao.only;
            if (ImGui::Checkbox(viewKeyLabel("AO alone", ViewAction::AoOnly).c_str(), &only)) setAoOnly(only);
            float aperture = float(l.ao.apertureDegrees), offset = float(l.ao.offset), distance = float(l.ao.distance);
            if (ImGui::SliderFloat("AO aperture", &aperture, 10.0f, 120.0f, "%.0f deg")) l.ao.apertureDegrees = aperture;
            const bool volume = l.ao.source == gl::AmbientOcclusion::Source::Volume;
            enumCombo("AO source", l.ao.source);
            if (ImGui::SliderFloat("AO offset", &offset, 0.0f, 8.0f, volume ? "%.2f texels" : "%.2f voxels"))
                l.ao.offset = offset;
            if (ImGui::SliderFloat("AO distance", &distance, 1.0f, 1024.0f, "%.0f voxels", ImGuiSliderFlags_Logarithmic))
                l.ao.distance = distance;
            float step = float(l.ao.step);
            if (ImGui::SliderFloat("AO step", &step, 0.05f, 1.0f, "%.2f of the cone")) l.ao.step = step;
            if (volume) ImGui::Checkbox("AO cones interleaved over 4x4 pixels", &l.ao.interleave);
            if (!volume) enumCombo("AO filter", l.ao.filter);
        } else {
            l.ao.only = false;
        }
        lightingPanel();
        int levels[2] = {int(std::min<uint32_t>(l.firstLevel, octree.brickLevel)),
                         int(std::min<uint32_t>(l.lastLevel, octree.brickLevel))};
        if (ImGui::SliderInt2("outline levels", levels, 0, int(octree.brickLevel))) {
            l.firstLevel = uint32_t(std::min(levels[0], levels[1]));
            l.lastLevel = uint32_t(std::max(levels[0], levels[1]));
        }
        if (ImGui::Button(viewKeyLabel("frame all", ViewAction::Frame).c_str())) act(ViewAction::Frame);
        ImGui::SameLine();
        if (ImGui::Button("X")) act(ViewAction::AlongX);
        ImGui::SameLine();
        if (ImGui::Button("Y")) act(ViewAction::AlongY);
        ImGui::SameLine();
        if (ImGui::Button("Z")) act(ViewAction::AlongZ);
        ImGui::SameLine();
        ImGui::Checkbox("orthographic", &orbit.camera.orthographic);
        ImGui::SameLine();
        if (ImGui::Button(viewKeyLabel("screenshot", ViewAction::Screenshot).c_str())) act(ViewAction::Screenshot);

        ImGui::Separator();
        if (canRevoxelize()) {
            int r = int(resolution);
            ImGui::SliderInt(fmt::format("resolution ({}/{})", viewKeyFor(ViewAction::Finer).chars[0], viewKeyFor(ViewAction::Coarser).chars[0]).c_str(), &r, 8, 4096, "%d", ImGuiSliderFlags_Logarithmic);
            if (ImGui::IsItemDeactivatedAfterEdit()) revoxelize(r);
            bool changed = enumCombo(viewKeyLabel("backend", ViewAction::Backend).c_str(), chosen.backend);
            changed |= enumCombo(viewKeyLabel("dilation", ViewAction::Dilation).c_str(), chosen.dilation);
            changed |= enumCombo(viewKeyLabel("mode", ViewAction::Mode).c_str(), chosen.mode);
            if (changed) revoxelize(resolution);
        } else {
            ImGui::TextDisabled("re-voxelization needs a mesh input");
        }
        ImGui::Text("%s voxels, %s bricks, %u levels", thousands(octree.voxelCount()).c_str(),
                    thousands(octree.bricks.size()).c_str(), octree.brickLevel + 1);
        ImGui::TextWrapped("nodes per level: %s", perLevel.c_str());
        if (stats.gpuBytes) ImGui::Text("GPU %.1f MB (build), %s", double(stats.gpuBytes) / 1e6, stats.backend.c_str());
        for (const StageTime& s : stats.stages)
            ImGui::Text("  %-22s %8.2f ms GPU %8.2f ms wall", s.name.c_str(), s.gpuMs, s.wallMs);
        if (!message.empty()) {
            ImGui::Separator();
            ImGui::PushTextWrapPos(480);
            ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), "%s", message.c_str());
            ImGui::PopTextWrapPos();
        }
        keysPanel();
        ImGui::End();
    }
};

ViewerState* stateOf(GLFWwindow* w) { return static_cast<ViewerState*>(glfwGetWindowUserPointer(w)); }

/// GLFW windows and ImGui, torn down on every path out.
struct WindowSystem {
    GLFWwindow* window = nullptr;
    bool imgui = false, glfwBackend = false, glBackend = false;
    ~WindowSystem()
    {
        if (glBackend) ImGui_ImplOpenGL3_Shutdown();
        if (glfwBackend) ImGui_ImplGlfw_Shutdown();
        if (imgui) ImGui::DestroyContext();
        if (window) glfwDestroyWindow(window);
        glfwTerminate();
    }
};

} // namespace

ViewWindowResult runViewWindow(ViewWindowInput input, Voxelizer& voxelizer)
{
    WindowSystem ws;
    if (!glfwInit()) throw DeviceError("cannot open svo view's window: " + glfwReason());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, input.backend.device.glDebug ? GLFW_TRUE : GLFW_FALSE);
    const std::string title = "svo view: " + input.title;
    ws.window = glfwCreateWindow(input.width, input.height, title.c_str(), nullptr, nullptr);
    if (!ws.window) throw DeviceError("cannot open svo view's window with OpenGL 4.5 core: " + glfwReason());
    glfwMakeContextCurrent(ws.window);
    glfwSwapInterval(input.frames > 0 ? 0 : 1); // scripted runs do not wait for the display

    ViewerState st(std::move(input), voxelizer);
    gl::ContextOptions co;
    co.adoptCurrent = true;
    co.debug = st.in.backend.device.glDebug;
    st.context.emplace(co);
    st.result.renderer = st.context->info().renderer;
    st.setOctree(std::move(st.in.loaded.octree));
    st.stats = st.in.stats;
    st.resolution = st.in.resolution;
    st.view.emplace(*st.context, st.octree, st.in.loaded.mesh ? &*st.in.loaded.mesh : nullptr);
    st.orbit.camera = st.in.camera;
    st.chosen = st.in.backend.settings;

    // Our callbacks first: ImGui's GLFW backend chains to them.
    glfwSetWindowUserPointer(ws.window, &st);
    glfwSetCharCallback(ws.window, [](GLFWwindow* w, unsigned c) {
        if (!ImGui::GetIO().WantCaptureKeyboard) stateOf(w)->press(c < 128 ? unsigned(std::tolower(int(c))) : c);
    });
    glfwSetKeyCallback(ws.window, [](GLFWwindow* w, int key, int, int action, int) {
        if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
        // The keys that type no character: view_keys.h's "also" keys.
        if (key == GLFW_KEY_ESCAPE) stateOf(w)->act(ViewAction::Quit);
        if (key == GLFW_KEY_KP_ADD) stateOf(w)->act(ViewAction::Finer);
        if (key == GLFW_KEY_KP_SUBTRACT) stateOf(w)->act(ViewAction::Coarser);
    });
    glfwSetScrollCallback(ws.window, [](GLFWwindow* w, double, double dy) {
        if (!ImGui::GetIO().WantCaptureMouse) stateOf(w)->orbit.zoom(dy);
    });
    glfwSetCursorPosCallback(ws.window, [](GLFWwindow* w, double x, double y) {
        ViewerState& s = *stateOf(w);
        const double dx = x - s.lastX, dy = y - s.lastY;
        s.lastX = x;
        s.lastY = y;
        if (ImGui::GetIO().WantCaptureMouse) return;
        if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) s.orbit.turn(dx, dy);
        else if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                 glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS)
            s.orbit.pan(dx, dy, s.height);
    });

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ws.imgui = true;
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini left in the user's folder
    ImGui::StyleColorsDark();
    ws.glfwBackend = ImGui_ImplGlfw_InitForOpenGL(ws.window, true);
    ws.glBackend = ws.glfwBackend && ImGui_ImplOpenGL3_Init("#version 450");
    if (!ws.glBackend) throw DeviceError("cannot start the panel (Dear ImGui's GLFW and OpenGL 3 backends)");

    auto last = std::chrono::steady_clock::now();
    double frameMs = 0, totalMs = 0;
    size_t scripted = 0;
    while (!glfwWindowShouldClose(ws.window) && !st.quit && (st.in.frames == 0 || st.result.frames < st.in.frames)) {
        glfwPollEvents();
        if (st.result.frames > 0 && scripted < st.in.keys.size()) st.press(static_cast<unsigned char>(st.in.keys[scripted++]));
        if (st.quit) break;
        // AO turned on (a key or the panel) leaves along the normals.
        if (st.in.layers.ao.cones > 0 && st.in.layers.ao.source == gl::AmbientOcclusion::Source::Volume)
            st.ensureChannels(kNormals);
        glfwGetFramebufferSize(ws.window, &st.width, &st.height);
        if (st.width < 1 || st.height < 1) { // minimized
            glfwWaitEventsTimeout(0.1);
            continue;
        }
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        st.panel(frameMs);
        ImGui::Render();

        try {
            st.view->draw(st.orbit.camera, st.width, st.height, st.in.layers);
        } catch (const Error& e) {
            // What the panel turned on cannot be drawn (a grid too wide for
            // the lighting volume, the GPU out of memory): say so in the
            // panel, turn AO and lighting off, and draw again without them.
            st.message = errorMessage(e);
            st.result.errors.push_back(st.message);
            st.in.layers.ao.cones = 0;
            st.in.layers.ao.only = false;
            st.in.layers.light.mode = gl::Illumination::Mode::Off;
            st.view->draw(st.orbit.camera, st.width, st.height, st.in.layers);
        }
        // A CPU rasterizer's loop limit cut some rays short: the frame is
        // drawn as it came out, and the panel says so.
        if (const uint32_t cut = st.view->cutPixels()) {
            st.message = fmt::format("{} pixels' rays were cut short by the driver's loop limit; "
                                     "fewer cones, a wider step or a coarser grid avoid it",
                                     cut);
            if (!st.loopCutReported) st.result.errors.push_back(st.message);
            st.loopCutReported = true;
        }
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        glfwSwapBuffers(ws.window);

        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last).count();
        last = now;
        frameMs = frameMs == 0 ? ms : 0.9 * frameMs + 0.1 * ms;
        if (st.result.frames > 0) totalMs += ms;
        ++st.result.frames;
    }
    ViewWindowResult result = std::move(st.result);
    result.meanFrameMs = result.frames > 1 ? totalMs / (result.frames - 1) : 0;
    result.resolution = st.resolution;
    st.view.reset();
    st.context.reset();
    result.octree = std::move(st.octree);
    return result;
}

} // namespace svo::app
