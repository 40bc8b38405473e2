#include "cli_options.h"
#include "option_flags.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string_view>
#include <utility>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/voxelizer.h"

namespace svo::app {

DeviceOptions BackendArgs::deviceOptions() const { return DeviceOptions{device, glDebug, ""}; }

VoxelizeOptions BackendArgs::voxelizeOptions() const
{
    VoxelizeOptions o;
    o.backend = backend == "cpu"       ? Backend::Cpu
                : backend == "raster"  ? Backend::Raster
                : backend == "compute" ? Backend::Compute
                                       : Backend::Auto;
    o.dilation = conservative == "hardware" ? Dilation::Hardware
                 : conservative == "shader" ? Dilation::Shader
                 : conservative == "centroid" ? Dilation::CentroidPush
                                              : Dilation::Auto;
    o.attributes = attributes;
    o.mode = parseVoxelMode(mode);
    o.gpuMemory = gpuMemory;
    return o;
}

uint64_t parseByteSize(const std::string& text, const std::string& option)
{
    const auto bad = [&] {
        return InvalidInput(fmt::format("{}: '{}' is not a size in bytes (a number, optionally with K, M, G or T)", option,
                                        text));
    };
    size_t end = 0;
    double v = 0;
    try {
        v = std::stod(text, &end);
    } catch (const std::exception&) {
        throw bad();
    }
    std::string unit = text.substr(end); // "G", "GiB", "GB", "B" or ""
    if (unit.size() > 2 && unit.compare(unit.size() - 2, 2, "iB") == 0) unit.resize(unit.size() - 2);
    else if (!unit.empty() && unit.back() == 'B') unit.pop_back();
    int shift = 0;
    if (unit == "K" || unit == "k") shift = 10;
    else if (unit == "M" || unit == "m") shift = 20;
    else if (unit == "G" || unit == "g") shift = 30;
    else if (unit == "T" || unit == "t") shift = 40;
    else if (!unit.empty()) throw bad();
    const double bytes = std::ldexp(v, shift);
    if (!std::isfinite(bytes) || bytes < 1 || bytes > 1e18) throw bad();
    return uint64_t(bytes);
}

void addGpuMemoryOption(CLI::App& cmd, BackendArgs& a)
{
    cmd.add_option_function<std::string>(
        "--gpu-memory", [&a](const std::string& t) { a.gpuMemory = parseByteSize(t, "--gpu-memory"); },
        "GPU memory a voxelization may use (e.g. 8G, 512M); a grid that needs more is voxelized in tiles and "
        "merged, with the same voxels (default: what the device reports free)");
}

void addBackendOptions(CLI::App& cmd, BackendArgs& a)
{
    cmd.add_option("--backend", a.backend,
                   "auto (compute on a GPU, raster on llvmpipe: the faster there), raster, compute (GPU compute "
                   "shaders, the same voxels), or cpu (double-precision reference)")
        ->check(CLI::IsMember({"auto", "raster", "compute", "cpu"}))
        ->capture_default_str();
    cmd.add_option("--conservative", a.conservative,
                   "Raster dilation: auto, hardware (GL_NV_conservative_raster), shader, or centroid (the seed "
                   "report's vertex push; a benchmark baseline that misses voxels)")
        ->check(CLI::IsMember({"auto", "hardware", "shader", "centroid"}))
        ->capture_default_str();
    cmd.add_option("--device", a.device, "EGL device: auto, hardware, software or an index (env SVO_EGL_DEVICE)");
    cmd.add_flag("--gl-debug", a.glDebug, "Print GL debug messages");
}

void addModeOption(CLI::App& cmd, BackendArgs& a)
{
    cmd.add_option("--mode", a.mode,
                   "conservative (every voxel whose cube meets a triangle; 26-separating) or thin (every voxel one "
                   "of whose three axis-aligned centre segments meets a triangle; 6-separating)")
        ->check(CLI::IsMember({"conservative", "thin"}))
        ->capture_default_str();
}

void addAttributeOption(CLI::App& cmd, BackendArgs& a)
{
    cmd.add_option_function<std::vector<std::string>>(
           "--attributes",
           [&a](const std::vector<std::string>& names) {
               for (const auto& n : names)
                   a.attributes |= n == "normal" ? kNormals : n == "triangle" ? kTriangles : kColors;
           },
           "Per-voxel channels: normal, triangle (smallest triangle id), color (needs vertex colours)")
        ->delimiter(',')
        ->check(CLI::IsMember({"normal", "triangle", "color"}));
}

LevelSetOptions FieldArgs::levelSetOptions() const
{
    LevelSetOptions ls;
    ls.sign = SignOptions(sign == "parity"    ? SignMethod::Parity
                          : sign == "winding" ? SignMethod::Winding
                                              : SignMethod::Auto,
                          windingAccuracy.value_or(SignOptions{}.windingAccuracy));
    if (band) ls.exteriorBand = ls.interiorBand = *band;
    if (exteriorBand) ls.exteriorBand = *exteriorBand;
    if (interiorBand) ls.interiorBand = *interiorBand;
    return ls;
}

namespace {
/// A number option checked, as it is parsed, by the library's rule under the flag's name.
CLI::Option* addCheckedNumber(CLI::App& cmd, const std::string& flag, std::optional<double>& value,
                              void (*rule)(double, const std::string&), const std::string& help)
{
    return cmd.add_option_function<double>(
        flag,
        [&value, flag, rule](double v) {
            rule(v, flag);
            value = v;
        },
        help);
}
} // namespace

void addBandOptions(CLI::App& cmd, FieldArgs& a, const std::string& appliesTo)
{
    addCheckedNumber(cmd, "--band", a.band, checkBand,
                     "Band half width in voxels on both sides, 1 to 1000, " + appliesTo + " (default 3)");
    addCheckedNumber(cmd, "--exterior-band", a.exteriorBand, checkBand,
                     "Band width outside the surface, in voxels, 1 to 1000 (default 3)");
    addCheckedNumber(cmd, "--interior-band", a.interiorBand, checkBand,
                     "Band width inside the surface, in voxels, 1 to 1000 (default 3)");
}

void addSignOptions(CLI::App& cmd, FieldArgs& a, const std::string& appliesTo)
{
    cmd.add_option("--sign", a.sign,
                   "Inside/outside " + appliesTo +
                       ": auto (parity for closed, consistently oriented meshes, the winding number otherwise), "
                       "parity or winding (as asked)")
        ->check(CLI::IsMember({"auto", "parity", "winding"}));
    addCheckedNumber(cmd, "--winding-accuracy", a.windingAccuracy, checkWindingAccuracy,
                     "Winding numbers: tree nodes farther than this many radii use their far-field expansion (a "
                     "positive finite number, default 1.5; larger is slower and more exact; 1e300 evaluates every "
                     "triangle)");
}

bool bandsGiven(const CLI::App& cmd)
{
    return cmd.count("--band") || cmd.count("--exterior-band") || cmd.count("--interior-band");
}

void addGridOptions(CLI::App& cmd, int64_t& resolution, double& voxelSize)
{
    auto* res = cmd.add_option("-r,--resolution", resolution,
                               "Voxel size = longest bounding-box side / N (default 256); the result spans N+1 voxels "
                               "along that side (N+2 when the box ends exactly on voxel faces)");
    auto* size = cmd.add_option("--voxel-size", voxelSize, "Voxel size in world units");
    res->excludes(size);
}

std::string nonEmptyMeshPath(const std::string& value)
{
    return value.empty() ? "the mesh path is empty; give a mesh file, or no mesh for the built-in Cornell box" : "";
}

GridRequest gridRequest(const CLI::App& cmd, int64_t resolution, double voxelSize)
{
    const bool gotRes = cmd.count("--resolution") > 0, gotSize = cmd.count("--voxel-size") > 0;
    // The library's rules, under the flags' names (before any work).
    if (gotRes) checkResolution(double(resolution), "--resolution");
    if (gotSize) checkVoxelSize(voxelSize, "--voxel-size");
    GridRequest r;
    r.resolution = gotRes ? resolution : (gotSize ? 0 : 256);
    r.voxelSize = gotSize ? voxelSize : 0;
    return r;
}

CLI::Option* addOutputPath(CLI::App& cmd, const std::string& name, std::string& path, const std::string& help,
                           const std::vector<std::string>& extensions)
{
    return cmd.add_option(name, path, help)->check(
        [extensions](const std::string& value) -> std::string {
            if (value.empty()) return "the path is empty; give a file name";
            if (extensions.empty()) return "";
            std::string ext = std::filesystem::path(value).extension().string();
            std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
            if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) return "";
            std::string list;
            for (const auto& e : extensions) list += (list.empty() ? "" : ", ") + e;
            return fmt::format("{}: the name must end in {}, the format svo writes there", value, list);
        },
        "FILE");
}

GridOptions OutputArgs::gridOptions() const
{
    GridOptions g;
    g.topology = topology == "bool" ? GridOptions::Topology::Bool : GridOptions::Topology::Mask;
    g.fog = fog;
    return g;
}

void addOutputOptions(CLI::App& cmd, OutputArgs& a)
{
    cmd.add_option("--topology", a.topology, "Grid type of the topology: bool (BoolGrid, which python3-openvdb reads) or mask (MaskGrid)")
        ->check(CLI::IsMember({"mask", "bool"}))
        ->capture_default_str();
    cmd.add_flag("--fog", a.fog, "Also write a fog-volume FloatGrid 'density' (.vdb and .nvdb output)");
}

std::string backendLine(const VoxelizeStats& s)
{
    if (s.backend == "cpu") return "cpu (double-precision reference)";
    if (s.dilation.empty()) return fmt::format("{}, on {}", s.backend, s.device);
    return fmt::format("{}, {} dilation, on {}{}", s.backend, s.dilation, s.device,
                       s.dilation == "hardware" ? " + GL_NV_conservative_raster" : "");
}

std::string describeInput(const std::string& path, const LoadedOctree& lo, const VoxelizeStats& stats)
{
    switch (lo.kind) {
    case LoadedOctree::Kind::Svo: return fmt::format("{} (.svo)", path);
    case LoadedOctree::Kind::Vdb:
        return fmt::format("{}, grid '{}' ({}, {} bricks{})", path, lo.gridName, lo.gridType,
                           thousands(lo.octree.bricks.size()),
                           lo.tilesExpanded ? fmt::format(", {} active tiles expanded", lo.tilesExpanded) : "");
    case LoadedOctree::Kind::Mesh: break;
    }
    return fmt::format("{} ({} triangles), voxelized by {}", path, thousands(lo.mesh ? lo.mesh->triangles.size() : 0),
                       backendLine(stats));
}

std::string describeOutput(const std::string& path, const WriteReport& r, const GridOptions& g)
{
    if (r.format == OutputFormat::Svo) return fmt::format("{} ({:.2f} MB octree)", path, double(r.bytes) / 1e6);
    return fmt::format("{} ({:.2f} MB, {} {} leaves{}{})", path, double(r.bytes) / 1e6, thousands(r.leaves),
                       g.topology == GridOptions::Topology::Bool ? "bool" : "mask", g.fog ? ", with fog grid" : "",
                       r.format == OutputFormat::NanoVdb ? ", NanoVDB" : "");
}

std::string printable(const std::string& text)
{
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c == 0x7f) out += fmt::format("\\x{:02x}", c);
        else out += ch;
    }
    return out;
}

std::string errorMessage(const std::exception& e)
{
    const auto* error = dynamic_cast<const Error*>(&e);
    if (!error) return e.what();
    return error->message([](const std::string& identifier) { return std::string(flagFor(identifier)); });
}

void printWarnings(const std::vector<std::string>& warnings)
{
    // The library's warnings name no options (VoxelizeStats::warnings): printed as they are.
    for (const auto& w : warnings) fmt::print(stderr, "svo: warning: {}\n", printable(w));
}

void printStages(const std::vector<StageTime>& stages)
{
    for (const auto& s : stages)
        fmt::print("  {:<20} {:>10} {:>10.2f}\n", s.name, s.gpuMs < 0 ? std::string("-") : fmt::format("{:.3f}", s.gpuMs),
                   s.wallMs);
}

void printStartup(const StartupStats& s)
{
    if (s.eglMs > 0) fmt::print("  {:<20} {:>10} {:>10.2f}\n", "EGL set-up", "-", s.eglMs);
    if (s.programsCompiled + s.programsLoaded == 0) return;
    std::string what = fmt::format("{} compiled", s.programsCompiled);
    if (s.programsLoaded) what = fmt::format("{} cached, {}", s.programsLoaded, what);
    fmt::print("  {:<20} {:>10} {:>10.2f}   ({}{})\n", "programs", "-", s.programMs, what,
               s.programCache.empty() ? "; no program cache" : "");
}

void printOctreeSummary(const Octree& o)
{
    const OctreeStats st = octreeStats(o);
    const auto t = o.grid.translation();
    fmt::print("  {:<12} {} x {} x {} voxels from index ({}, {}, {}), voxel size {:.6g}, translation ({:.6g}, {:.6g}, "
               "{:.6g})\n",
               "grid", o.grid.dims[0], o.grid.dims[1], o.grid.dims[2], o.grid.anchor[0], o.grid.anchor[1],
               o.grid.anchor[2], o.grid.voxelSize, t[0], t[1], t[2]);
    fmt::print("  {:<12} {} (root 0 .. bricks {}); root covers {}^3 voxels\n", "levels", o.brickLevel + 1, o.brickLevel,
               8u << o.brickLevel);
    fmt::print("  {:<12} {:>6} {:>14} {:>14}\n", "", "level", "nodes", "occupied");
    for (size_t l = 0; l < st.nodesPerLevel.size(); ++l)
        fmt::print("  {:<12} {:>6} {:>14} {:>14}\n", "", l, thousands(st.nodesPerLevel[l]),
                   thousands(st.occupiedPerLevel[l]));
    fmt::print("  {:<12} {}\n", "bricks", thousands(st.bricks));
    fmt::print("  {:<12} {}\n", "voxels", thousands(st.voxels));
    fmt::print("  {:<12} {} (nodes {} + bricks {})\n", "bytes", thousands(st.bytes),
               thousands(o.nodes.size() * sizeof(OctreeNode)), thousands(o.bricks.size() * sizeof(Brick)));
    fmt::print("  {:<12} {:.3f}\n", "bytes/voxel", st.bytesPerVoxel());
    fmt::print("  {:<12} {:.3f} of brick voxels occupied\n", "fill ratio", st.fillRatio());
}

std::string thousands(uint64_t n)
{
    std::string s = std::to_string(n);
    for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
    return s;
}

void checkOutputs(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs)
{
    for (size_t i = 0; i < outputs.size(); ++i) {
        for (const auto& in : inputs)
            if (sameFile(outputs[i], in))
                throw InvalidInput(fmt::format("{}: is the input {}; svo never writes over an input", outputs[i], in));
        for (size_t j = i + 1; j < outputs.size(); ++j)
            if (sameFile(outputs[i], outputs[j]))
                throw InvalidInput(fmt::format("{}: given for two outputs; each output needs its own file", outputs[i]));
    }
}

} // namespace svo::app
