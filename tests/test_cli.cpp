// The svo command: exit codes, messages, and that bad input leaves no output.
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <set>
#include <sstream>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "svo/core/octree.h"
#include "svo/core/octree_file.h"
#include "run_shell.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

using svo::test::Run;
using svo::test::runShell;

/// `env`: "NAME=value ..." for the command's environment.
Run runSvo(const std::string& args, const std::string& env = "")
{
    return runShell(env + (env.empty() ? "" : " ") + std::string(SVO_EXE) + " " + args);
}

/// Another program's output (stdout and stderr).
std::string runCommand(const std::string& cmd)
{
    FILE* p = popen((cmd + " 2>&1").c_str(), "r");
    std::string out;
    std::array<char, 4096> buf;
    size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
    pclose(p);
    return out;
}

/// svo started in the background, its output in a file, for signal tests.
struct Background {
    pid_t pid = -1;
    std::string log;
};

Background startSvo(const std::vector<std::string>& args, const std::string& log, bool withoutDisplay = false)
{
    std::vector<std::string> all = {SVO_EXE};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> envText;
    for (char** e = environ; *e; ++e)
        if (!withoutDisplay || std::string(*e).rfind("DISPLAY=", 0) != 0) envText.emplace_back(*e);
    std::vector<char*> env;
    for (auto& e : envText) env.push_back(e.data());
    env.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    Background b;
    b.log = log;
    EXPECT_EQ(posix_spawn(&b.pid, SVO_EXE, &actions, nullptr, argv.data(), env.data()), 0);
    posix_spawn_file_actions_destroy(&actions);
    return b;
}

/// Waits for the child, returning its exit status (-1 when a signal killed it).
int waitFor(pid_t pid)
{
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The children of `pid` whose command is `name`, from /proc.
std::vector<pid_t> childrenNamed(pid_t pid, const std::string& name)
{
    std::vector<pid_t> out;
    for (const auto& e : fs::directory_iterator("/proc")) {
        const std::string id = e.path().filename();
        if (id.find_first_not_of("0123456789") != std::string::npos) continue;
        std::ifstream stat(e.path() / "stat");
        std::string line;
        std::getline(stat, line);
        const auto close = line.rfind(')');
        if (close == std::string::npos || line.find('(' + name + ')') == std::string::npos) continue;
        std::istringstream rest(line.substr(close + 2));
        char state;
        pid_t parent = 0;
        rest >> state >> parent;
        if (parent == pid && state != 'Z') out.push_back(pid_t(std::stol(id)));
    }
    return out;
}

/// The X sockets there are now.
std::set<std::string> xSockets()
{
    std::set<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator("/tmp/.X11-unix", ec)) names.insert(e.path().string());
    return names;
}

/// Waits until the Xvfb that svo (`pid`) starts is up: its socket appears
/// (not among `before`). The socket is the one that server listens on (other
/// tests may start X servers at the same time): a path of /proc/net/unix
/// whose inode is among the server's open files. Returns the Xvfb children
/// of `pid` seen and the socket (empty if none came up).
std::pair<std::vector<pid_t>, std::string> serverStartedBy(pid_t pid, const std::set<std::string>& before)
{
    auto listensOn = [](pid_t server, const std::string& socketPath) {
        std::ifstream table("/proc/net/unix");
        std::string line, inode;
        while (std::getline(table, line))
            if (line.size() > socketPath.size() && line.compare(line.size() - socketPath.size(), socketPath.size(), socketPath) == 0) {
                std::istringstream fields(line);
                std::string f;
                for (int k = 0; k < 7 && fields >> f; ++k) inode = f; // the 7th field is the inode
            }
        if (inode.empty()) return false;
        std::error_code ec;
        for (const auto& fd : fs::directory_iterator("/proc/" + std::to_string(server) + "/fd", ec))
            if (fs::read_symlink(fd.path(), ec).string() == "socket:[" + inode + "]") return true;
        return false;
    };
    std::vector<pid_t> servers;
    std::string socket;
    for (int i = 0; i < 20000 && socket.empty(); ++i) {
        if (servers.empty()) servers = childrenNamed(pid, "Xvfb");
        for (const auto& s : xSockets())
            if (!before.count(s) && servers.size() == 1 && listensOn(servers[0], s)) socket = s;
        if (socket.empty()) std::this_thread::sleep_for(std::chrono::microseconds(500));
        if (waitpid(pid, nullptr, WNOHANG) != 0) break;
    }
    return {servers, socket};
}

/// Whether process `pid` is gone (or a zombie) within two seconds.
bool goneSoon(pid_t pid)
{
    for (int i = 0; i < 200; ++i) {
        std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
        std::string line;
        if (!std::getline(stat, line) || line.find(") Z") != std::string::npos) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

/// The number of lines in `text`.
size_t lineCount(const std::string& text) { return size_t(std::count(text.begin(), text.end(), '\n')); }

/// A file's bytes.
std::string fileText(const std::string& file)
{
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The first "Number of active voxels" of `vdb_print -l` (OpenVDB's own
/// count, tiles included, written with commas), or "none".
std::string activeVoxels(const std::string& printed)
{
    std::smatch m;
    return std::regex_search(printed, m, std::regex("Number of active voxels: +([0-9,]+)")) ? m[1].str() : "none";
}

/// "text {} text" with the number in place of {}.
std::string fmt(const std::string& pattern, size_t n)
{
    const auto at = pattern.find("{}");
    return pattern.substr(0, at) + std::to_string(n) + pattern.substr(at + 2);
}

class Cli : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return tmp_.path(name); }
    std::string write(const std::string& name, const std::string& text) const { return tmp_.write(name, text); }
    /// Nothing but the listed files in the folder: no temporaries left behind.
    void expectOnly(const std::vector<std::string>& names) const
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

// One summary line by default (what was written, its voxels as vdb_print
// counts them, the time), the whole table with -v, nothing with -q.
TEST_F(Cli, DefaultSceneWritesAVdbAndPrintsOneLineOrTheTable)
{
    const auto r = runSvo("voxelize -r 48 -o " + path("cb.vdb"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(lineCount(r.out), 1u) << r.out;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m,
                                  std::regex("^svo voxelize: wrote " + path("cb.vdb") +
                                             R"( \(bool grid 'surface', ([0-9,]+) voxels, [0-9.]+ MB\) in [0-9.]+ m?s\n$)")))
        << r.out;
    EXPECT_EQ(activeVoxels(runCommand("vdb_print -l " + path("cb.vdb"))), m[1].str());
    const auto table = runSvo("voxelize -r 48 -v -o " + path("cb.vdb"));
    ASSERT_EQ(table.code, 0) << table.out;
    EXPECT_NE(table.out.find("triangles   3,136"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("octree build"), std::string::npos) << table.out;
    const auto quiet = runSvo("voxelize -r 48 -q -o " + path("q.vdb"));
    ASSERT_EQ(quiet.code, 0) << quiet.out;
    EXPECT_EQ(quiet.out, "");
    EXPECT_EQ(fs::file_size(path("q.vdb")), fs::file_size(path("cb.vdb")));
    const auto both = runSvo("voxelize -r 48 -q -v -o " + path("x.vdb"));
    EXPECT_EQ(both.code, 1) << both.out;
    EXPECT_EQ(lineCount(both.out), 1u) << both.out;
    expectOnly({"cb.vdb", "q.vdb"});
}

TEST_F(Cli, StartUpRowsAndTheProgramCacheAcrossRuns)
{
    const std::string cache = "SVO_PROGRAM_CACHE=" + path("programs");
    const auto cold = runSvo("voxelize -r 24 -v --backend raster -o " + path("a.vdb"), cache);
    ASSERT_EQ(cold.code, 0) << cold.out;
    EXPECT_NE(cold.out.find("EGL set-up"), std::string::npos) << cold.out;
    if (!fs::exists(path("programs"))) {
        EXPECT_NE(cold.out.find("no program cache"), std::string::npos) << cold.out;
        GTEST_SKIP() << "the driver offers no program binary formats";
    }
    const size_t files = size_t(std::distance(fs::directory_iterator(path("programs")), fs::directory_iterator()));
    EXPECT_NE(cold.out.find(fmt("({} compiled)", files)), std::string::npos) << cold.out;
    const auto warm = runSvo("voxelize -r 24 -v --backend raster -o " + path("a.vdb"), cache);
    ASSERT_EQ(warm.code, 0) << warm.out;
    EXPECT_NE(warm.out.find(fmt("({} cached, 0 compiled)", files)), std::string::npos) << warm.out;
    // Mesa without its disk cache offers no binary formats: then svo keeps no cache either.
    const std::string noMesaCache = "MESA_SHADER_CACHE_DISABLE=true SVO_PROGRAM_CACHE=" + path("other");
    const auto info = runSvo("glinfo", noMesaCache);
    ASSERT_EQ(info.code, 0) << info.out;
    if (info.out.find("program binary formats     0") != std::string::npos) {
        const auto r = runSvo("voxelize -r 24 -v --backend raster -o " + path("b.vdb"), noMesaCache);
        ASSERT_EQ(r.code, 0) << r.out;
        EXPECT_NE(r.out.find("no program cache"), std::string::npos) << r.out;
        EXPECT_FALSE(fs::exists(path("other")));
    }
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
    const auto a = runSvo("voxelize " + write("far.off", off + "3 0 1 2\n") + " -v --voxel-size 0.1 -o " + path("off.vdb"));
    const auto b = runSvo("voxelize " + write("far.obj", obj + "f 1 2 3\n") + " -v --voxel-size 0.1 -o " + path("obj.vdb"));
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
    const auto v = runSvo("voxelize -r 48 -v -o " + path("box.svo"));
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

// svo validate --errors writes BoolGrids, as every svo output, which
// python3-openvdb reads (a MaskGrid with --topology mask). Their voxels are the
// errors: the missed voxels are none of the voxelization's (svo voxelize with
// the same options) and all of the CPU reference's; the extra ones are all
// the voxelization's; their counts are the report's.
TEST_F(Cli, ValidateErrorsAreBoolGridsOfTheMissedAndExtraVoxels)
{
    const std::string options = " -r 64 --conservative centroid ";
    const auto r = runSvo("validate" + options + "--no-holes --errors " + path("e.vdb"));
    ASSERT_EQ(r.code, 3) << r.out; // the centroid push misses voxels (ValidateFailsWithExitCode3OnMissedVoxels)
    EXPECT_NE(r.out.find("errors       " + path("e.vdb") + " (bool grids missed, extra)"), std::string::npos) << r.out;
    auto count = [&](const std::string& row) {
        std::smatch m;
        return std::regex_search(r.out, m, std::regex("\n  " + row + " +([0-9,]+)")) ? m[1].str() : "none";
    };
    const std::string missed = count(R"(missed \(E\))"), extra = count("extra");
    ASSERT_NE(missed, "0");
    ASSERT_EQ(runSvo("voxelize" + options + "-o " + path("v.vdb")).code, 0);
    ASSERT_EQ(runSvo("voxelize -r 64 --backend cpu -o " + path("cpu.vdb")).code, 0);
    // Each grid: its name, type, voxels, how many the voxelization has, and (missed) how many the CPU reference has.
    const std::string script = write("errors.py", R"(import sys, pyopenvdb
grids, _ = pyopenvdb.readAll(sys.argv[1])
tested = pyopenvdb.read(sys.argv[2], "surface").getConstAccessor()
cpu = pyopenvdb.read(sys.argv[3], "surface").getConstAccessor()
for g in sorted(grids, key=lambda g: g.name):
    ijk = [(x, y, z) for v in g.citerOnValues() for x in range(v["min"][0], v["max"][0] + 1)
           for y in range(v["min"][1], v["max"][1] + 1) for z in range(v["min"][2], v["max"][2] + 1)]
    print(g.name, g.valueTypeName, len(ijk), sum(tested.isValueOn(c) for c in ijk),
          sum(cpu.isValueOn(c) for c in ijk) if g.name == "missed" else "-", g["svo:grid"])
)");
    const auto plain = [](const std::string& n) { return std::regex_replace(n, std::regex(","), ""); };
    EXPECT_EQ(runCommand("/usr/bin/python3 " + script + " " + path("e.vdb") + " " + path("v.vdb") + " " + path("cpu.vdb")),
              "extra bool " + plain(extra) + " " + plain(extra) + " - resolution 64\n" + "missed bool " + plain(missed) +
                  " 0 " + plain(missed) + " resolution 64\n");
    // --topology mask: the same voxels as a MaskGrid; --topology without --errors is refused.
    const auto mask = runSvo("validate" + options + "--no-holes --topology mask --errors " + path("m.vdb"));
    ASSERT_EQ(mask.code, 3) << mask.out;
    const std::string printed = runCommand("vdb_print -l " + path("m.vdb"));
    EXPECT_NE(printed.find("Type: Tree_mask_5_4_3"), std::string::npos) << printed;
    EXPECT_EQ(printed.find("Type: Tree_bool_5_4_3"), std::string::npos) << printed;
    const auto refused = runSvo("validate -r 16 --topology mask");
    EXPECT_EQ(refused.code, 1) << refused.out;
    EXPECT_EQ(refused.out, "svo: error: --topology applies to --errors (the grid type of the missed and extra voxels)\n");
    expectOnly({"e.vdb", "m.vdb", "v.vdb", "cpu.vdb", "errors.py"});
}

// --sdf, --udf and --fill solid run on the CPU with --backend cpu: the same
// active voxels and sign method as the default backend's (test_cpu_fields
// compares the fields voxel for voxel).
TEST_F(Cli, FieldsRunOnTheCpuBackend)
{
    auto read = [&](const std::string& name) {
        std::ifstream in(path(name));
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    auto field = [](const std::string& json, const std::string& key) {
        std::smatch m;
        return std::regex_search(json, m, std::regex("\"" + key + "\": (\"[^\"]*\"|[0-9]+)")) ? m[1].str()
                                                                                              : std::string();
    };
    const std::string mesh =
        write("tet.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    for (const char* kind : {"--sdf", "--udf", "--fill solid", "--sdf --sign winding"}) {
        SCOPED_TRACE(kind);
        auto r = runSvo("voxelize " + mesh + " -r 32 " + kind + " --backend cpu -o " + path("c.vdb") + " --json " +
                        path("c.json"));
        ASSERT_EQ(r.code, 0) << r.out;
        r = runSvo("voxelize " + mesh + " -r 32 " + kind + " -o " + path("g.vdb") + " --json " + path("g.json"));
        ASSERT_EQ(r.code, 0) << r.out;
        const std::string cpu = read("c.json"), gpu = read("g.json");
        EXPECT_EQ(field(cpu, "backend"), "\"cpu\"") << cpu;
        EXPECT_NE(field(cpu, "active_voxels"), "") << cpu;
        EXPECT_EQ(field(cpu, "active_voxels"), field(gpu, "active_voxels"));
        EXPECT_EQ(field(cpu, "sign"), field(gpu, "sign"));
        // Winding numbers: the GPU passes (compute: not the CPU that auto
        // picks on llvmpipe) walk the tree at every centre of their bricks,
        // the CPU climbs this closed mesh's columns by crossings.
        const std::string cpuWalks = field(cpu, "winding_walks");
        ASSERT_NE(cpuWalks, "") << cpu;
        if (std::string(kind).find("winding") == std::string::npos) {
            EXPECT_EQ(cpuWalks, "0");
            continue;
        }
        r = runSvo("voxelize " + mesh + " -r 32 " + kind + " --backend compute -o " + path("r.vdb") + " --json " +
                   path("r.json"));
        ASSERT_EQ(r.code, 0) << r.out;
        const std::string compute = read("r.json");
        EXPECT_EQ(field(compute, "active_voxels"), field(cpu, "active_voxels"));
        EXPECT_GT(std::stoull(cpuWalks), 0u);
        EXPECT_LT(std::stoull(cpuWalks), std::stoull(field(compute, "winding_walks")));
        EXPECT_GE(std::stoull(field(compute, "winding_walks")), 512 * std::stoull(field(compute, "band_bricks")));
    }
}

TEST_F(Cli, ThinModeVoxelizesFewerVoxelsAndValidates)
{
    auto read = [&](const std::string& name) {
        std::ifstream in(path(name));
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    auto voxels = [](const std::string& json) {
        std::smatch m;
        return std::regex_search(json, m, std::regex("\"voxels\": ([0-9]+)")) ? std::stoull(m[1]) : 0ull;
    };
    // A closed tetrahedron, so that the hole check applies.
    const std::string mesh =
        write("tet.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    auto r = runSvo("voxelize " + mesh + " -r 48 -v --mode thin -o " + path("t.vdb") + " --json " + path("t.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("mode        thin"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("centre segments grown by half of it"), std::string::npos) << r.out;
    r = runSvo("voxelize " + mesh + " -r 48 -o " + path("c.vdb") + " --json " + path("c.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string thin = read("t.json"), conservative = read("c.json");
    EXPECT_NE(thin.find("\"mode\": \"thin\""), std::string::npos) << thin;
    EXPECT_NE(conservative.find("\"mode\": \"conservative\""), std::string::npos) << conservative;
    EXPECT_GT(voxels(thin), 0u);
    EXPECT_LT(voxels(thin), voxels(conservative));

    r = runSvo("validate " + mesh + " -r 48 --mode thin --json " + path("v.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("the exact thin set"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("6-connected fill"), std::string::npos) << r.out;
    const std::string report = read("v.json");
    EXPECT_NE(report.find("\"mode\": \"thin\""), std::string::npos) << report;
    EXPECT_NE(report.find("\"connectivity\": 6"), std::string::npos) << report;
    EXPECT_NE(report.find("\"passed\": true"), std::string::npos) << report;
    EXPECT_EQ(voxels(report), voxels(thin)); // the same voxels as svo voxelize --mode thin

    r = runSvo("voxelize -r 16 --mode thick -o " + path("x.vdb"));
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find("--mode"), std::string::npos) << r.out;
    expectOnly({"tet.off", "t.vdb", "t.json", "c.vdb", "c.json", "v.json"});
}

TEST_F(Cli, NoOutputIsEverAnInputHoweverItIsNamed)
{
    const std::string tetra = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string mesh = write("m.off", tetra);
    fs::create_symlink(mesh, path("link.off"));
    fs::create_hard_link(mesh, path("hard.off"));
    // Links whose names carry the output's extension, so the format check passes.
    fs::create_symlink(mesh, path("alias.vdb"));
    fs::create_symlink(mesh, path("alias.png"));
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
        "validate " + mesh + " -r 16 --errors " + path("alias.vdb"),
        "vtk " + mesh + " -r 16 --png " + path("alias.png"),
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
    expectOnly({"m.off", "link.off", "hard.off", "alias.vdb", "alias.png", "sub", "box.svo"});
}

/// Interrupted while the output is being written: the temporary is removed,
/// an earlier output survives, and the exit status is 128 + the signal.
TEST_F(Cli, InterruptsRemoveTheTemporaryAndExitConventionally)
{
    for (const int sig : {SIGINT, SIGTERM}) {
        const std::string out = write("out.vdb", "earlier result");
        // A large fog grid takes a few hundred ms to write: the signal lands mid-write.
        Background svo = startSvo({"voxelize", "-r", "768", "--fog", "-o", out}, path("log.txt"));
        bool sawTemporary = false;
        for (int i = 0; i < 120000 && !sawTemporary; ++i) {
            for (const auto& e : fs::directory_iterator(tmp_.dir()))
                sawTemporary |= e.path().filename().string().rfind("out.vdb.tmp-", 0) == 0;
            if (!sawTemporary) std::this_thread::sleep_for(std::chrono::microseconds(500));
            if (waitpid(svo.pid, nullptr, WNOHANG) != 0) break;
        }
        ASSERT_TRUE(sawTemporary) << "the temporary output never appeared";
        kill(svo.pid, sig);
        EXPECT_EQ(waitFor(svo.pid), 128 + sig);
        std::ifstream log(svo.log), in(out);
        const std::string logText((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
        EXPECT_NE(logText.find(sig == SIGINT ? "svo: interrupted" : "svo: terminated"), std::string::npos) << logText;
        EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), "earlier result");
        expectOnly({"out.vdb", "log.txt"});
    }
}

/// Interrupted while rendering through its own Xvfb: the server goes too.
TEST_F(Cli, InterruptStopsTheXServerSvoStarted)
{
    if (system("command -v Xvfb >/dev/null 2>&1") != 0) GTEST_SKIP() << "Xvfb is not installed";
    const std::string mesh = write("m.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const auto before = xSockets();
    Background svo = startSvo({"vtk", mesh, "-r", "256", "--png", path("m.png")}, path("log.txt"), true);
    const auto [servers, socket] = serverStartedBy(svo.pid, before);
    ASSERT_EQ(servers.size(), 1u) << "svo vtk --png did not start Xvfb";
    ASSERT_FALSE(socket.empty()) << "Xvfb never opened its socket";
    kill(svo.pid, SIGINT);
    EXPECT_EQ(waitFor(svo.pid), 130);
    // The server was ours: once svo has exited it must be gone, with its socket.
    const bool gone = goneSoon(servers[0]);
    EXPECT_TRUE(gone) << "Xvfb " << servers[0] << " outlived svo";
    if (!gone) kill(servers[0], SIGTERM);
    EXPECT_FALSE(fs::exists(socket)) << socket << " left behind";
    expectOnly({"m.off", "log.txt"});
}

/// Killed outright (SIGKILL: no clean-up runs), svo still takes its Xvfb
/// with it: the server does not live on under init.
TEST_F(Cli, TheXServerSvoStartedDiesWhenSvoIsKilled)
{
    if (system("command -v Xvfb >/dev/null 2>&1") != 0) GTEST_SKIP() << "Xvfb is not installed";
    const std::string mesh = write("m.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const auto before = xSockets();
    Background svo = startSvo({"vtk", mesh, "-r", "256", "--png", path("m.png")}, path("log.txt"), true);
    const auto [servers, socket] = serverStartedBy(svo.pid, before);
    ASSERT_EQ(servers.size(), 1u) << "svo vtk --png did not start Xvfb";
    ASSERT_FALSE(socket.empty()) << "Xvfb never opened its socket";
    // Killed only once the server has told svo its display (and closed that
    // pipe): killed earlier, the server would die of SIGPIPE on the write anyway.
    std::ifstream cmdline("/proc/" + std::to_string(servers[0]) + "/cmdline");
    std::string arg, displayFd;
    for (bool next = false; std::getline(cmdline, arg, '\0'); next = arg == "-displayfd")
        if (next) displayFd = arg;
    ASSERT_FALSE(displayFd.empty()) << "no -displayfd in Xvfb's command line";
    const std::string pipeEnd = "/proc/" + std::to_string(servers[0]) + "/fd/" + displayFd;
    for (int i = 0; i < 1000 && fs::exists(fs::symlink_status(pipeEnd)); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_FALSE(fs::exists(fs::symlink_status(pipeEnd))) << "Xvfb never wrote its display";
    kill(svo.pid, SIGKILL);
    EXPECT_EQ(waitFor(svo.pid), -1);
    const bool gone = goneSoon(servers[0]);
    EXPECT_TRUE(gone) << "Xvfb " << servers[0] << " outlived svo killed by SIGKILL";
    if (!gone) kill(servers[0], SIGTERM);
    for (int i = 0; i < 200 && fs::exists(socket); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_FALSE(fs::exists(socket)) << socket << " left behind"; // Xvfb removes it on SIGTERM
}

/// A DISPLAY with no server behind it: VTK would print a page of log and
/// abort (exit 134). svo renders through its own Xvfb instead, with one
/// warning, or, with no Xvfb either, fails in one line before any work.
TEST_F(Cli, ADisplayThatDoesNotOpenFallsBackToXvfbOrFailsInOneLine)
{
    const std::string mesh = write("m.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const std::string nowhere = "DISPLAY=:4093"; // -displayfd picks free displays from :0 up
    const auto none = runSvo("vtk " + mesh + " -r 16 --png " + path("a.png"), nowhere + " PATH=/nonexistent");
    EXPECT_EQ(none.code, 1) << none.out;
    EXPECT_EQ(lineCount(none.out), 1u) << none.out;
    EXPECT_NE(none.out.find("DISPLAY=:4093 cannot be opened"), std::string::npos) << none.out;
    EXPECT_FALSE(fs::exists(path("a.png")));
    if (system("command -v Xvfb >/dev/null 2>&1") != 0) GTEST_SKIP() << "Xvfb is not installed";
    const auto r = runSvo("vtk " + mesh + " -r 16 --png " + path("b.png"), nowhere);
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("svo: warning: DISPLAY=:4093 cannot be opened; rendering through an Xvfb"), std::string::npos)
        << r.out;
    EXPECT_GT(fs::exists(path("b.png")) ? fs::file_size(path("b.png")) : 0u, 100u);
    expectOnly({"m.off", "b.png"});
}

/// Interrupted at a fixed point (SVO_TEST_SIGNAL raises SIGTERM there) after
/// the first of two outputs is finished: neither earlier file is replaced, and
/// nothing is left behind. Interrupted during the commit, the run completes.
TEST_F(Cli, AnInterruptAfterTheFirstOutputReplacesNone)
{
    const std::string mesh = write("m.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const std::string vdb = path("out.vdb"), json = path("out.json");
    const std::string args = "voxelize " + mesh + " -r 16 --backend cpu -o " + vdb + " --json " + json;
    for (const char* point : {"staged:1", "staged:2"}) {
        write("out.vdb", "earlier vdb");
        write("out.json", "earlier json");
        const auto r = runSvo(args, std::string("SVO_TEST_SIGNAL=") + point);
        EXPECT_EQ(r.code, 143) << point << "\n" << r.out;
        EXPECT_NE(r.out.find("svo: terminated"), std::string::npos) << r.out;
        std::ifstream a(vdb), b(json);
        EXPECT_EQ(std::string((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>()), "earlier vdb") << point;
        EXPECT_EQ(std::string((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>()), "earlier json") << point;
        expectOnly({"m.off", "out.vdb", "out.json"});
    }
    // A signal between the two renames: the commit goes on, and the run succeeds.
    const auto r = runSvo(args, "SVO_TEST_SIGNAL=renamed:1");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_GT(fs::file_size(vdb), 100u);
    EXPECT_GT(fs::file_size(json), 100u);
    expectOnly({"m.off", "out.vdb", "out.json"});

    // svo vtk: the picture is finished first, then the .vtu.
    if (system("command -v Xvfb >/dev/null 2>&1") != 0) GTEST_SKIP() << "Xvfb is not installed";
    write("x.vtu", "earlier vtu");
    write("y.png", "earlier png");
    const auto v = runSvo("vtk " + mesh + " -r 16 -o " + path("x.vtu") + " --png " + path("y.png"),
                          "DISPLAY= SVO_TEST_SIGNAL=staged:1");
    EXPECT_EQ(v.code, 143) << v.out;
    std::ifstream vtu(path("x.vtu")), png(path("y.png"));
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>()), "earlier vtu");
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(png)), std::istreambuf_iterator<char>()), "earlier png");
    expectOnly({"m.off", "out.vdb", "out.json", "x.vtu", "y.png"});
}

/// The second output fails (the file-size limit stands in for a full disk:
/// the .svo fits under it, the JSON does not): the first, already finished,
/// is not put in place either, and the message says nothing was written.
TEST_F(Cli, AFailingSecondOutputLeavesTheFirstUnreplaced)
{
    const std::string tri = write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string args = "voxelize " + tri + " -r 4 --backend cpu";
    // Sizes first: the .svo must fit under the limit and the JSON must not.
    ASSERT_EQ(runSvo(args + " -o " + path("free.svo") + " --json " + path("free.json")).code, 0);
    ASSERT_LT(fs::file_size(path("free.svo")), 1024u);
    ASSERT_GT(fs::file_size(path("free.json")), 1024u);
    write("out.svo", "earlier svo");
    write("out.json", "earlier json");
    // SIGXFSZ ignored, so that a write past the limit fails (EFBIG) as on a full disk.
    const auto r = runShell("bash -c \"trap '' XFSZ; ulimit -f 1; exec " + std::string(SVO_EXE) + " " + args + " -o " +
                            path("out.svo") + " --json " + path("out.json") + "\"");
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find(path("out.json")), std::string::npos) << r.out;
    std::ifstream a(path("out.svo")), b(path("out.json"));
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>()), "earlier svo");
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>()), "earlier json");
    expectOnly({"tri.obj", "free.svo", "free.json", "out.svo", "out.json"});
}

/// Outputs that are not regular files are never replaced by one: a link is
/// followed (the file it names is replaced, the link stays), a FIFO or a
/// character device is written through, /dev/stdout writes to svo's standard
/// output wherever it goes, and a socket is refused in one line. As root, a
/// rename would replace /dev/null itself: a private copy of the device is
/// tried first, so that a regression fails there and never reaches /dev/null.
TEST_F(Cli, OutputsThatAreNotFilesAreWrittenThroughOrRefusedNeverReplaced)
{
    const std::string mesh = write("m.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const std::string run = "voxelize " + mesh + " -r 16 --backend cpu -o ";
    auto text = [](const std::string& file) {
        std::ifstream in(file);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    // A link to a file: the file is replaced, the link stays; a dangling link creates its target.
    fs::create_directory(path("real"));
    write("real/target.vdb", "earlier");
    fs::create_symlink(path("real/target.vdb"), path("link.vdb"));
    fs::create_symlink("made.json", path("dangling.json")); // relative to the link's folder
    auto r = runSvo(run + path("link.vdb") + " --json " + path("dangling.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::is_symlink(path("link.vdb")));
    EXPECT_GT(fs::file_size(path("real/target.vdb")), 100u);
    EXPECT_TRUE(fs::is_symlink(path("dangling.json")));
    EXPECT_NE(text(path("made.json")).find("\"voxels\""), std::string::npos);
    EXPECT_EQ(std::distance(fs::directory_iterator(path("real")), fs::directory_iterator()), 1); // no temporary
    // A FIFO: written through to its reader.
    ASSERT_EQ(mkfifo(path("pipe.vdb").c_str(), 0644), 0);
    ASSERT_EQ(system(("timeout 60 cat " + path("pipe.vdb") + " > " + path("received.vdb") + " &").c_str()), 0);
    r = runSvo(run + path("pipe.vdb"));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::is_fifo(path("pipe.vdb")));
    for (int i = 0; i < 500 && runSvo("info " + path("received.vdb")).code != 0; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10)); // until cat has it all
    EXPECT_EQ(runSvo("info " + path("received.vdb")).code, 0);
    // A socket is refused, before any work.
    const int sock = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::snprintf(address.sun_path, sizeof address.sun_path, "%s", path("sock.vdb").c_str());
    ASSERT_EQ(bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    r = runSvo(run + path("sock.vdb"));
    close(sock);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(lineCount(r.out), 1u) << r.out;
    EXPECT_NE(r.out.find("is a socket"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::is_socket(path("sock.vdb")));
    // Character devices: a private /dev/null first (root only may make one), then /dev/null itself.
    const bool privateNull = mknod(path("null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
    for (const std::string& device : {path("null"), std::string("/dev/null")}) {
        if (device != "/dev/null" && !privateNull) continue;
        r = runSvo(run + path("a.vdb") + " --json " + device);
        EXPECT_EQ(r.code, 0) << device << "\n" << r.out;
        ASSERT_TRUE(fs::is_character_file(device)) << device << " was replaced";
    }
    // /dev/stdout, through a private link first: the JSON comes out on stdout as the outputs are put in
    // place, then the summary, which names only what is in place.
    fs::create_symlink("/proc/self/fd/1", path("stdout"));
    for (const std::string& out : {path("stdout"), std::string("/dev/stdout")}) {
        r = runSvo(run + path("b.vdb") + " --json " + out);
        EXPECT_EQ(r.code, 0) << out << "\n" << r.out;
        ASSERT_TRUE(fs::is_symlink(out)) << out << " was replaced";
        const auto summary = r.out.find("svo voxelize"), json = r.out.find("\"voxels\"");
        EXPECT_TRUE(summary != std::string::npos && json != std::string::npos && json < summary) << out << "\n" << r.out;
    }
    // And through a link to a FIFO or a device, with -o.
    fs::create_symlink(privateNull ? path("null") : std::string("/dev/null"), path("null.vdb"));
    r = runSvo(run + path("null.vdb"));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::is_symlink(path("null.vdb")));
    EXPECT_TRUE(fs::is_character_file(path("null.vdb")));
    // /dev/stdout redirected to a file: svo writes through its own stdout, so the file holds the JSON, then the summary.
    r = runShell(std::string(SVO_EXE) + " " + run + path("c.vdb") + " --json /dev/stdout > " + path("all.txt"));
    EXPECT_EQ(r.code, 0) << r.out;
    const std::string all = text(path("all.txt"));
    const auto summary = all.find("svo voxelize"), json = all.find("\"voxels\"");
    EXPECT_TRUE(summary != std::string::npos && json != std::string::npos && json < summary) << all;
    EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
}

/// An empty mesh path (an unset variable in a script) is an error, not the
/// built-in Cornell box that no mesh at all gives.
TEST_F(Cli, AnEmptyMeshPathIsAnErrorNotTheBuiltInScene)
{
    for (const std::string& args : {"voxelize '' -r 16 -o " + path("x.vdb"), "validate '' -r 16 --json " + path("x.json")}) {
        const auto r = runSvo(args);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.out;
        EXPECT_EQ(lineCount(r.out), 1u) << args << "\n" << r.out;
        EXPECT_NE(r.out.find("the mesh path is empty"), std::string::npos) << args << "\n" << r.out;
    }
    expectOnly({});
}

/// The small ways to lose a file or be misled: each works as expected or is refused.
TEST_F(Cli, SmallMisusesAreRefusedOrDoWhatTheySay)
{
    const std::string tetra = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string mesh = write("m.off", tetra);
    const auto cwd = fs::current_path();
    fs::current_path(tmp_.dir());
    // --repeat without -o times the runs and writes nothing.
    auto r = runSvo("voxelize m.off -r 16 --repeat 2");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("nothing written (--repeat without -o)"), std::string::npos) << r.out;
    EXPECT_NE(runSvo("voxelize m.off -r 16 --repeat 2 -v").out.find("none (--repeat without -o"), std::string::npos);
    EXPECT_FALSE(fs::exists(path("m.vdb")));
    // The default name is written, and replaced like any output, as vdb_tool does.
    EXPECT_EQ(runSvo("voxelize m.off -r 16").code, 0);
    const auto first = fs::file_size(path("m.vdb"));
    r = runSvo("voxelize m.off -r 32");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("wrote m.vdb"), std::string::npos) << r.out;
    EXPECT_NE(fs::file_size(path("m.vdb")), first);
    fs::current_path(cwd);
    // An empty path is refused, not replaced by the default name.
    for (const std::string& args : {"voxelize " + mesh + " -r 16 -o ''", "voxelize " + mesh + " -r 16 -o x.vdb --json ''",
                                    "validate " + mesh + " -r 16 --errors ''", "vtk " + mesh + " -r 16 --png ''"}) {
        r = runSvo(args);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.out;
        EXPECT_NE(r.out.find("the path is empty"), std::string::npos) << args << "\n" << r.out;
    }
    // A name must not hide its format.
    r = runSvo("vtk " + mesh + " -r 16 --png " + path("x.jpg"));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("must end in .png"), std::string::npos) << r.out;
    r = runSvo("validate " + mesh + " -r 16 --errors " + path("x.xyz"));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("must end in .vdb"), std::string::npos) << r.out;
    // Options that do not apply to .svo are refused.
    r = runSvo("voxelize " + mesh + " -r 16 --fog -o " + path("x.svo"));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("not .svo"), std::string::npos) << r.out;
    // Non-finite sizes are named as such.
    for (const std::string v : {"inf", "nan", "-1", "0"}) {
        r = runSvo("voxelize " + mesh + " --voxel-size " + v + " -o " + path("x.vdb"));
        EXPECT_EQ(r.code, 1) << v;
        EXPECT_NE(r.out.find("--voxel-size must be a positive finite number"), std::string::npos) << v << ": " << r.out;
    }
    // A damaged file's bytes are quoted escaped: no terminal control sequence gets through.
    const std::string garbage = write("g.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 \x1b[31mred\x07\n");
    r = runSvo("voxelize " + garbage + " -o " + path("x.vdb"));
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find('\x07'), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("[31mred\\x07"), std::string::npos) << r.out; // escaped, as \xNN
    expectOnly({"m.off", "m.vdb", "g.off"});
}

// Outputs are replaced, as vdb_tool replaces them; --no-clobber refuses an
// output that exists, before any work and in one line, for every command
// that writes, and leaves the file as it was. (Inputs are never outputs:
// NoOutputIsEverAnInputHoweverItIsNamed.)
TEST_F(Cli, OutputsAreReplacedUnlessNoClobberRefusesThem)
{
    const std::string mesh = write("m.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    ASSERT_EQ(runSvo("voxelize " + mesh + " -r 16 -o " + path("a.svo")).code, 0);
    const auto small = fs::file_size(path("a.svo"));
    ASSERT_EQ(runSvo("voxelize " + mesh + " -r 64 -o " + path("a.svo")).code, 0);
    EXPECT_GT(fs::file_size(path("a.svo")), small);
    const std::vector<std::string> kept = {"k.vdb", "k.json", "k.svo", "k.obj", "k.png", "n.triangle.vdb"};
    for (const auto& name : kept) write(name, "earlier");
    const std::vector<std::pair<std::string, std::string>> attempts = {
        {"voxelize " + mesh + " -r 16 --no-clobber -o " + path("k.vdb"), "k.vdb"},
        {"voxelize " + mesh + " -r 16 --no-clobber -o " + path("n.vdb") + " --json " + path("k.json"), "k.json"},
        {"voxelize " + mesh + " -r 16 --attributes triangle --no-clobber -o " + path("n.vdb"), "n.triangle.vdb"},
        {"voxelize " + mesh + " -r 16 --sdf --closest-triangle --no-clobber -o " + path("n.vdb"), "n.triangle.vdb"},
        {"convert " + path("a.svo") + " --no-clobber -o " + path("k.svo"), "k.svo"},
        {"scene cornell --no-clobber -o " + path("k.obj"), "k.obj"},
        {"view " + path("a.svo") + " --size 64x48 --no-clobber --screenshot " + path("k.png"), "k.png"},
        {"validate " + mesh + " -r 16 --no-clobber --json " + path("k.json"), "k.json"},
        {"vtk " + path("a.svo") + " --no-clobber --png " + path("k.png"), "k.png"},
    };
    for (const auto& [args, refused] : attempts) {
        const auto r = runSvo(args);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.out;
        EXPECT_EQ(r.out, "svo: error: " + path(refused) + ": exists, and --no-clobber refuses to replace it\n") << args;
        for (const auto& name : kept) EXPECT_EQ(fileText(path(name)), "earlier") << args << ": " << name;
    }
    // Without it, each is replaced.
    const auto r = runSvo("convert " + path("a.svo") + " -o " + path("k.svo"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(fs::file_size(path("k.svo")), fs::file_size(path("a.svo")));
    ASSERT_EQ(runSvo("scene cornell -q -o " + path("k.obj")).code, 0);
    EXPECT_NE(fileText(path("k.obj")), "earlier");
    std::vector<std::string> all = kept;
    all.insert(all.end(), {"m.off", "a.svo"});
    expectOnly(all);
}

// A .vdb written with default options opens whole in python3-openvdb, whatever
// channels were asked for: triangle indices (Int32Grid, which it lacks) go to
// <output>.triangle.vdb, named in the summary, which OpenVDB's vdb_print reads,
// over the same voxels as the output.
TEST_F(Cli, DefaultOutputsOpenWholeInPyopenvdbAndTriangleIndicesGoBeside)
{
    ASSERT_EQ(runSvo("scene icosphere --level 2 -o " + path("ico.off")).code, 0);
    ASSERT_EQ(runSvo("voxelize -r 32 --attributes normal,triangle -o " + path("attr.svo")).code, 0);
    const std::string gridsOf = "/usr/bin/python3 -c \"import pyopenvdb,sys; g,_=pyopenvdb.readAll(sys.argv[1]); "
                                "print(' '.join(sorted(x.name+':'+x.valueTypeName for x in g)))\" ";
    struct Case {
        std::string args, output, grids, sidecarGrid;
    };
    const std::vector<Case> cases = {
        {"voxelize -r 32 --attributes normal,triangle,color", "attr.vdb", "color:vec3s normal:vec3s surface:bool",
         "triangle_id"},
        {"voxelize " + path("ico.off") + " -r 32 --sdf --closest-triangle", "ls.vdb", "surface:float", "closest_triangle"},
        {"voxelize " + path("ico.off") + " -r 32 --udf --closest-triangle", "udf.vdb", "distance:float",
         "closest_triangle"},
        {"convert " + path("attr.svo"), "conv.vdb", "normal:vec3s surface:bool", "triangle_id"},
        {"voxelize " + path("ico.off") + " -r 32 --fill solid", "solid.vdb", "solid:bool", ""},
        {"voxelize -r 32 --fog --attributes normal", "fog.vdb", "density:float normal:vec3s surface:bool", ""},
    };
    std::vector<std::string> files = {"ico.off", "attr.svo"};
    for (const auto& c : cases) {
        const auto r = runSvo(c.args + " -o " + path(c.output));
        ASSERT_EQ(r.code, 0) << c.args << "\n" << r.out;
        files.push_back(c.output);
        EXPECT_EQ(runCommand(gridsOf + path(c.output)), c.grids + "\n") << c.args;
        const std::string sidecar = c.output.substr(0, c.output.size() - 4) + ".triangle.vdb";
        if (c.sidecarGrid.empty()) continue;
        files.push_back(sidecar);
        EXPECT_NE(r.out.find("; " + c.sidecarGrid + " in " + path(sidecar) + "\n"), std::string::npos) << r.out;
        const std::string printed = runCommand("vdb_print -l " + path(sidecar)), main = runCommand("vdb_print -l " + path(c.output));
        EXPECT_NE(printed.find("Name: " + c.sidecarGrid), std::string::npos) << printed;
        EXPECT_NE(printed.find("Type: Tree_int32_5_4_3"), std::string::npos) << printed;
        // The indices cover the output's voxels: its topology grid (every voxel) or its band.
        EXPECT_EQ(activeVoxels(printed), activeVoxels(main)) << c.args << "\n" << printed << main;
        // What the output would be refused for, had the indices stayed in it.
        EXPECT_NE(runCommand(gridsOf + path(sidecar)).find("Tree_int32_5_4_3 is not a supported OpenVDB grid type"),
                  std::string::npos);
    }
    expectOnly(files);
}

// A run that writes out.vdb without triangle indices removes the
// out.triangle.vdb an earlier run wrote beside it (it holds the indices of an
// output that is gone) and says so in its summary; only a file svo marked as
// out.vdb's sidecar (metadata svo:sidecar_of), never an input, never another
// output's, never with --no-clobber (a warning says it was left).
TEST_F(Cli, AStaleTriangleSidecarIsRemovedOnlyWhenItIsTheOutputsOwn)
{
    const std::string mesh = write("m.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    ASSERT_EQ(runSvo("voxelize " + mesh + " -r 16 --attributes triangle -o " + path("attr.svo")).code, 0);
    ASSERT_EQ(runSvo("voxelize " + mesh + " -r 16 -o " + path("plain.svo")).code, 0);
    const std::string m = "voxelize " + mesh + " -r 16 ";
    struct Case {
        std::string withIndices, without;
    };
    // Surface voxels, level sets and unsigned distances, convert; the later run of another kind, or -v.
    const std::vector<Case> cases = {
        {m + "--attributes normal,triangle", m},
        {m + "--sdf --closest-triangle", m + "--sdf"},
        {m + "--udf --closest-triangle", m + "--fill solid"},
        {m + "--attributes triangle", m + "--sdf -v"},
        {"convert " + path("attr.svo"), "convert " + path("plain.svo")},
        {"convert " + path("attr.svo"), "convert " + path("plain.svo") + " -v"},
    };
    std::vector<std::string> files = {"m.off", "attr.svo", "plain.svo"};
    for (size_t i = 0; i < cases.size(); ++i) {
        const std::string out = path("o" + std::to_string(i) + ".vdb"), sidecar = path("o" + std::to_string(i) + ".triangle.vdb");
        files.push_back("o" + std::to_string(i) + ".vdb");
        ASSERT_EQ(runSvo(cases[i].withIndices + " -o " + out).code, 0) << cases[i].withIndices;
        ASSERT_TRUE(fs::exists(sidecar)) << cases[i].withIndices;
        const auto r = runSvo(cases[i].without + " -o " + out);
        ASSERT_EQ(r.code, 0) << cases[i].without << "\n" << r.out;
        EXPECT_FALSE(fs::exists(sidecar)) << cases[i].without;
        const std::string said = sidecar + ", the triangle indices of an earlier o" + std::to_string(i) + ".vdb";
        if (cases[i].without.find(" -v") == std::string::npos) {
            EXPECT_EQ(lineCount(r.out), 1u) << r.out;
            EXPECT_NE(r.out.find("; removed " + said + "\n"), std::string::npos) << r.out;
        } else {
            EXPECT_NE(r.out.find("  removed" + std::string(cases[i].without.rfind("convert", 0) == 0 ? 6 : 5, ' ') +
                                 said + "\n"),
                      std::string::npos)
                << r.out;
        }
    }

    // s.triangle.vdb, written for s.vdb; OpenVDB's vdb_print reads the mark.
    ASSERT_EQ(runSvo(m + "--attributes triangle -o " + path("s.vdb")).code, 0);
    const std::string own = path("s.triangle.vdb");
    EXPECT_NE(runCommand("vdb_print -l -m " + own).find("svo:sidecar_of: s.vdb"), std::string::npos)
        << runCommand("vdb_print -l -m " + own);
    const std::string ownBytes = fileText(own);
    // Kept: for another output (t.vdb, u.vdb, s.svo, s.nvdb), as a link, not svo's, an input, or --no-clobber.
    fs::copy_file(own, path("t.triangle.vdb"));
    fs::create_symlink(own, path("u.triangle.vdb"));
    write("f.triangle.vdb", "not svo's");
    files.insert(files.end(), {"s.vdb", "s.triangle.vdb", "t.vdb", "t.triangle.vdb", "u.vdb", "u.triangle.vdb", "f.vdb",
                               "f.triangle.vdb", "s.svo", "s.nvdb"});
    for (const std::string& args : {m + "-o " + path("t.vdb"), m + "-o " + path("u.vdb"), m + "-o " + path("f.vdb"),
                                    m + "-o " + path("s.svo"), m + "-o " + path("s.nvdb"),
                                    "convert " + own + " -o " + path("s.vdb")}) {
        const auto r = runSvo(args);
        ASSERT_EQ(r.code, 0) << args << "\n" << r.out;
        EXPECT_EQ(r.out.find("removed"), std::string::npos) << args << "\n" << r.out;
        EXPECT_EQ(fileText(own), ownBytes) << args;
    }
    EXPECT_EQ(fileText(path("t.triangle.vdb")), ownBytes);
    EXPECT_EQ(fileText(path("f.triangle.vdb")), "not svo's");
    EXPECT_TRUE(fs::is_symlink(path("u.triangle.vdb")));
    fs::remove(path("s.vdb"));
    const auto kept = runSvo(m + "--no-clobber -o " + path("s.vdb"));
    ASSERT_EQ(kept.code, 0) << kept.out;
    EXPECT_NE(kept.out.find("svo: warning: " + own + ": left in place (--no-clobber)"), std::string::npos) << kept.out;
    EXPECT_EQ(fileText(own), ownBytes);
    // A later run with indices replaces them, and -q says nothing of a removal.
    const auto again = runSvo("voxelize " + mesh + " -r 20 --attributes triangle -o " + path("s.vdb"));
    ASSERT_EQ(again.code, 0) << again.out;
    EXPECT_NE(again.out.find("; triangle_id in " + own + "\n"), std::string::npos) << again.out;
    EXPECT_NE(activeVoxels(runCommand("vdb_print -l " + own)), activeVoxels(runCommand("vdb_print -l " + path("t.triangle.vdb"))));
    const auto quiet = runSvo(m + "-q -o " + path("s.vdb"));
    EXPECT_EQ(quiet.code, 0);
    EXPECT_EQ(quiet.out, "");
    EXPECT_FALSE(fs::exists(own));
    files.erase(std::find(files.begin(), files.end(), "s.triangle.vdb"));
    expectOnly(files);
}

// A GPU memory budget below what the grid needs: the grid is voxelized in
// tiles, with the voxels of the untiled run, and vdb_print reads the file.
TEST_F(Cli, AGpuMemoryBudgetTilesTheGridToTheSameVoxels)
{
    auto read = [&](const std::string& name) {
        std::ifstream in(path(name));
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    auto number = [](const std::string& json, const std::string& key) {
        std::smatch m;
        return std::regex_search(json, m, std::regex("\"" + key + "\": ([0-9]+)")) ? std::stoull(m[1]) : 0ull;
    };
    // The budget asks auto for the GPU passes; the whole grid names them.
    auto r = runSvo("voxelize -r 128 --backend raster -o " + path("whole.vdb") + " --json " + path("whole.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    r = runSvo("voxelize -r 128 -v --gpu-memory 2.5MiB -o " + path("tiled.vdb") + " --json " + path("tiled.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(" tiles"), std::string::npos) << r.out;
    const std::string whole = read("whole.json"), tiled = read("tiled.json");
    EXPECT_EQ(number(whole, "tiles"), 1u) << whole;
    EXPECT_GT(number(tiled, "tiles"), 1u) << tiled;
    EXPECT_LE(number(tiled, "gpu_bytes"), uint64_t(2.5 * (1 << 20))) << tiled;
    EXPECT_EQ(number(tiled, "voxels"), number(whole, "voxels"));
    EXPECT_EQ(number(tiled, "bricks"), number(whole, "bricks"));
    EXPECT_EQ(number(tiled, "list_entries"), number(whole, "list_entries"));
    const std::string printed = runCommand("vdb_print -l " + path("tiled.vdb"));
    EXPECT_NE(printed.find(fmt("file_voxel_count: {}\n", number(whole, "voxels"))), std::string::npos) << printed;

    for (const std::string& bad : {"--gpu-memory 12Q", "--gpu-memory 0", "--gpu-memory -5M", "--gpu-memory 1K",
                                   "--gpu-memory 1G --backend cpu"}) {
        r = runSvo("voxelize -r 32 " + bad + " -o " + path("x.vdb"));
        EXPECT_EQ(r.code, 1) << bad << "\n" << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << bad << "\n" << r.out;
    }
    // The library's rule, in the CLI's words, for surfaces and fields alike.
    for (const char* kind : {"", " --sdf", " --fill solid"}) {
        r = runSvo(std::string("voxelize -r 32 --backend cpu --gpu-memory 1G") + kind + " -o " + path("x.vdb"));
        EXPECT_EQ(r.code, 1) << kind;
        EXPECT_EQ(r.out, "svo: error: --gpu-memory applies to the GPU backends, not to --backend cpu\n") << kind;
    }
    expectOnly({"whole.vdb", "whole.json", "tiled.vdb", "tiled.json"});
}

// A voxel size below what OpenVDB's transforms take (a millimetre mesh at a
// fine resolution) is refused for .vdb before any work; .svo still takes it.
TEST_F(Cli, AVoxelSizeOpenVdbCannotHoldIsRefusedBeforeAnyWork)
{
    const std::string mesh = write("tiny.off", "OFF\n4 4 0\n0 0 0\n0.001 0 0\n0 0.001 0\n0 0 0.001\n"
                                               "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    for (const std::string& extra : {std::string(), std::string(" --sdf")}) {
        const auto r = runSvo("voxelize " + mesh + " -r 100" + extra + " -o " + path("t.vdb"));
        EXPECT_EQ(r.code, 1) << r.out;
        EXPECT_NE(r.out.find("t.vdb: voxel size 1e-05 is below the smallest an OpenVDB transform takes"),
                  std::string::npos)
            << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    }
    auto r = runSvo("voxelize " + mesh + " -r 100 -o " + path("t.svo"));
    EXPECT_EQ(r.code, 0) << r.out;
    r = runSvo("voxelize " + mesh + " -r 60 -o " + path("t.vdb")); // 1.67e-5: above the limit
    EXPECT_EQ(r.code, 0) << r.out;
    expectOnly({"tiny.off", "t.svo", "t.vdb"});
}

// --sdf, --udf and --fill solid write .nvdb too, laid out from the bricks:
// NanoVDB's own validator passes each file, and svo info reads its grid back
// with the .vdb output's voxel count.
TEST_F(Cli, LevelSetsAndSolidsWriteNanoVdb)
{
    ASSERT_EQ(runSvo("scene icosphere --level 3 -o " + path("ico.off")).code, 0);
    for (const std::string kind : {"--sdf", "--udf", "--fill solid", "--fill solid --topology mask"}) {
        const auto nano = runSvo("voxelize " + path("ico.off") + " -r 32 " + kind + " -o " + path("f.nvdb") + " --json " +
                                 path("n.json"));
        ASSERT_EQ(nano.code, 0) << kind << ": " << nano.out;
        EXPECT_EQ(runCommand("nanovdb_validate " + path("f.nvdb") + " >/dev/null 2>&1 && echo valid"), "valid\n") << kind;
        const auto vdb = runSvo("voxelize " + path("ico.off") + " -r 32 " + kind + " -o " + path("f.vdb") + " --json " +
                                path("v.json"));
        ASSERT_EQ(vdb.code, 0) << kind << ": " << vdb.out;
        auto voxels = [&](const std::string& json) {
            const std::string text = runCommand("cat " + path(json));
            const auto at = text.find("\"active_voxels\": ");
            return at == std::string::npos ? std::string() : text.substr(at, text.find_first_of(",\n", at) - at);
        };
        EXPECT_FALSE(voxels("n.json").empty()) << kind;
        EXPECT_EQ(voxels("n.json"), voxels("v.json")) << kind;
        const auto info = runSvo("info " + path("f.nvdb"));
        EXPECT_EQ(info.code, 0) << kind << ": " << info.out;
    }
    // Without --grid, info describes the file's main grid, not a channel
    // that sorts before it: the level set beside its closest triangles, the
    // surface beside its normals.
    const std::string ico = "voxelize " + path("ico.off") + " -r 32 ";
    ASSERT_EQ(runSvo(ico + "--sdf --closest-triangle -o " + path("f.nvdb")).code, 0);
    EXPECT_NE(runSvo("info " + path("f.nvdb")).out.find("grid 'surface' (Tree_float_5_4_3"), std::string::npos);
    ASSERT_EQ(runSvo(ico + "--attributes normal -o " + path("f.vdb")).code, 0);
    EXPECT_NE(runSvo("info " + path("f.vdb")).out.find("grid 'surface' (Tree_bool_5_4_3"), std::string::npos);
    expectOnly({"ico.off", "f.nvdb", "f.vdb", "n.json", "v.json"});
}

// --fill band: the voxels nearer than --band to a triangle, the active
// voxels of --udf with that band, as a topology grid 'band' (.vdb and
// .nvdb, mask or bool); the same bytes on the CPU and compute backends and
// in regions under a GPU memory budget; NanoVDB's validator passes it.
TEST_F(Cli, ABandIsTheUnsignedFieldsActiveVoxels)
{
    ASSERT_EQ(runSvo("scene icosphere --level 3 -o " + path("ico.off")).code, 0);
    const std::string call = "voxelize " + path("ico.off") + " -r 40 --band 2.5 ";
    auto voxels = [&](const std::string& json) {
        const std::string text = runCommand("cat " + path(json));
        const auto at = text.find("\"active_voxels\": ");
        return at == std::string::npos ? std::string() : text.substr(at, text.find_first_of(",\n", at) - at);
    };
    ASSERT_EQ(runSvo(call + "--udf -o " + path("u.vdb") + " --json " + path("u.json")).code, 0);
    ASSERT_FALSE(voxels("u.json").empty());
    const std::vector<std::string> files = {"cpu.nvdb", "compute.nvdb", "budget.nvdb"};
    for (const std::string topology : {"mask", "bool"}) {
        SCOPED_TRACE(topology);
        const std::string band = call + "--fill band --topology " + topology + " ";
        for (const char* backend : {"cpu", "compute"}) {
            const auto r = runSvo(band + "--backend " + backend + " -o " + path(std::string(backend) + ".nvdb") +
                                  " --json " + path("b.json"));
            ASSERT_EQ(r.code, 0) << r.out;
            EXPECT_NE(r.out.find("band, " + topology + " 'band'"), std::string::npos) << r.out;
            EXPECT_EQ(voxels("b.json"), voxels("u.json")) << backend;
        }
        ASSERT_EQ(runSvo(band + "--backend compute --gpu-memory 1M -o " + path("budget.nvdb")).code, 0);
        for (const auto& f : files)
            EXPECT_EQ(runCommand("nanovdb_validate " + path(f) + " >/dev/null 2>&1 && echo valid"), "valid\n") << f;
        EXPECT_EQ(runCommand("cmp " + path("cpu.nvdb") + " " + path("compute.nvdb") + " && echo same"), "same\n");
        EXPECT_EQ(runCommand("cmp " + path("cpu.nvdb") + " " + path("budget.nvdb") + " && echo same"), "same\n");
        ASSERT_EQ(runSvo(band + "-o " + path("b.vdb") + " --json " + path("b.json")).code, 0);
        EXPECT_EQ(voxels("b.json"), voxels("u.json"));
        EXPECT_NE(runSvo("info " + path("b.vdb")).out.find("grid 'band' (Tree_" + topology), std::string::npos);
    }
    // What --fill band does not take, refused before any work.
    for (const std::string bad : {"--fill band --interior-band 2 -o " + path("x.vdb"),
                                  "--fill band --closest-triangle -o " + path("x.vdb"),
                                  "--fill band --sign winding -o " + path("x.vdb"),
                                  "--fill band --udf -o " + path("x.vdb"), "--fill band -o " + path("x.svo")}) {
        const auto r = runSvo(call + bad);
        EXPECT_NE(r.code, 0) << bad;
        EXPECT_NE(r.out.find("error"), std::string::npos) << bad << ": " << r.out;
    }
    expectOnly({"ico.off", "u.vdb", "u.json", "cpu.nvdb", "compute.nvdb", "budget.nvdb", "b.json", "b.vdb"});
}

// A region no triangle reaches writes the grids and sidecar of any other
// region, empty: a pipeline that reads a region's 'normal' or
// 'triangle_id' finds it whether or not the region holds voxels.
TEST_F(Cli, AnEmptyRegionWritesTheGridsOfAnyOtherRegion)
{
    ASSERT_EQ(runSvo("scene icosphere --level 2 -o " + path("ico.off")).code, 0);
    const std::string call = "voxelize " + path("ico.off") +
                             " -r 32 --attributes normal triangle --region=1024,1024,1024,1032,1032,1032 -o ";
    for (const char* backend : {"cpu", "compute"}) {
        SCOPED_TRACE(backend);
        const auto vdb = runSvo(call + path("e.vdb") + " --backend " + backend);
        ASSERT_EQ(vdb.code, 0) << vdb.out;
        EXPECT_NE(vdb.out.find("0 voxels"), std::string::npos) << vdb.out;
        EXPECT_EQ(runSvo("info " + path("e.vdb") + " --grid normal").code, 0);
        EXPECT_EQ(runSvo("info " + path("e.triangle.vdb") + " --grid triangle_id").code, 0);
        ASSERT_EQ(runSvo(call + path("e.nvdb") + " --backend " + backend).code, 0);
        for (const char* grid : {"surface", "normal", "triangle_id"})
            EXPECT_EQ(runSvo("info " + path("e.nvdb") + " --grid " + grid).code, 0) << grid;
        EXPECT_EQ(runCommand("nanovdb_validate " + path("e.nvdb") + " >/dev/null 2>&1 && echo valid"), "valid\n");
    }
    expectOnly({"ico.off", "e.vdb", "e.triangle.vdb", "e.nvdb"});
}

// A surface's .nvdb on a GL backend is laid out by the GPU builder (the -v
// stages say so): the same bytes as the CPU backend's CPU layout, fog
// included, and NanoVDB's validator passes it.
TEST_F(Cli, SurfaceNanoVdbOnTheGpuIsTheCpuLayoutsBytes)
{
    ASSERT_EQ(runSvo("scene icosphere --level 3 -o " + path("ico.off")).code, 0);
    for (const std::string kind : {"", "--fog ", "--topology mask "}) {
        const auto gpu = runSvo("voxelize " + path("ico.off") + " -r 40 -v --backend compute " + kind + "-o " + path("g.nvdb"));
        ASSERT_EQ(gpu.code, 0) << kind << gpu.out;
        EXPECT_NE(gpu.out.find("nanovdb grid (gpu)"), std::string::npos) << kind << gpu.out;
        const auto cpu = runSvo("voxelize " + path("ico.off") + " -r 40 -v --backend cpu " + kind + "-o " + path("c.nvdb"));
        ASSERT_EQ(cpu.code, 0) << kind << cpu.out;
        EXPECT_NE(cpu.out.find("nvdb build (cpu)"), std::string::npos) << kind << cpu.out;
        EXPECT_EQ(runCommand("cmp " + path("g.nvdb") + " " + path("c.nvdb") + " && echo same"), "same\n") << kind;
        EXPECT_EQ(runCommand("nanovdb_validate " + path("g.nvdb") + " >/dev/null 2>&1 && echo valid"), "valid\n") << kind;
    }
    expectOnly({"ico.off", "g.nvdb", "c.nvdb"});
}

// --codec compresses .nvdb output with NanoVDB's codecs: NanoVDB's validator and
// svo info read each file, smaller than the plain one; another output refuses it.
TEST_F(Cli, NanoVdbOutputTakesNanoVdbsCodecs)
{
    ASSERT_EQ(runSvo("scene icosphere --level 3 -o " + path("ico.off")).code, 0);
    for (const std::string kind : {"", "--sdf "}) {
        std::map<std::string, uintmax_t> sizes;
        for (const std::string codec : {"none", "zip", "blosc"}) {
            const std::string out = path(codec + ".nvdb");
            const auto r = runSvo("voxelize " + path("ico.off") + " -r 48 " + kind + "--codec " + codec + " -o " + out);
            ASSERT_EQ(r.code, 0) << kind << codec << ": " << r.out;
            EXPECT_EQ(runCommand("nanovdb_validate " + out + " >/dev/null 2>&1 && echo valid"), "valid\n") << kind << codec;
            const auto info = runSvo("info " + out);
            EXPECT_EQ(info.code, 0) << kind << codec << ": " << info.out;
            sizes[codec] = std::filesystem::file_size(out);
        }
        EXPECT_LT(sizes["zip"], sizes["none"]) << kind;
        EXPECT_LT(sizes["blosc"], sizes["none"]) << kind;
    }
    const auto refused = runSvo("voxelize " + path("ico.off") + " -r 16 --codec zip -o " + path("x.vdb"));
    EXPECT_NE(refused.code, 0);
    EXPECT_NE(refused.out.find("x.vdb: --codec applies to .nvdb output"), std::string::npos) << refused.out;
    expectOnly({"ico.off", "none.nvdb", "zip.nvdb", "blosc.nvdb"});
}

// --sdf and --fill solid write grids that OpenVDB's own vdb_print reads as a
// level set and a solid; combinations without meaning are refused first.
TEST_F(Cli, LevelSetsAndSolidsAreGridsVdbPrintReads)
{
    ASSERT_EQ(runSvo("scene icosphere --level 3 -o " + path("ico.off")).code, 0);
    const auto sdf = runSvo("voxelize " + path("ico.off") + " -r 32 -v --sdf --exterior-band 2 --interior-band 4 -o " +
                            path("ls.vdb"));
    ASSERT_EQ(sdf.code, 0) << sdf.out;
    EXPECT_NE(sdf.out.find("parity: the mesh is closed and consistently oriented"), std::string::npos) << sdf.out;
    const auto printed = runCommand("vdb_print -l " + path("ls.vdb"));
    EXPECT_NE(printed.find("class: level set"), std::string::npos) << printed;
    EXPECT_NE(printed.find("Name: surface"), std::string::npos) << printed;
    // A solid is a BoolGrid like every other output, a MaskGrid on request:
    // the same active voxels and tiles either way.
    const auto solid = runSvo("voxelize " + path("ico.off") + " -r 64 --fill solid -o " + path("solid.vdb"));
    ASSERT_EQ(solid.code, 0) << solid.out;
    EXPECT_NE(solid.out.find("(solid, bool 'solid', "), std::string::npos) << solid.out;
    const auto mask = runSvo("voxelize " + path("ico.off") + " -r 64 --fill solid --topology mask -o " + path("mask.vdb"));
    ASSERT_EQ(mask.code, 0) << mask.out;
    const std::string boolPrinted = runCommand("vdb_print -l " + path("solid.vdb")),
                      maskPrinted = runCommand("vdb_print -l " + path("mask.vdb"));
    EXPECT_NE(boolPrinted.find("Name: solid"), std::string::npos) << boolPrinted;
    EXPECT_NE(boolPrinted.find("Type: Tree_bool_5_4_3"), std::string::npos) << boolPrinted;
    EXPECT_NE(maskPrinted.find("Type: Tree_mask_5_4_3"), std::string::npos) << maskPrinted;
    const std::string count = activeVoxels(boolPrinted);
    EXPECT_EQ(activeVoxels(maskPrinted), count);
    EXPECT_NE(solid.out.find(" " + count + " active voxels"), std::string::npos) << solid.out;
    EXPECT_EQ(runCommand("/usr/bin/python3 -c \"import pyopenvdb,sys; g=pyopenvdb.read(sys.argv[1], 'solid'); "
                         "print(g.valueTypeName, '{:,}'.format(g.activeVoxelCount()))\" " + path("solid.vdb")),
              "bool " + count + "\n");

    for (const char* bad : {"--sdf -o x.svo", "--band 2", "--sdf --udf", "--udf --interior-band 2", "--sdf --band 2 "
                            "--exterior-band 3", "--fill solid --attributes normal", "--closest-triangle",
                            "--sdf --topology mask", "--udf --topology bool", "--fill solid --fog",
                            "--sdf --band 0.5", "--winding-accuracy 3", "--sdf --backend raster",
                            "--udf --conservative hardware", "--part-of-closed-mesh",
                            "--sdf --sign winding --part-of-closed-mesh"}) {
        const auto r = runSvo("voxelize " + path("ico.off") + " " + bad + (std::string(bad).find(" -o ") == std::string::npos ? " -o " + path("bad.vdb") : std::string()));
        EXPECT_EQ(r.code, 1) << bad << ": " << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << bad << ": " << r.out; // one line
    }
    const auto parityOnly = runSvo("voxelize " + path("ico.off") + " --sdf --sign parity --winding-accuracy 3 -o " +
                                   path("bad.vdb"));
    EXPECT_EQ(parityOnly.code, 1) << parityOnly.out;
    EXPECT_NE(parityOnly.out.find("--winding-accuracy applies to winding-number signs"), std::string::npos)
        << parityOnly.out;
    // The built-in Cornell box is an open room: its sign comes from the winding number, and says why.
    const auto open = runSvo("voxelize -r 16 -v --sdf -o " + path("cb.vdb"));
    EXPECT_EQ(open.code, 0) << open.out;
    EXPECT_NE(open.out.find("winding: the mesh is not closed (116 boundary edges)"), std::string::npos) << open.out;
    EXPECT_NE(runCommand("vdb_print -l " + path("cb.vdb")).find("class: level set"), std::string::npos);
    expectOnly({"ico.off", "ls.vdb", "solid.vdb", "mask.vdb", "cb.vdb"});
}

// svo scene city: a mesh of about --triangles from --seed, the same file for
// the same seed, which svo voxelize reads; --triangles and --seed mean
// nothing to the other scenes and are refused there.
TEST_F(Cli, SceneCityWritesAMeshThatVoxelizeReads)
{
    const auto r = runSvo("scene city --triangles 20000 --seed 3 -o " + path("x.obj"));
    ASSERT_EQ(r.code, 0) << r.out;
    std::smatch count;
    ASSERT_TRUE(std::regex_search(r.out, count, std::regex(R"(city \(seed 3, 20,000 triangles\) \(((19|20),[0-9]{3}) triangles)")))
        << r.out;
    ASSERT_EQ(runSvo("scene city --seed 3 --triangles 20000 -o " + path("y.obj")).code, 0);
    const auto bytes = [&](const std::string& name) {
        std::ifstream in(path(name), std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    EXPECT_EQ(bytes("x.obj"), bytes("y.obj"));
    const auto v = runSvo("voxelize " + path("x.obj") + " -r 128 -v -o " + path("x.vdb"));
    ASSERT_EQ(v.code, 0) << v.out;
    EXPECT_NE(v.out.find("triangles   " + count[1].str()), std::string::npos) << v.out;
    EXPECT_NE(runCommand("vdb_print -l " + path("x.vdb")).find("Name: surface"), std::string::npos);
    for (const char* bad : {"cornell --seed 2", "icosphere --triangles 5000", "city --triangles 999",
                            "city --triangles 1000000001", "city --triangles 1e5", "city --seed -1",
                            "city --seed=-5"}) {
        const auto b = runSvo(std::string("scene ") + bad + " -o " + path("bad.obj"));
        EXPECT_EQ(b.code, 1) << bad << ": " << b.out;
        EXPECT_EQ(std::count(b.out.begin(), b.out.end(), '\n'), 1) << bad << ": " << b.out;
    }
    expectOnly({"x.obj", "y.obj", "x.vdb"});
}

// svo validate --sdf: svo's level set against CGAL (and beside OpenVDB's);
// options that need --sdf, or mean nothing with it, are refused in one line.
TEST_F(Cli, ValidateSdfPassesOnClosedAndOpenMeshesAndRefusesMisuse)
{
    ASSERT_EQ(runSvo("scene icosphere --level 3 -o " + path("ico.off")).code, 0);
    const auto r = runSvo("validate " + path("ico.off") + " -r 32 --sdf --exterior-band 2 --interior-band 4 --json " +
                          path("v.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* line : {"parity: the mesh is closed", "max error", "0 differ from CGAL's Side_of_triangle_mesh",
                             "0 missing, 0 extra", "meshToLevelSet", "verdict      passed"})
        EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
    std::ifstream in(path("v.json"));
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* field : {"\"kind\": \"sdf\"", "\"exterior_band\": 2.0", "\"interior_band\": 4.0",
                              "\"sign_checked\": true", "\"missing\": 0,", "\"extra\": 0,", "\"over_tolerance\": 0,",
                              "\"passed\": true", "\"only_openvdb\""})
        EXPECT_NE(json.find(field), std::string::npos) << field << "\n" << json;
    // The built-in Cornell box is open: signs are not checked, and the report says why.
    const auto open = runSvo("validate -r 16 --sdf");
    EXPECT_EQ(open.code, 0) << open.out;
    EXPECT_NE(open.out.find("winding: the mesh is not closed"), std::string::npos) << open.out;
    EXPECT_NE(open.out.find("not checked against CGAL: the mesh is open"), std::string::npos) << open.out;

    const std::pair<const char*, const char*> misuses[] = {
        {"--band 2", "apply to --sdf"},
        {"--interior-band 2", "apply to --sdf"},
        {"--sign winding", "--sign applies to --sdf"},
        {"--winding-accuracy 3", "--winding-accuracy applies to --sdf"},
        {"--sdf --band 2 --exterior-band 3", "--band sets both bands"},
        {"--sdf --sign parity --winding-accuracy 3", "not to --sign parity"},
        {"--sdf --mode thin", "--mode applies to surface voxels"},
        {"--sdf --errors e.vdb", "does not apply to --sdf"},
        {"--sdf --no-holes", "not to --sdf"},
        {"--sdf --strict", "not to --sdf"},
        {"--sdf --backend raster", "compute passes only"},
        {"--sdf --conservative shader", "compute passes only"}};
    for (const auto& [bad, message] : misuses) {
        const auto m = runSvo("validate " + path("ico.off") + " -r 16 " + bad);
        EXPECT_EQ(m.code, 1) << bad << ": " << m.out;
        EXPECT_EQ(std::count(m.out.begin(), m.out.end(), '\n'), 1) << bad << ": " << m.out;
        EXPECT_NE(m.out.find(message), std::string::npos) << bad << ": " << m.out;
    }
    expectOnly({"ico.off", "v.json"});
}

namespace {


TEST_F(Cli, ViewScreenshotWritesAPngOfTheAskedSize)
{
    const auto r = runSvo("view -r 16 --screenshot " + path("cb.png") +
                          " --size 64x48 --view +z --layers voxels,outlines,bricks,mesh --levels 1:2 --attributes "
                          "normal --color normal");
    ASSERT_EQ(r.code, 0) << r.out;
    std::ifstream f(path("cb.png"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 33u);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_EQ(bytes.substr(12, 4), "IHDR");
    auto be32 = [&](size_t at) {
        return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
               uint32_t(uint8_t(bytes[at + 2])) << 8 | uint32_t(uint8_t(bytes[at + 3]));
    };
    EXPECT_EQ(be32(16), 64u);
    EXPECT_EQ(be32(20), 48u);
    expectOnly({"cb.png"}); // no temporary left beside it
}

TEST_F(Cli, ViewBadInputFailsAsVoxelizeDoes)
{
    const std::string missing = path("missing.obj");
    const auto view = runSvo("view " + missing + " --screenshot " + path("x.png"));
    const auto voxelize = runSvo("voxelize " + missing + " -o " + path("x.vdb"));
    EXPECT_EQ(view.code, 1);
    EXPECT_EQ(lineCount(view.out), 1u) << view.out;
    EXPECT_NE(view.out.find("missing.obj"), std::string::npos) << view.out;
    EXPECT_EQ(view.out, voxelize.out);
    const auto bad = runSvo("view " + write("bad.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n") + " --screenshot " + path("x.png"));
    EXPECT_EQ(bad.code, 1);
    EXPECT_EQ(lineCount(bad.out), 1u) << bad.out;
    EXPECT_EQ(bad.out, runSvo("voxelize " + path("bad.obj") + " -o " + path("x.vdb")).out);
    for (const char* args : {"--size 0x10", "--layers voxels,bogus", "--levels 3:1", "--camera 1,2,3", "--view sideways",
                             "--color normal", "--color triangle --attributes normal", "--color rainbow"}) {
        const auto r = runSvo(std::string("view -r 8 --screenshot ") + path("x.png") + " " + args);
        EXPECT_EQ(r.code, 1) << args;
        EXPECT_EQ(lineCount(r.out), 1u) << args << ": " << r.out;
    }
    expectOnly({"bad.obj"});
}

TEST_F(Cli, ViewLightsTheVoxelsAndRefusesBadLighting)
{
    // A lit picture of the built-in Cornell box (its mesh is voxelized with normals).
    for (const char* render : {"direct", "gi --gi-emission directional --gi-cones 3",
                               "gi --gi-emission directional --gi-clearance", "gi --specular 0.3,0.3,0.2",
                               "gi --cone-pattern fixed"}) {
        const auto lit = runSvo(std::string("view -r 16 --size 64x48 --render ") + render +
                                " --light point:0,1.8,0:5 --light sun:0.3,-1,0.2:1,1,0.5 --screenshot " + path("lit.png"));
        ASSERT_EQ(lit.code, 0) << lit.out;
    }
    // An octree file without the normal channel cannot be lit; the error says what to do.
    ASSERT_EQ(runSvo("voxelize -r 16 -o " + path("plain.svo")).code, 0);
    const auto plain = runSvo("view " + path("plain.svo") + " --render gi --screenshot " + path("x.png"));
    EXPECT_EQ(plain.code, 1);
    EXPECT_EQ(lineCount(plain.out), 1u) << plain.out;
    EXPECT_NE(plain.out.find("plain.svo: --render gi needs the octree's normal channel"), std::string::npos) << plain.out;
    // The mesh's own triangles lit instead of the voxels (--surface mesh): a
    // mesh input only.
    const auto meshShot = runSvo("view -r 16 --size 64x48 --render gi --surface mesh --screenshot " + path("lit.png"));
    ASSERT_EQ(meshShot.code, 0) << meshShot.out;
    // --surface auto (the default) shades a mesh input's triangles in lit and
    // AO pictures: the same bytes as --surface mesh, not as --surface voxels.
    auto bytes = [](const std::string& file) {
        std::ifstream f(file, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(f), {});
    };
    for (const char* surface : {"auto", "mesh", "voxels"})
        ASSERT_EQ(runSvo(std::string("view -r 16 --size 64x48 --render ao --surface ") + surface + " --screenshot " +
                         path(std::string("ao_") + surface + ".png"))
                      .code,
                  0);
    EXPECT_EQ(bytes(path("ao_auto.png")), bytes(path("ao_mesh.png")));
    EXPECT_NE(bytes(path("ao_auto.png")), bytes(path("ao_voxels.png")));
    const auto noMesh = runSvo("view " + path("plain.svo") + " --render ao --surface mesh --screenshot " + path("x.png"));
    EXPECT_EQ(noMesh.code, 1);
    EXPECT_EQ(lineCount(noMesh.out), 1u) << noMesh.out;
    EXPECT_NE(noMesh.out.find("plain.svo: --surface mesh shades the input mesh"), std::string::npos) << noMesh.out;
    for (const char* args : {"--render gi --light lamp:1,2,3", "--render gi --light sun:0,0,0", "--render gi --light point:1,2",
                             "--render direct --albedo 2", "--render gi --light-volume 100", "--render gi --gi-cones 0",
                             "--render gi --gi-emission sideways", "--light sun:0,-1,0", "--render gi --specular 1.5",
                             "--render direct --specular 0.5", "--render gi --specular 0.5 --specular-aperture 0",
                             "--render ao --ao-source mesh", "--render ao --light-volume 100", "--render gi --gi-step 0",
                             "--render ao --ao-step 1.5", "--render ao --surface triangles",
                             "--render ao --cone-pattern random"}) {
        const auto r = runSvo(std::string("view -r 8 --screenshot ") + path("x.png") + " " + args);
        EXPECT_EQ(r.code, 1) << args;
        EXPECT_EQ(lineCount(r.out), 1u) << args << ": " << r.out;
    }
    // Lighting options are checked before any voxelizing: a grid that would
    // take long to make is not made.
    const auto early = runSvo("view -r 1000000 --render gi --light sun:0,0,0 --screenshot " + path("x.png"));
    EXPECT_EQ(early.code, 1);
    EXPECT_NE(early.out.find("direction 0,0,0 is zero"), std::string::npos) << early.out;
    expectOnly({"lit.png", "plain.svo", "ao_auto.png", "ao_mesh.png", "ao_voxels.png"});
}

/// The window under Xvfb (xvfb-run): it opens, follows scripted keys, and
/// its live re-voxelization gives exactly `svo voxelize`'s voxels.
TEST_F(Cli, ViewWindowRevoxelizesLiveToTheVoxelsOfVoxelize)
{
    if (system("command -v xvfb-run >/dev/null 2>&1 && command -v xauth >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run and xauth are not installed";
    const std::string xvfb = "xvfb-run -a -s '-screen 0 640x480x24'";
    const std::string mesh = write("ico.off", "");
    ASSERT_EQ(runSvo("scene icosphere --level 5 -o " + mesh).code, 0);
    // '+' doubles 16 to 32, 'v' and 'o' toggle layers, 'p' writes a screenshot, 'q' closes.
    const auto r = runSvo("view " + mesh + " -r 16 --size 160x120 --frames 50 --keys +vop-+q --save " + path("live.svo"),
                          "cd " + path("") + " &&  " + xvfb);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("resolution 32"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("7 frames"), std::string::npos) << r.out; // q after 6 scripted keys
    ASSERT_EQ(runSvo("voxelize " + mesh + " -r 32 -o " + path("ref.svo")).code, 0);
    using svo::octreeKeys, svo::readOctreeFile;
    const svo::Octree live = readOctreeFile(path("live.svo")), ref = readOctreeFile(path("ref.svo"));
    EXPECT_GT(ref.voxelCount(), 1000u);
    auto sorted = [](std::vector<uint64_t> k) {
        std::sort(k.begin(), k.end());
        return k;
    };
    EXPECT_EQ(live.grid.dims, ref.grid.dims);
    EXPECT_TRUE(sorted(octreeKeys(live)) == sorted(octreeKeys(ref)));
    EXPECT_TRUE(fs::exists(path("svo-view-1.png")));

    // A re-voxelization that fails keeps the octree and says why; the window
    // goes on. 'c' picks hardware dilation, 'b' the raster then the compute
    // backend, which refuses any dilation choice on every device.
    const auto kept = runSvo("view " + mesh + " -r 16 --size 160x120 --frames 5 --keys cbb --save " + path("kept.svo"),
                             xvfb);
    ASSERT_EQ(kept.code, 0) << kept.out;
    EXPECT_NE(kept.out.find("warning: kept the previous octree"), std::string::npos) << kept.out;
    EXPECT_NE(kept.out.find("resolution 16"), std::string::npos) << kept.out;
    ASSERT_EQ(runSvo("voxelize " + mesh + " -r 16 -o " + path("ref16.svo")).code, 0);
    EXPECT_TRUE(sorted(octreeKeys(readOctreeFile(path("kept.svo")))) ==
                sorted(octreeKeys(readOctreeFile(path("ref16.svo")))));

    // 'a' on an octree without channels voxelizes again with them, the same voxels.
    const auto coloured = runSvo("view " + mesh + " -r 16 --size 160x120 --frames 3 --keys a --save " +
                                     path("coloured.svo"),
                                 xvfb);
    ASSERT_EQ(coloured.code, 0) << coloured.out;
    const svo::Octree withNormals = readOctreeFile(path("coloured.svo"));
    EXPECT_EQ(withNormals.attributes.normals.size(), withNormals.voxelCount());
    EXPECT_EQ(withNormals.attributes.triangles.size(), withNormals.voxelCount());
    EXPECT_TRUE(sorted(octreeKeys(withNormals)) == sorted(octreeKeys(readOctreeFile(path("ref16.svo")))));

    // 'r' shows the AO alone: the window's screenshot is the same picture,
    // byte for byte, as `svo view --render ao --screenshot` of that size.
    const auto ao = runSvo("view -r 32 --size 160x120 --frames 4 --keys rp", "cd " + path("") + " && " + xvfb);
    ASSERT_EQ(ao.code, 0) << ao.out;
    ASSERT_EQ(runSvo("view -r 32 --size 160x120 --render ao --screenshot " + path("ao.png")).code, 0);
    auto bytes = [](const std::string& file) {
        std::ifstream f(file, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(f), {});
    };
    EXPECT_GT(bytes(path("ao.png")).size(), 100u);
    EXPECT_EQ(bytes(path("svo-view-2.png")), bytes(path("ao.png")));

    // 'l' turns direct light on, a second 'l' adds the bounce: the same
    // pictures as --render direct and --render gi.
    const auto lit = runSvo("view -r 32 --size 160x120 --frames 6 --keys lplp", "cd " + path("") + " && " + xvfb);
    ASSERT_EQ(lit.code, 0) << lit.out;
    ASSERT_EQ(runSvo("view -r 32 --size 160x120 --render direct --screenshot " + path("direct.png")).code, 0);
    ASSERT_EQ(runSvo("view -r 32 --size 160x120 --render gi --screenshot " + path("gi.png")).code, 0);
    EXPECT_EQ(bytes(path("svo-view-3.png")), bytes(path("direct.png")));
    EXPECT_EQ(bytes(path("svo-view-4.png")), bytes(path("gi.png")));
    EXPECT_NE(bytes(path("direct.png")), bytes(path("gi.png")));

    // AO turned on for a grid too wide for the lighting volume: the window
    // says why in the panel (and a warning on exit) and goes on without it.
    const std::string thin = write("thin.obj", "v 0 0 0\nv 1000 0 0\nv 0 1 0\nf 1 2 3\n");
    const auto wide = runSvo("view " + thin + " -r 4096 --size 160x120 --frames 4 --keys g", xvfb);
    ASSERT_EQ(wide.code, 0) << wide.out;
    EXPECT_NE(wide.out.find("warning: octree view: ambient occlusion: a grid 41"), std::string::npos) // 4096 and padding
        << wide.out;
    EXPECT_NE(wide.out.find("--ao-source octree"), std::string::npos) << wide.out;

    // Rays past llvmpipe's loop budget (1° cones stepping a hundredth of their
    // width for 2000 voxels): the window draws on and warns once on exit; a
    // screenshot is refused in one line and writes nothing. A GPU has no budget.
    const std::string past = "view -r 64 --size 64x48 --render ao --ao-aperture 1 --ao-step 0.01 --ao-distance 2000";
    const auto cut = runSvo(past + " --frames 3", xvfb);
    ASSERT_EQ(cut.code, 0) << cut.out;
    if (cut.out.find("on llvmpipe") != std::string::npos) {
        const std::string warning = "rays were cut short by the driver's loop limit";
        const size_t first = cut.out.find(warning);
        EXPECT_NE(first, std::string::npos) << cut.out;
        EXPECT_EQ(cut.out.find(warning, first + 1), std::string::npos) << "warned more than once: " << cut.out;
        const auto shot = runSvo(past + " --screenshot " + path("cut.png"));
        EXPECT_EQ(shot.code, 1) << shot.out;
        // One error line; the progress of the 1 s render says it stopped, not that it is done.
        const size_t error = shot.out.find("svo: error: octree view: llvmpipe");
        EXPECT_NE(error, std::string::npos) << shot.out;
        EXPECT_EQ(shot.out.find('\n', error), shot.out.size() - 1) << shot.out;
        EXPECT_NE(shot.out.find("ended the rays of"), std::string::npos) << shot.out;
        EXPECT_EQ(shot.out.find("done in"), std::string::npos) << shot.out;
        EXPECT_FALSE(fs::exists(path("cut.png")));
    }

    for (const char* args : {"--frames 3 --screenshot x.png", "--keys + --screenshot x.png", "--frames -1",
                             "--save x.svo --screenshot x.png"}) {
        const auto bad = runSvo(std::string("view -r 8 ") + args, xvfb);
        EXPECT_EQ(bad.code, 1) << args;
        EXPECT_EQ(lineCount(bad.out), 1u) << args << ": " << bad.out;
    }
}

TEST_F(Cli, ViewWithoutDisplayOrScreenshotSaysSoInOneLine)
{
    const auto r = runSvo("view -r 8", "DISPLAY= WAYLAND_DISPLAY=");
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(lineCount(r.out), 1u) << r.out;
    EXPECT_NE(r.out.find("no display"), std::string::npos) << r.out;
}

} // namespace
