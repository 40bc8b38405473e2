// The svo command's numbers: each option is checked once, by the library's
// rule for it, under the flag's name; NaN never becomes a default.
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <sys/wait.h>

#include "run_shell.h"
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
    const auto ok = runSvo(args + " --ortho 2");
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

} // namespace
