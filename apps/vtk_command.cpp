// svo vtk INPUT -o OUT.htg|.vtu|.vtp [--levels A..B] [--png out.png]
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "library_call.h"
#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "vtk_export.h"
#include "xvfb.h"
#include "svo/core/mesh_io.h"

namespace svo::app {
namespace {

struct VtkArgs {
    std::string input, output, png, levels, gridName;
    GridRequest grid; ///< -r/--resolution or --voxel-size
    BackendArgs backend;
    int width = 1600;
    OutputHabits habits; ///< -q, -v, --no-clobber
};

/// "A..B", "A..", "..B" or "A".
LevelRange parseLevels(const std::string& text)
{
    LevelRange r;
    if (text.empty()) return r;
    auto number = [&](const std::string& s) -> uint32_t {
        try {
            size_t used = 0;
            const long v = std::stol(s, &used);
            if (used == s.size() && v >= 0 && v < 64) return uint32_t(v);
        } catch (const std::exception&) {
        }
        throw InvalidInput(fmt::format("--levels '{}': expected A..B with levels from 0", text));
    };
    const auto dots = text.find("..");
    if (dots == std::string::npos) {
        r.first = r.last = number(text);
    } else {
        if (dots > 0) r.first = number(text.substr(0, dots));
        if (dots + 2 < text.size()) r.last = number(text.substr(dots + 2));
    }
    if (r.first > r.last) throw InvalidInput(fmt::format("--levels '{}': the first level is past the last", text));
    return r;
}

void runVtk(const VtkArgs& a)
{
    if (a.output.empty() && a.png.empty()) throw InvalidInput("give -o OUT (.htg, .vtu or .vtp), --png PICTURE, or both");
    const LevelRange levels = parseLevels(a.levels);
    std::string ext;
    if (!a.output.empty()) {
        ext = std::filesystem::path(a.output).extension().string();
        if (ext != ".htg" && ext != ".vtu" && ext != ".vtp")
            throw IoError(fmt::format("{}: the output must end in .htg (hyper tree grid), .vtu (voxel cells) or .vtp "
                                      "(node outlines)",
                                      a.output));
        checkWritable(a.output);
    }
    checkOutputs({a.input}, {a.output, a.png});
    checkClobber(a.habits, {a.output, a.png});
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return seconds(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    };
    if (!a.png.empty()) {
        checkWritable(a.png);
        requireDisplay(); // before loading and voxelizing
    }
    const VtkExport& vtk = vtkExport(); // before any work: a missing module is an error up front
    OutputBatch outputs({a.output, a.png}); // both in place together at the end, or neither
    LibraryCall call(a.backend, "building the octree");
    const LoadedOctree lo = call.load(a.input, a.gridName, gridRequest(a.grid));
    // Printed once the outputs are in place: the report (-v), or a line per file written.
    const bool report = reportShown();
    std::string printed;
    if (report) {
        printed += "svo vtk\n";
        printed += fmt::format("  {:<8} {}\n", "input", describeInput(a.input, lo, call.stats));
        printed += fmt::format("  {:<8} {} voxels, {} levels (bricks at {}; levels {}..{} split bricks down to voxels)\n",
                               "octree", lo.octree.voxelCount(), lo.octree.brickLevel + 1, lo.octree.brickLevel,
                               lo.octree.brickLevel + 1, lo.octree.brickLevel + 3);
    }
    if (!a.png.empty()) {
        Progress p("rendering " + a.png);
        PictureOptions po;
        po.width = a.width;
        po.height = a.width * 3 / 4;
        po.mesh = lo.mesh ? &*lo.mesh : nullptr;
        po.outlineLevels = levels;
        vtk.renderPicture(a.png, lo.octree, po);
        printed += report ? fmt::format("  {:<8} {} ({} x {})\n", "picture", a.png, po.width, po.height)
                          : fmt::format("svo vtk: wrote {} ({} x {} picture, {} voxels) in {}\n", a.png, po.width,
                                        po.height, thousands(lo.octree.voxelCount()), elapsed());
    }
    if (!a.output.empty()) {
        Progress p("writing " + a.output);
        if (ext == ".htg") vtk.writeHyperTreeGrid(a.output, lo.octree, levels);
        if (ext == ".vtu") vtk.writeVoxelCells(a.output, lo.octree);
        if (ext == ".vtp") vtk.writeNodeOutlines(a.output, lo.octree, levels);
        printed += report ? fmt::format("  {:<8} {}\n", "output", a.output)
                          : fmt::format("svo vtk: wrote {} ({}, {} voxels) in {}\n", a.output,
                                        ext == ".htg"   ? "hyper tree grid"
                                        : ext == ".vtu" ? "voxel cells"
                                                        : "node outlines",
                                        thousands(lo.octree.voxelCount()), elapsed());
    }
    outputs.commit();
    if (summaryShown()) fmt::print("{}", printed);
}

} // namespace

void addVtkCommand(CLI::App& app)
{
    auto args = std::make_shared<VtkArgs>();
    CLI::App* cmd = app.add_subcommand("vtk", "Write an octree (of a mesh, .vdb or .svo) for VTK/ParaView, or a picture");
    cmd->add_option("input", args->input,
                    fmt::format("A mesh ({}; voxelized first), .vdb or .svo", supportedMeshExtensions()))
        ->required();
    addOutputPath(*cmd, "-o,--output", args->output, ".htg hyper tree grid, .vtu voxel cells, or .vtp node outlines");
    cmd->add_option("--levels", args->levels, "Levels A..B: deepest level of the .htg, outline levels of .vtp/--png");
    addOutputPath(*cmd, "--png", args->png, "Also render voxels, outlines and mesh to a PNG (uses Xvfb if no DISPLAY)", {".png"});
    cmd->add_option("--size", args->width, "Picture width in pixels; the height is 3/4 of it")
        ->check(CLI::Range(64, 8192))
        ->capture_default_str();
    addGridNameOption(*cmd, args->gridName);
    addGridOptions(*cmd, args->grid);
    addBackendOptions(*cmd, args->backend);
    addOutputHabits(*cmd, args->habits);
    cmd->callback([args] { runVtk(*args); });
}

} // namespace svo::app
