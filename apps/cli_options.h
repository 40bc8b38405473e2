#pragma once
/// @file cli_options.h
/// What the subcommands share: options that become library arguments, and
/// the words they print. The work itself is the library's (svo/svo.h).
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "svo/core/field_options.h"
#include "svo/core/grid.h"
#include "svo/core/octree.h"
#include "svo/vdb_io/grid_options.h"
#include "svo/gl/device_options.h"
#include "svo/gl/startup_stats.h"
#include "svo/gl/voxelize_settings.h"
#include "svo/gl/voxelize_stats.h"
#include "svo/load_octree.h"
#include "svo/vdb_io/octree_files.h"
#include "svo/core/option_info.h"

namespace CLI {
class App;
class Option;
} // namespace CLI

namespace svo {
class Voxelizer;
struct VoxelizeOptions;
} // namespace svo

namespace svo::app {

/// @brief Adds a flag for each option of @a options (declared once beside the
/// library struct: svo/core/option_info.h), bound to its field, with the
/// field's current value as the default shown.
/// @param keywords  only these options (all when empty)
/// @param appliesTo ends each flag's help text ("for --sdf")
template <typename Options>
void addOptions(CLI::App& cmd, Options& options, std::vector<std::string_view> keywords = {},
                const std::string& appliesTo = "");

/// The voxelization and device options of a command that voxelizes.
struct BackendArgs {
    VoxelizeSettings settings;
    DeviceOptions device;
    /// The options these arguments ask for (no interrupter, no statistics yet).
    VoxelizeOptions voxelizeOptions() const;
};
/// --backend, --conservative, --device, --gl-debug, --program-cache.
void addBackendOptions(CLI::App& cmd, BackendArgs& args);
/// Bytes from "1073741824", "512M", "1.5G", "2GiB" (K, M, G, T: powers of 1024).
/// Throws svo::Error naming `option` for anything else, or for 0.
uint64_t parseByteSize(const std::string& text, const std::string& option);

/// The level-set options `svo voxelize` and `svo validate --sdf` share, and
/// --band, which sets both bands (the command line's own shorthand).
struct FieldArgs {
    LevelSetOptions options;
    std::optional<double> band; ///< --band: both bands, unless one is given on its own
    /// The options with --band applied.
    LevelSetOptions levelSetOptions(const CLI::App& cmd) const;
};
/// --band, --exterior-band, --interior-band; `appliesTo` ends the help text ("for --sdf").
void addBandOptions(CLI::App& cmd, FieldArgs& args, const std::string& appliesTo);
/// Whether any of --band, --exterior-band, --interior-band was given.
bool bandsGiven(const CLI::App& cmd);

/// CLI11 check for an input mesh argument: an empty path is a mistake (an
/// unset variable, say), not the built-in scene.
std::string nonEmptyMeshPath(const std::string& value);

/// -r/--resolution and --voxel-size (mutually exclusive).
void addGridOptions(CLI::App& cmd, GridRequest& request);
/// --grid: which grid of a .vdb or .nvdb input (loadOctree's gridName).
void addGridNameOption(CLI::App& cmd, std::string& gridName);
/// The request those options make; resolution 256 when neither is given.
GridRequest gridRequest(const GridRequest& given);

/// --topology and --fog. The command line's default topology is bool, which python3-openvdb reads.
struct OutputArgs {
    GridOptions grids = [] {
        GridOptions g;
        g.topology = GridOptions::Topology::Bool;
        return g;
    }();
};
void addOutputOptions(CLI::App& cmd, OutputArgs& args);
/// @brief Refuses, before any work, a --codec other than none for an output
/// that is not .nvdb, or one this build cannot write.
/// @throw svo::InvalidInput naming the output, or svo::Unsupported
void checkCodec(const OutputArgs& args, const std::string& output);

/// @brief -q, -v and --no-clobber: how much a command that writes files
/// prints, and whether it may replace an output that exists. Outputs are
/// replaced by default, as vdb_tool replaces them; inputs never are
/// (checkOutputs).
struct OutputHabits {
    bool quiet = false;     ///< -q: errors only on stderr, nothing on stdout, no progress
    bool verbose = false;   ///< -v: the stage table instead of one summary line
    bool noClobber = false; ///< --no-clobber: refuse, before any work, an output that exists
};

/// @brief The flags of OutputHabits, declared once for every command that writes.
template <typename Visit>
void forEachOption(OutputHabits& h, Visit&& visit)
{
    visit(OptionInfo{"OutputHabits::quiet", "quiet", "Print errors only: no summary, no warnings, no progress", "-q,--quiet"},
          h.quiet);
    visit(OptionInfo{"OutputHabits::verbose", "verbose",
                     "Print the whole report (stages and their GPU and wall times) instead of one summary line",
                     "-v,--verbose"},
          h.verbose);
    visit(OptionInfo{"OutputHabits::noClobber", "no_clobber",
                     "Refuse to replace an output file that exists (by default outputs are replaced; inputs never are)"},
          h.noClobber);
}
/// -q, -v (which exclude each other) and --no-clobber; the parsed flags take
/// effect for progress lines and warnings as the command's callback starts.
void addOutputHabits(CLI::App& cmd, OutputHabits& habits);
/// @brief Whether the running command prints its summary (not -q).
bool summaryShown();
/// @brief Whether the running command prints its whole report (-v).
bool reportShown();
/// @brief With --no-clobber, refuses the first of @a outputs that exists
/// (empty paths skipped): svo::IoError naming it, before any work.
void checkClobber(const OutputHabits& habits, const std::vector<std::string>& outputs);
/// @brief "1.23 s" or "345 ms": a run's wall time for a summary line.
std::string seconds(double ms);

/// A path option for a file svo writes. Refuses an empty path (`-o ''`), and
/// when `extensions` are given (lower case, with the dot), a name whose
/// extension is none of them, so that a file's name never hides its format.
CLI::Option* addOutputPath(CLI::App& cmd, const std::string& name, std::string& path, const std::string& help,
                           const std::vector<std::string>& extensions = {});

/// "raster, hardware dilation, on <device>" or "cpu (double-precision reference)".
std::string backendLine(const VoxelizeStats& stats);
/// One line about an input read by loadOctree.
std::string describeInput(const std::string& path, const LoadedOctree& loaded, const VoxelizeStats& stats);
/// "out.vdb (1.23 MB, 345 mask leaves)".
std::string describeOutput(const std::string& path, const WriteReport& report, const GridOptions& grids);

/// Prints the warnings a call gathered, as "svo: warning: ...".
void printWarnings(const std::vector<std::string>& warnings);
/// Prints levels, nodes per level, bricks, bytes, bytes per voxel, fill ratio.
void printOctreeSummary(const Octree& octree);
/// Prints stage, GPU ms and wall ms rows.
void printStages(const std::vector<StageTime>& stages);
/// The start-up rows of a stage table: EGL set-up and programs, where the call paid for them.
void printStartup(const StartupStats& startup);

/// The text with control bytes (newlines included) and DEL written as \xNN, so
/// that a message quoting a damaged file stays one line and cannot drive the
/// terminal. UTF-8 passes unchanged.
std::string printable(const std::string& text);
/// An exception's message for the command line: an svo::Error's with each
/// option it names written as its flag (option_flags.h: the library writes
/// AmbientOcclusion::volumeResolution, the command line --light-volume), so
/// "<flag> <detail>" for an error about one option; any other's what().
std::string errorMessage(const std::exception& e);

/// 1234567 -> "1,234,567"
std::string thousands(uint64_t n);
/// Throws svo::Error when an output is the same file as an input (however
/// the path is spelled: links, `./`, `..`) or as another output. Empty
/// paths (options not given) are skipped.
void checkOutputs(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs);

} // namespace svo::app
