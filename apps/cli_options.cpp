#include "cli_options.h"
#include "option_flags.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <filesystem>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/core/city_scene.h"
#include "svo/core/error.h"
#include "svo/core/octree.h"
#include "progress.h"
#include "svo/gl/view_request.h"
#include "svo/vdb_io/nanovdb_file.h"
#include "svo/voxelizer.h"
#ifdef SVO_WITH_VALIDATE
#include "svo/validate/report.h"
#endif

namespace svo::app {

VoxelizeOptions BackendArgs::voxelizeOptions() const
{
    VoxelizeOptions o;
    static_cast<VoxelizeSettings&>(o) = settings;
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

namespace {

/// Adds each option a library struct declares (forEachOption) as a flag bound to its field.
class FlagAdder {
public:
    FlagAdder(CLI::App& cmd, std::vector<std::string_view> keywords, std::string appliesTo)
        : cmd_(cmd), keywords_(std::move(keywords)), appliesTo_(std::move(appliesTo))
    {
    }

    void operator()(const OptionInfo& info, bool& value)
    {
        if (!wanted(info)) return;
        if (!value) {
            cmd_.add_flag(flagNames(info), value, help(info));
            return;
        }
        // On by default: the flag turns it off, and its name must say so.
        if (flagOf(info).rfind("--no-", 0) != 0)
            throw std::logic_error("svo: " + std::string(info.identifier) + " is on by default; its flag must be --no-...");
        cmd_.add_flag_callback(flagNames(info), [&value] { value = false; }, help(info) + ": on by default, this flag turns it off");
    }
    void operator()(const OptionInfo& info, std::string& value)
    {
        if (wanted(info)) cmd_.add_option(flagNames(info), value, help(info));
    }
    template <typename E, typename = decltype(enumNames(E{}))>
    void operator()(const OptionInfo& info, E& value)
    {
        if (!wanted(info)) return;
        const std::string flag = flagOf(info);
        cmd_.add_option_function<std::string>(
               flagNames(info), [&value, flag](const std::string& name) { value = parse<E>(name, flag); }, help(info))
            ->check(CLI::IsMember(names<E>()))
            ->default_str(std::string(nameOf(value)));
    }
    void operator()(const OptionInfo& info, CheckedNumber number)
    {
        if (!wanted(info)) return;
        const std::string flag = flagOf(info);
        cmd_.add_option_function<double>(
               flagNames(info),
               [number, flag](double v) {
                   number.rule(v, flag); // the library's rule, under the flag's name
                   number.value = v;
               },
               help(info))
            ->default_str(fmt::format("{}", number.value));
    }
    template <typename Int, typename Read>
    void operator()(const OptionInfo& info, CheckedInteger<Int, Read> number)
    {
        if (!wanted(info)) return;
        const std::string flag = flagOf(info);
        // Read as its declared type (CLI11 refuses what that cannot hold), then the library's rule.
        CLI::Option* option = cmd_.add_option_function<Read>(
                                      flagNames(info),
                                      [number, flag](Read v) {
                                          number.rule(int64_t(v), flag);
                                          number.value = Int(v);
                                      },
                                      help(info))
                                  ->default_str(fmt::format("{}", number.value));
        // CLI11 reads "-1" into an unsigned type as its largest value: refused instead.
        if constexpr (std::is_unsigned_v<Read>)
            option->check(
                [](const std::string& text) -> std::string {
                    const size_t first = text.find_first_not_of(" \t");
                    if (first == std::string::npos || text[first] != '-') return "";
                    return fmt::format("'{}' is negative; give a whole number from 0 to {}", text,
                                       std::numeric_limits<Read>::max());
                },
                "NON-NEGATIVE");
    }
    void operator()(const OptionInfo& info, NamedBool choice)
    {
        if (!wanted(info)) return;
        cmd_.add_option_function<std::string>(
               flagNames(info), [choice](const std::string& name) { choice.value = name == choice.trueName; },
               help(info))
            ->check(CLI::IsMember({std::string(choice.falseName), std::string(choice.trueName)}))
            ->default_str(std::string(choice.value ? choice.trueName : choice.falseName));
    }
    template <typename T>
    void operator()(const OptionInfo& info, OptionalNumber<T> number)
    {
        if (!wanted(info)) return;
        const std::string flag = flagOf(info);
        cmd_.add_option_function<double>(
            flagNames(info),
            [number, flag](double v) {
                number.rule(v, flag); // the library's rule, under the flag's name
                number.value = T(v);
            },
            help(info));
    }
    void operator()(const OptionInfo& info, ByteCount count)
    {
        if (!wanted(info)) return;
        const std::string flag = flagOf(info);
        cmd_.add_option_function<std::string>(
            flagNames(info), [count, flag](const std::string& text) { count.bytes = parseByteSize(text, flag); }, help(info));
    }
    void operator()(const OptionInfo& info, RegionOption option)
    {
        if (!wanted(info)) return;
        const std::string flag = flagOf(info);
        cmd_.add_option_function<std::vector<int64_t>>(
               flagNames(info),
               [option, flag](const std::vector<int64_t>& v) {
                   if (v.size() != 6)
                       throw InvalidInput(flag, fmt::format("takes six whole numbers x0,y0,z0,x1,y1,z1, got {}", v.size()));
                   option.region = regionFrom({v[0], v[1], v[2], v[3], v[4], v[5]}, flag);
               },
               help(info))
            ->delimiter(',')
            ->type_name("X0,Y0,Z0,X1,Y1,Z1");
    }
    void operator()(const OptionInfo& info, ChannelSet channels)
    {
        if (!wanted(info)) return;
        const std::string flag = flagOf(info);
        cmd_.add_option_function<std::vector<std::string>>(
               flagNames(info),
               [channels, flag](const std::vector<std::string>& names) {
                   for (const auto& n : names) channels.bits |= parse<AttributeChannel>(n, flag);
               },
               help(info))
            ->delimiter(',')
            ->check(CLI::IsMember(names<AttributeChannel>()));
    }

private:
    bool wanted(const OptionInfo& info) const
    {
        return keywords_.empty() || std::find(keywords_.begin(), keywords_.end(), info.keyword) != keywords_.end();
    }
    std::string help(const OptionInfo& info) const
    {
        return appliesTo_.empty() ? std::string(info.doc) : fmt::format("{}, {}", info.doc, appliesTo_);
    }

    CLI::App& cmd_;
    std::vector<std::string_view> keywords_;
    std::string appliesTo_;
};

} // namespace

template <typename Options>
void addOptions(CLI::App& cmd, Options& options, std::vector<std::string_view> keywords, const std::string& appliesTo)
{
    forEachOption(options, FlagAdder(cmd, std::move(keywords), appliesTo));
}
template void addOptions(CLI::App&, VoxelizeSettings&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, DeviceOptions&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, LevelSetOptions&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, GridOptions&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, gl::ViewRequest&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, gl::AmbientOcclusion&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, gl::Illumination&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, GridRequest&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, CityOptions&, std::vector<std::string_view>, const std::string&);
template void addOptions(CLI::App&, OutputHabits&, std::vector<std::string_view>, const std::string&);
#ifdef SVO_WITH_VALIDATE
template void addOptions(CLI::App&, validate::ReportOptions&, std::vector<std::string_view>, const std::string&);
#endif

namespace {
// The running command's habits: one command runs in a process, and its
// progress lines and warnings are printed from deep inside calls.
bool quietRun = false;
bool verboseRun = false;
} // namespace

void addOutputHabits(CLI::App& cmd, OutputHabits& habits)
{
    addOptions(cmd, habits);
    cmd.get_option("--quiet")->excludes("--verbose");
    cmd.parse_complete_callback([&habits] {
        quietRun = habits.quiet;
        verboseRun = habits.verbose;
        setProgressShown(!habits.quiet);
    });
}

bool summaryShown() { return !quietRun; }
bool reportShown() { return verboseRun; }

void checkClobber(const OutputHabits& habits, const std::vector<std::string>& outputs)
{
    if (!habits.noClobber) return;
    for (const auto& path : outputs) {
        std::error_code ec;
        if (!path.empty() && std::filesystem::exists(std::filesystem::symlink_status(path, ec)))
            throw IoError(fmt::format("{}: exists, and --no-clobber refuses to replace it", path));
    }
}

std::string seconds(double ms) { return ms < 1000 ? fmt::format("{:.0f} ms", ms) : fmt::format("{:.2f} s", ms / 1000); }

void addBackendOptions(CLI::App& cmd, BackendArgs& a)
{
    addOptions(cmd, a.settings, {"backend", "conservative"});
    addOptions(cmd, a.device);
}

LevelSetOptions FieldArgs::levelSetOptions(const CLI::App& cmd) const
{
    LevelSetOptions ls = options;
    if (band && !cmd.count("--exterior-band")) ls.exteriorBand = *band;
    if (band && !cmd.count("--interior-band")) ls.interiorBand = *band;
    return ls;
}

void addBandOptions(CLI::App& cmd, FieldArgs& a, const std::string& appliesTo)
{
    cmd.add_option_function<double>(
        "--band",
        [&a](double v) {
            checkBand(v, "--band");
            a.band = v;
        },
        "Band half width in voxels on both sides, 1 to 1000, " + appliesTo + " (default 3)");
    addOptions(cmd, a.options, {"exterior_band", "interior_band"});
}

bool bandsGiven(const CLI::App& cmd)
{
    return cmd.count("--band") || cmd.count("--exterior-band") || cmd.count("--interior-band");
}

void addGridOptions(CLI::App& cmd, GridRequest& request)
{
    addOptions(cmd, request);
    cmd.get_option("--resolution")->excludes("--voxel-size");
}

void addGridNameOption(CLI::App& cmd, std::string& gridName)
{
    cmd.add_option("--grid", gridName,
                   "Grid of a .vdb or .nvdb input (default: the first level set in name order, else the first "
                   "surface, solid, fog or distance grid, else the first grid)");
}

std::string nonEmptyMeshPath(const std::string& value)
{
    return value.empty() ? "the mesh path is empty; give a mesh file, or no mesh for the built-in Cornell box" : "";
}

GridRequest gridRequest(const GridRequest& given)
{
    GridRequest r = given; // each number checked by its rule as it was parsed
    if (r.resolution == 0 && r.voxelSize == 0) r.resolution = kDefaultResolution;
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

void addOutputOptions(CLI::App& cmd, OutputArgs& a) { addOptions(cmd, a.grids); }

void checkCodec(const OutputArgs& a, const std::string& output)
{
    if (a.grids.codec == vdb::NanoCodec::None) return;
    if (output.empty() || outputFormat(output) != OutputFormat::NanoVdb)
        throw InvalidInput(fmt::format("{}: --codec applies to .nvdb output", output.empty() ? "no output" : output));
    if (!vdb::nanoCodecAvailable(a.grids.codec))
        throw Unsupported(fmt::format("{}: this svo was built without the {} codec (libblosc)", output,
                                      nameOf(a.grids.codec)));
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
    return error->message([](const std::string& identifier) { return flagFor(identifier); });
}

void printWarnings(const std::vector<std::string>& warnings)
{
    // The library's warnings name no options (VoxelizeStats::warnings): printed as they are.
    if (quietRun) return;
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
