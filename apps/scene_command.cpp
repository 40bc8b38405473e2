// svo scene NAME -o out.off|out.obj: the generated scenes as mesh files, for peers and benchmarks.
#include <CLI/CLI.hpp>
#include <chrono>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "cli_options.h"
#include "svo/core/atomic_file.h"
#include "svo/core/city_scene.h"
#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"

namespace svo::app {
namespace {

struct SceneArgs {
    std::string name, output;
    int level = 8;
    CityOptions city;
    OutputHabits habits; ///< -q, -v (the summary is the whole report), --no-clobber
};

TriangleMesh makeScene(const SceneArgs& a)
{
    if (a.name == "cornell") return cornellBox();
    if (a.name == "spheres") return sphereGrid();
    if (a.name == "city") return cityScene(a.city);
    return icosphere({0, 0, 0}, 1.0, a.level);
}

void runScene(const CLI::App& cmd, const SceneArgs& a)
{
    for (const char* flag : {"--triangles", "--seed"})
        if (a.name != "city" && cmd.count(flag)) throw InvalidInput(fmt::format("{} applies to the city scene", flag));
    checkClobber(a.habits, {a.output});
    const auto start = std::chrono::steady_clock::now();
    const TriangleMesh mesh = makeScene(a);
    OutputBatch outputs({a.output}); // in place at the very end (atomic_file.h)
    writeMesh(a.output, mesh);
    outputs.commit();
    if (summaryShown())
        fmt::print("svo scene: {} ({} triangles, {} vertices) -> {} in {}\n", mesh.source, thousands(mesh.triangles.size()),
                   thousands(mesh.positions.size()), a.output,
                   seconds(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()));
}

} // namespace

void addSceneCommand(CLI::App& app)
{
    auto args = std::make_shared<SceneArgs>();
    CLI::App* cmd = app.add_subcommand("scene", "Write a generated scene as a .off or .obj mesh (for other tools and benchmarks)");
    cmd->add_option("name", args->name,
                    "cornell (the built-in Cornell box, 3,136 triangles), spheres (a PBR-demo-like grid, 54,720), "
                    "icosphere (20 * 4^level) or city (a procedural city of --triangles, from --seed)")
        ->required()
        ->check(CLI::IsMember({"cornell", "spheres", "icosphere", "city"}));
    addOutputPath(*cmd, "-o,--output", args->output, "Output .off or .obj", {".off", ".obj"})->required();
    cmd->add_option("--level", args->level, "Icosphere subdivisions (8: 1,310,720 triangles)")
        ->check(CLI::Range(0, 10))
        ->capture_default_str();
    addOptions(*cmd, args->city);
    addOutputHabits(*cmd, args->habits);
    cmd->callback([cmd, args] { runScene(*cmd, *args); });
}

} // namespace svo::app
