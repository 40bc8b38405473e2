// The svo command's numbers: each option is checked once, by the library's
// rule for it, under the flag's name; NaN never becomes a default.
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <sys/wait.h>

#include <fmt/format.h>

#include "option_flags.h"
#include "run_shell.h"
#include "svo/gl/octree_view.h"
#include "svo/gl/view_request.h"
#include "svo/vdb_io/grid_options.h"
#include "svo/voxelizer.h"
#include "temp_dir.h"

namespace {

svo::test::Run runSvo(const std::string& args) { return svo::test::runShell(std::string(SVO_EXE) + " " + args); }

/// A closed tetrahedron, so that --sdf runs have an inside.
std::string tetrahedron(const svo::test::TempDir& dir)
{
    const std::string path = dir.path("tet.obj");
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    return path;
}

/// Exit 1 with exactly one line that holds `message`.
void expectRefused(const std::string& args, const std::string& message)
{
    const auto r = runSvo(args);
    EXPECT_EQ(r.code, 1) << args << "\n" << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << args << "\n" << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << args << "\n" << r.out;
}

TEST(CliOptions, NanBandsAreRefusedNotReplacedByTheDefault)
{
    svo::test::TempDir dir("cli_options");
    const std::string mesh = tetrahedron(dir), out = " -r 8 -o " + dir.path("x.vdb");
    const std::string rule = ": a band is a number of voxels from 1 to 1000";
    expectRefused("voxelize " + mesh + out + " --sdf --band nan", "--band nan" + rule);
    expectRefused("voxelize " + mesh + out + " --sdf --exterior-band nan", "--exterior-band nan" + rule);
    expectRefused("voxelize " + mesh + out + " --sdf --interior-band nan", "--interior-band nan" + rule);
    expectRefused("voxelize " + mesh + out + " --udf --band nan", "--band nan" + rule);
    expectRefused("voxelize " + mesh + out + " --sdf --band 0.5", "--band 0.5" + rule);
    expectRefused("voxelize " + mesh + out + " --sdf --band inf", "--band inf" + rule);
    EXPECT_FALSE(std::filesystem::exists(dir.path("x.vdb")));
}

TEST(CliOptions, WindingAccuracyIsRefusedInOneShortLineAsPythonRefusesIt)
{
    svo::test::TempDir dir("cli_options");
    const std::string args = "voxelize " + tetrahedron(dir) + " -r 8 -o " + dir.path("x.vdb") + " --sdf";
    const std::string rule = ": the winding accuracy is a positive finite number";
    for (const std::string v : {"0", "-1", "nan", "inf"}) {
        expectRefused(args + " --winding-accuracy " + v, "--winding-accuracy " + v + rule);
        const auto r = runSvo(args + " --winding-accuracy " + v);
        EXPECT_LT(r.out.size(), 240u) << r.out; // once a 310-digit range
    }
}

TEST(CliOptions, OrthoThatIsNotPositiveIsRefusedNotDrawnInPerspective)
{
    svo::test::TempDir dir("cli_options");
    const std::string args = "view " + tetrahedron(dir) + " -r 8 --size 32x24 --screenshot " + dir.path("v.png");
    const std::string rule = ": an orthographic view spans a positive finite number of world units";
    for (const std::string v : {"0", "-1", "nan", "inf"}) expectRefused(args + " --ortho " + v, "--ortho " + v + rule);
    expectRefused(args + " --fov nan", "--fov nan: a field of view is between 0 and 180 degrees");
    expectRefused(args + " --fov 180", "--fov 180: a field of view");
    EXPECT_FALSE(std::filesystem::exists(dir.path("v.png")));
    const auto ok = runSvo(args + " -v --ortho 2");
    EXPECT_EQ(ok.code, 0) << ok.out;
    EXPECT_NE(ok.out.find("orthographic 2"), std::string::npos) << ok.out;
}

// Without SVO_WITH_VALIDATE, tests/CMakeLists.txt filters out CliOptions.Validate*.
TEST(CliOptions, ValidateRefusesANegativeWorstAndANanBand)
{
    svo::test::TempDir dir("cli_options");
    expectRefused("validate " + tetrahedron(dir) + " -r 8 --sdf --band nan",
                  "--band nan: a band is a number of voxels from 1 to 1000");
    expectRefused("validate " + tetrahedron(dir) + " -r 8 --worst -1",
                  "--worst -1: the worst cases listed of each kind are 0 to 1000000");
    const auto ok = runSvo("validate " + tetrahedron(dir) + " -r 8 --worst 0");
    EXPECT_EQ(ok.code, 0) << ok.out;
}

TEST(CliOptions, ValidateAndVoxelizeAgreeThatALevelSetHasNoThinMode)
{
    svo::test::TempDir dir("cli_options");
    const std::string mesh = tetrahedron(dir);
    const std::string rule = "--mode thin: --mode applies to surface voxels; level sets, unsigned distances and "
                             "solids do not depend on it";
    const std::string out = " -o " + dir.path("x.vdb");
    expectRefused("voxelize " + mesh + " -r 8 --sdf --mode thin" + out, rule);
    expectRefused("voxelize " + mesh + " -r 8 --udf --mode thin" + out, rule);
    expectRefused("voxelize " + mesh + " -r 8 --fill solid --mode thin" + out, rule);
    expectRefused("validate " + mesh + " -r 8 --sdf --mode thin", rule);
    EXPECT_FALSE(std::filesystem::exists(dir.path("x.vdb")));
    // The default mode, named, is the same call in both.
    const auto v = runSvo("voxelize " + mesh + " -r 8 --sdf --mode conservative" + out);
    EXPECT_EQ(v.code, 0) << v.out;
    const auto c = runSvo("validate " + mesh + " -r 8 --sdf --mode conservative");
    EXPECT_EQ(c.code, 0) << c.out;
}

/// The identifier of the option an error names first, or "" when the call throws no svo::Error.
template <typename Call>
std::string argumentOf(Call call)
{
    try {
        call();
    } catch (const svo::Error& e) {
        return e.argument();
    }
    return {};
}

// The one table of flags (apps/option_flags.h): each flag is one its command lists.
TEST(CliOptions, EveryFlagInTheTableIsOneItsCommandLists)
{
    for (const svo::app::OptionFlag& o : svo::app::kOptionFlags) {
        const auto r = runSvo(std::string(o.command) + " --help");
        ASSERT_EQ(r.code, 0) << o.command << "\n" << r.out;
        // "--ao-source octree": the flag, and the value among its choices.
        const std::string flag(o.flag.substr(0, o.flag.find(' ')));
        EXPECT_NE(r.out.find(flag + " "), std::string::npos) << o.identifier << " -> " << flag << "\n" << r.out;
        if (flag.size() < o.flag.size()) {
            const std::string value(o.flag.substr(flag.size() + 1));
            EXPECT_NE(r.out.find(value), std::string::npos) << o.identifier << " -> " << o.flag << "\n" << r.out;
        }
        EXPECT_EQ(svo::app::flagFor(o.identifier), o.flag);
    }
    EXPECT_TRUE(svo::app::flagFor("--band").empty()); // a flag already: named as it is
    EXPECT_TRUE(svo::app::flagFor("exterior_band").empty());
}

// The options the library names in its own checks (the ones a test can reach
// without a GPU) each have a flag in the table.
TEST(CliOptions, TheOptionsTheLibraryNamesHaveFlags)
{
    std::vector<std::string> named;
    for (const auto& field : {&svo::LevelSetOptions::exteriorBand, &svo::LevelSetOptions::interiorBand}) {
        svo::LevelSetOptions ls;
        ls.*field = 0.5;
        named.push_back(argumentOf([&] { svo::checkLevelSetOptions(ls); }));
    }
    svo::LevelSetOptions ls;
    ls.sign.windingAccuracy = 0;
    named.push_back(argumentOf([&] { svo::checkLevelSetOptions(ls); }));
    svo::VoxelizeOptions thin;
    thin.mode = svo::VoxelMode::Thin;
    named.push_back(argumentOf([&] { svo::checkFieldMode(thin); }));
    named.push_back(argumentOf([] { svo::gl::namedView({svo::Vec3d{0, 0, 0}, svo::Vec3d{1, 1, 1}}, "sideways", 1.0); }));
    // The view's checks run the single-option rules on its fields (svo/gl/ambient_occlusion.h, illumination.h).
    svo::gl::ViewRequest step;
    step.layers.ao.step = 1.5;
    named.push_back(argumentOf([&] { svo::gl::checkViewRequest(step); }));
    svo::gl::ViewRequest volume;
    volume.layers.ao.volumeResolution = 100;
    named.push_back(argumentOf([&] { svo::gl::checkViewRequest(volume); }));
    svo::gl::ViewRequest cones;
    cones.render = svo::gl::RenderMode::Global;
    cones.layers.light.cones = 0;
    named.push_back(argumentOf([&] { svo::gl::checkViewRequest(cones); }));
    const std::vector<std::string> want = {"LevelSetOptions::exteriorBand", "LevelSetOptions::interiorBand",
                                           "SignOptions::windingAccuracy", "VoxelizeOptions::mode",
                                           "svo::gl::namedView", "AmbientOcclusion::step",
                                           "AmbientOcclusion::volumeResolution", "Illumination::cones"};
    EXPECT_EQ(named, want);
    for (const auto& identifier : named) EXPECT_FALSE(svo::app::flagFor(identifier).empty()) << identifier;
}

// A bad band on the command line is refused in one line naming the flag, and
// an option the library names is printed as the flag that sets it.
TEST(CliOptions, ErrorsNameTheFlagNeverTheLibrarysField)
{
    svo::test::TempDir dir("cli_options");
    const std::string mesh = tetrahedron(dir), out = " -o " + dir.path("x.vdb");
    auto r = runSvo("voxelize " + mesh + " -r 8 --sdf --exterior-band 0.5" + out);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(r.out, "svo: error: --exterior-band 0.5: a band is a number of voxels from 1 to 1000\n");
    r = runSvo("voxelize " + mesh + " -r 8 --sdf --mode thin" + out);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(r.out.rfind("svo: error: --mode thin: --mode applies to surface voxels;", 0), 0u) << r.out;
    EXPECT_EQ(r.out.find("VoxelizeOptions"), std::string::npos) << r.out;
    r = runSvo("view " + mesh + " -r 8 --screenshot " + dir.path("v.png") + " --view sideways");
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(r.out, "svo: error: --view 'sideways': expected front, +x, -x, +y, -y, +z or -z\n");
    EXPECT_FALSE(std::filesystem::exists(dir.path("x.vdb")));
}

} // namespace

namespace {
/// The flag and the names of one declared option, as `svo voxelize --help` must list them.
struct HelpCheck {
    const std::string& help;
    template <typename E, typename = decltype(enumNames(E{}))>
    void operator()(const svo::OptionInfo& info, E& value)
    {
        const std::string line = flagLine(info);
        for (const auto& n : svo::names<E>()) EXPECT_NE(line.find(n), std::string::npos) << info.identifier << " " << n;
        EXPECT_NE(line.find("=" + std::string(svo::nameOf(value))), std::string::npos) << info.identifier << ": " << line;
    }
    void operator()(const svo::OptionInfo& info, svo::CheckedNumber number)
    {
        const std::string line = flagLine(info);
        EXPECT_NE(line.find(fmt::format("={}", number.value)), std::string::npos) << info.identifier << ": " << line;
    }
    template <typename Int>
    void operator()(const svo::OptionInfo& info, svo::CheckedInteger<Int> number)
    {
        const std::string line = flagLine(info);
        EXPECT_NE(line.find(fmt::format("={}", number.value)), std::string::npos) << info.identifier << ": " << line;
    }
    void operator()(const svo::OptionInfo& info, svo::NamedBool choice)
    {
        const std::string line = flagLine(info);
        for (const std::string_view n : {choice.falseName, choice.trueName})
            EXPECT_NE(line.find(std::string(n)), std::string::npos) << info.identifier << " " << n;
        EXPECT_NE(line.find("=" + std::string(choice.value ? choice.trueName : choice.falseName)), std::string::npos)
            << info.identifier << ": " << line;
    }
    template <typename T>
    void operator()(const svo::OptionInfo& info, T&&)
    {
        flagLine(info);
    }
    /// The help's line that starts with the option's flag; the library's errors about the option name that flag.
    std::string flagLine(const svo::OptionInfo& info)
    {
        const std::string f = svo::flagOf(info);
        EXPECT_EQ(svo::app::flagFor(info.identifier), f);
        const size_t at = help.find("  " + svo::flagNames(info) + " ");
        EXPECT_NE(at, std::string::npos) << info.identifier << " -> " << f;
        if (at == std::string::npos) return {};
        return help.substr(at, help.find('\n', at) - at);
    }
};
} // namespace

// Each option is declared once, beside its library struct (forEachOption):
// `svo voxelize` lists every one as a flag, with the declared names of its
// values and the library's default, and errors about it name that flag.
TEST(CliOptions, EveryDeclaredOptionIsAFlagWithTheLibrarysDefault)
{
    const auto r = runSvo("voxelize --help");
    ASSERT_EQ(r.code, 0) << r.out;
    HelpCheck check{r.out};
    svo::GridRequest request;
    svo::VoxelizeSettings settings;
    svo::DeviceOptions device;
    svo::LevelSetOptions levelSet;
    svo::forEachOption(request, check);
    svo::forEachOption(settings, check);
    svo::forEachOption(device, check);
    svo::forEachOption(levelSet, check);
    svo::GridOptions grids;
    grids.topology = svo::GridOptions::Topology::Bool; // the command line's own default: python3-openvdb reads it
    svo::forEachOption(grids, check);
}

// The view's options, declared beside the view's structs (svo/gl/view_request.h):
// `svo view` lists every one as a flag with the library's default, and errors
// about one name its flag.
TEST(CliOptions, EveryDeclaredViewOptionIsAFlagOfView)
{
    const auto r = runSvo("view --help");
    ASSERT_EQ(r.code, 0) << r.out;
    HelpCheck check{r.out};
    svo::gl::ViewRequest request;
    forEachOption(request, check); // found by argument-dependent lookup in svo::gl
}

TEST(CliOptions, ViewOptionsAreCheckedByTheLibrarysRulesUnderTheirFlags)
{
    svo::test::TempDir dir("cli_view_options");
    const std::string png = " --screenshot " + dir.path("v.png");
    auto r = runSvo("view -r 8" + png + " --gi-cones 17");
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(r.out, "svo: error: --gi-cones 17: the bounce gathers 1 to 16 cones\n");
    r = runSvo("view -r 8" + png + " --ao-step 1.5");
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(r.out, "svo: error: --ao-step 1.5: a cone's step is a share of its width in (0, 1]\n");
    r = runSvo("view -r 8" + png + " --light-volume 100");
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(r.out, "svo: error: --light-volume 100: a volume resolution is a power of two from 8 to 2048\n");
    EXPECT_FALSE(std::filesystem::exists(dir.path("v.png")));
}

// -q, -v and --no-clobber, declared once (OutputHabits), on every command that
// writes files; validate's report is its result, so it takes --no-clobber alone.
TEST(CliOptions, EveryCommandThatWritesTakesTheSameOutputFlags)
{
    for (const char* command : {"voxelize", "convert", "scene", "vtk", "view", "validate"}) {
        const auto r = runSvo(std::string(command) + " --help");
        ASSERT_EQ(r.code, 0) << command << "\n" << r.out;
        const bool all = std::string(command) != "validate";
        EXPECT_EQ(r.out.find("  -q,--quiet ") != std::string::npos, all) << command << "\n" << r.out;
        EXPECT_EQ(r.out.find("  -v,--verbose ") != std::string::npos, all) << command << "\n" << r.out;
        EXPECT_NE(r.out.find("  --no-clobber "), std::string::npos) << command << "\n" << r.out;
    }
}

// Every command that reads a mesh names the formats svo reads, glTF among
// them (the list is svo::supportedMeshExtensions's, written once).
TEST(CliOptions, EveryCommandThatReadsAMeshListsItsFormats)
{
    for (const char* command : {"voxelize", "validate", "info", "view", "vtk"}) {
        const auto r = runSvo(std::string(command) + " --help");
        ASSERT_EQ(r.code, 0) << command << "\n" << r.out;
        // CLI11 wraps long help lines: the list as one line, whatever the wrapping.
        std::string text;
        for (char c : r.out) {
            if (c == '\n' || c == ' ') {
                if (!text.empty() && text.back() != ' ') text += ' ';
            } else {
                text += c;
            }
        }
        EXPECT_NE(text.find(".obj, .ply, .stl, .off, .gltf, .glb"), std::string::npos) << command << "\n" << r.out;
    }
}

// An unsigned option refuses a negative number in one line, rather than
// reading -1 as 2^64 - 1 (CLI11's reading of it).
TEST(CliOptions, ANegativeSeedIsRefusedNotWrapped)
{
    svo::test::TempDir dir("cli_options");
    expectRefused("scene city --seed -1 -o " + dir.path("c.obj"),
                  "--seed: '-1' is negative; give a whole number from 0 to 18446744073709551615");
    EXPECT_FALSE(std::filesystem::exists(dir.path("c.obj")));
}
