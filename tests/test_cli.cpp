// The svo command: exit codes, messages, and that bad input leaves no output.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <sys/wait.h>

#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

struct Run {
    int code;
    std::string out;
};

Run runSvo(const std::string& args)
{
    const std::string cmd = std::string(SVO_EXE) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string out;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

class Cli : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return tmp_.path(name); }
    std::string write(const std::string& name, const std::string& text) const { return tmp_.write(name, text); }
    /// Nothing but the listed files in the folder: no temporaries left behind.
    void expectOnly(std::initializer_list<std::string> names) const
    {
        size_t n = 0;
        for (const auto& e : fs::directory_iterator(tmp_.dir())) {
            ++n;
            EXPECT_NE(std::find(names.begin(), names.end(), e.path().filename().string()), names.end())
                << "unexpected file " << e.path();
        }
        EXPECT_EQ(n, names.size());
    }
    svo::test::TempDir tmp_{"cli"};
};

} // namespace

TEST_F(Cli, DefaultSceneWritesAVdbAndPrintsTheTable)
{
    const auto r = runSvo("voxelize -r 48 -o " + path("cb.vdb"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("triangles   3,136"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("voxelize"), std::string::npos);
    EXPECT_GT(fs::file_size(path("cb.vdb")), 100u);
    expectOnly({"cb.vdb"});
}

TEST_F(Cli, BadMeshFailsAndKeepsAnEarlierOutput)
{
    const std::string out = write("out.vdb", "earlier result");
    const auto bad = write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    const auto r = runSvo("voxelize " + bad + " -o " + out);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find(bad), std::string::npos) << r.out;
    std::ifstream in(out);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "earlier result");
    expectOnly({"out.vdb", "bad.obj"});
}

TEST_F(Cli, FarTriangleAsObjGivesTheVoxelsOfItsOff)
{
    // A one-unit triangle 1e9 from the origin: read in float, as OBJ used to
    // be, it collapsed to one voxel; every text format now reads it exactly.
    const std::string corners[3] = {"1000000000.1 1000000000.2 1000000000.3", "1000000001.1 1000000000.2 1000000000.3",
                                    "1000000000.1 1000000001.2 1000000000.3"};
    std::string off = "OFF\n3 1 0\n", obj;
    for (const auto& c : corners) off += c + "\n", obj += "v " + c + "\n";
    const auto a = runSvo("voxelize " + write("far.off", off + "3 0 1 2\n") + " --voxel-size 0.1 -o " + path("off.vdb"));
    const auto b = runSvo("voxelize " + write("far.obj", obj + "f 1 2 3\n") + " --voxel-size 0.1 -o " + path("obj.vdb"));
    ASSERT_EQ(a.code, 0) << a.out;
    ASSERT_EQ(b.code, 0) << b.out;
    auto voxels = [](const std::string& out) {
        const auto at = out.find("\n  voxels");
        return at == std::string::npos ? std::string("no voxel count") : out.substr(at, out.find('\n', at + 1) - at);
    };
    EXPECT_EQ(voxels(a.out), "\n  voxels      76");
    EXPECT_EQ(voxels(b.out), voxels(a.out));
}

TEST_F(Cli, BadArgumentsFailWithoutOutput)
{
    const auto missing = runSvo("voxelize " + path("missing.stl") + " -o " + path("a.vdb"));
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.out.find("no such file"), std::string::npos) << missing.out;
    for (const char* r : {"0", "-5"}) {
        const auto res = runSvo(std::string("voxelize -r ") + r + " -o " + path("a.vdb"));
        EXPECT_EQ(res.code, 1) << res.out;
        EXPECT_NE(res.out.find("--resolution"), std::string::npos) << res.out;
    }
    const auto huge = runSvo("voxelize -r 100000000 -o " + path("a.vdb"));
    EXPECT_EQ(huge.code, 1);
    const auto size = runSvo("voxelize --voxel-size -1 -o " + path("a.vdb"));
    EXPECT_EQ(size.code, 1);
    const auto folder = runSvo("voxelize -r 16 -o /nonexistent-folder/a.vdb");
    EXPECT_EQ(folder.code, 1);
    EXPECT_NE(folder.out.find("does not exist"), std::string::npos) << folder.out;
    const auto device = runSvo("voxelize -r 16 --device 97 -o " + path("a.vdb"));
    EXPECT_EQ(device.code, 1);
    EXPECT_NE(device.out.find("no EGL device matches '97'"), std::string::npos) << device.out;
    expectOnly({});
}

TEST_F(Cli, OctreeFilesConvertBothWaysAndReport)
{
    const auto v = runSvo("voxelize -r 48 -o " + path("box.svo"));
    ASSERT_EQ(v.code, 0) << v.out;
    EXPECT_NE(v.out.find("octree build"), std::string::npos) << v.out;

    const auto info = runSvo("info " + path("box.svo"));
    ASSERT_EQ(info.code, 0) << info.out;
    for (const char* field : {"levels", "bricks", "bytes/voxel", "fill ratio"})
        EXPECT_NE(info.out.find(field), std::string::npos) << field << "\n" << info.out;

    ASSERT_EQ(runSvo("convert " + path("box.svo") + " -o " + path("box.vdb") + " --topology bool --fog").code, 0);
    const auto back = runSvo("convert " + path("box.vdb") + " -o " + path("again.svo"));
    ASSERT_EQ(back.code, 0) << back.out;
    // The same voxel count through every file.
    auto voxels = [](const std::string& out) {
        const auto at = out.find("\n  voxels");
        return out.substr(at, out.find('\n', at) - at);
    };
    EXPECT_EQ(voxels(runSvo("info " + path("again.svo")).out), voxels(info.out));
    EXPECT_EQ(voxels(runSvo("info " + path("box.vdb") + " --grid density").out), voxels(info.out));
    expectOnly({"box.svo", "box.vdb", "again.svo"});
}

TEST_F(Cli, BadOctreeInputsFailClearly)
{
    const std::string junk = write("junk.svo", "SVOCTREE but not really");
    const auto r = runSvo("info " + junk);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("junk.svo: not a valid .svo file"), std::string::npos) << r.out;

    const auto c = runSvo("convert " + junk + " -o " + path("out.vdb"));
    EXPECT_EQ(c.code, 1);
    const auto m = runSvo("convert " + write("tri.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n") + " -o " + path("o.svo"));
    EXPECT_EQ(m.code, 1);
    EXPECT_NE(m.out.find("svo voxelize"), std::string::npos) << m.out;
    const auto e = runSvo("voxelize -o " + path("out.txt"));
    EXPECT_EQ(e.code, 1);
    EXPECT_NE(e.out.find(".vdb, .nvdb or .svo"), std::string::npos) << e.out;
    expectOnly({"junk.svo", "tri.off"});
}

TEST_F(Cli, ValidateFailsWithExitCode3OnMissedVoxels)
{
    // The seed report's centroid-push dilation, kept as a baseline, misses voxels.
    const auto r = runSvo("validate -r 64 --conservative centroid --no-holes --json " + path("v.json"));
    EXPECT_EQ(r.code, 3) << r.out;
    EXPECT_NE(r.out.find("svo: validation failed:"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("voxels missed"), std::string::npos) << r.out;
    std::ifstream in(path("v.json"));
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"passed\": false"), std::string::npos) << json;
}

TEST_F(Cli, ValidatePassesAndWritesItsReports)
{
    const auto r = runSvo("validate -r 48 --json " + path("v.json") + " --errors " + path("e.vdb"));
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* field : {"missed", "boundary", "extra", "holes", "consistent", "passed"})
        EXPECT_NE(r.out.find(field), std::string::npos) << field << "\n" << r.out;
    std::ifstream in(path("v.json"));
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"missed\": 0,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"passed\": true"), std::string::npos) << json;
    // The errors file holds the (empty) missed and extra grids.
    const auto info = runSvo("info " + path("e.vdb") + " --grid extra");
    EXPECT_EQ(info.code, 0) << info.out;
    EXPECT_NE(info.out.find("grid 'extra'"), std::string::npos) << info.out;
    expectOnly({"v.json", "e.vdb"});
}

TEST_F(Cli, NoOutputIsEverAnInputHoweverItIsNamed)
{
    const std::string tetra = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string mesh = write("m.off", tetra);
    fs::create_symlink(mesh, path("link.off"));
    fs::create_hard_link(mesh, path("hard.off"));
    fs::create_directory(path("sub"));
    const std::string dotted = path("sub") + "/../m.off";
    ASSERT_EQ(runSvo("voxelize " + mesh + " -r 16 -o " + path("box.svo")).code, 0);
    const std::vector<std::string> attempts = {
        "voxelize " + mesh + " -r 16 -o " + path("out.vdb") + " --json " + mesh,
        "voxelize " + mesh + " -r 16 -o " + path("out.vdb") + " --json " + path("link.off"),
        "voxelize " + mesh + " -r 16 -o " + path("out.vdb") + " --json " + path("hard.off"),
        "voxelize " + mesh + " -r 16 -o " + path("out.vdb") + " --json " + dotted,
        "voxelize " + path("link.off") + " -r 16 -o " + path("out.vdb") + " --json " + mesh,
        "validate " + mesh + " -r 16 --json " + path("hard.off"),
        "validate " + mesh + " -r 16 --errors " + path("link.off"),
        "vtk " + mesh + " -r 16 --png " + path("link.off"),
        "convert " + path("box.svo") + " -o " + path("sub") + "/../box.svo",
    };
    const auto svoBytes = fs::file_size(path("box.svo"));
    for (const auto& args : attempts) {
        const auto r = runSvo(args);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.out;
        EXPECT_NE(r.out.find("svo never writes over an input"), std::string::npos) << args << "\n" << r.out;
        std::ifstream in(mesh);
        EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), tetra) << args;
        EXPECT_EQ(fs::file_size(path("box.svo")), svoBytes) << args;
    }
    // The default output name (known once the scene is) against --json.
    const auto cwd = fs::current_path();
    fs::current_path(tmp_.dir());
    const auto defaulted = runSvo("voxelize -r 16 --json cornell_box.vdb");
    fs::current_path(cwd);
    EXPECT_EQ(defaulted.code, 1) << defaulted.out;
    EXPECT_NE(defaulted.out.find("given for two outputs"), std::string::npos) << defaulted.out;
    expectOnly({"m.off", "link.off", "hard.off", "sub", "box.svo"});
}
