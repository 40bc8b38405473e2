// svo convert keeps what it converts, and every writer fails on a full disk:
// the outputs read back with OpenVDB's and NanoVDB's own readers.
#include <algorithm>
#include <array>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>
#include <openvdb/openvdb.h>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "svo/core/error.h"
#include "svo/vdb_io/nanovdb_input.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

struct Run {
    int code;
    std::string out;
};

/// svo with `args`; `fileSizeLimit` > 0 runs it under RLIMIT_FSIZE with
/// SIGXFSZ ignored, so that a write past the limit fails with EFBIG, as a
/// full disk fails with ENOSPC (no mount, no root needed).
Run runSvo(const std::vector<std::string>& args, rlim_t fileSizeLimit = 0)
{
    int pipeFd[2];
    if (pipe(pipeFd) != 0) return {-1, "pipe failed"};
    std::vector<std::string> all = {SVO_EXE};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        // Only async-signal-safe calls until exec.
        dup2(pipeFd[1], 1);
        dup2(pipeFd[1], 2);
        close(pipeFd[0]);
        close(pipeFd[1]);
        if (fileSizeLimit) {
            struct rlimit lim = {fileSizeLimit, fileSizeLimit};
            if (setrlimit(RLIMIT_FSIZE, &lim) != 0) _exit(125);
            signal(SIGXFSZ, SIG_IGN); // kept across exec
        }
        execv(SVO_EXE, argv.data());
        _exit(126);
    }
    close(pipeFd[1]);
    std::string out;
    std::array<char, 4096> buf;
    ssize_t n;
    while ((n = read(pipeFd[0], buf.data(), buf.size())) > 0) out.append(buf.data(), size_t(n));
    close(pipeFd[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

std::string slurp(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

size_t lines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

/// The lines of @a s other than progress reports ("loading x ..." and "loading
/// x done in 1.1 s"), which a step prints when it takes long, as under load.
size_t messageLines(const std::string& s)
{
    size_t n = 0;
    std::istringstream in(s);
    for (std::string line; std::getline(in, line);) {
        const bool started = line.size() >= 4 && line.compare(line.size() - 4, 4, " ...") == 0;
        if (!started && line.find(" done in ") == std::string::npos) ++n;
    }
    return n;
}

openvdb::GridPtrVec readAll(const std::string& path)
{
    openvdb::initialize();
    openvdb::io::File f(path);
    f.open();
    auto grids = f.getGrids();
    f.close();
    return *grids;
}

/// Grid metadata but OpenVDB's file statistics (file_*), which its writer makes.
std::map<std::string, std::string> userMetadata(const openvdb::GridBase& g)
{
    std::map<std::string, std::string> m;
    for (auto it = g.beginMeta(); it != g.endMeta(); ++it)
        if (it->first.rfind("file_", 0) != 0) m[it->first] = it->second->str();
    return m;
}

/// The same grid: name, type, class, transform, background, metadata, and
/// every active value (voxels and tiles) at the same place.
void expectSameGrid(const openvdb::GridBase& a, const openvdb::GridBase& b)
{
    EXPECT_EQ(a.getName(), b.getName());
    ASSERT_EQ(a.type(), b.type());
    EXPECT_EQ(a.getGridClass(), b.getGridClass());
    EXPECT_EQ(a.constTransform(), b.constTransform());
    EXPECT_EQ(userMetadata(a), userMetadata(b));
    EXPECT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
    const auto* fa = dynamic_cast<const openvdb::FloatGrid*>(&a);
    const auto* fb = dynamic_cast<const openvdb::FloatGrid*>(&b);
    ASSERT_TRUE(fa && fb) << "the test compares float grids; got " << a.type();
    EXPECT_EQ(fa->background(), fb->background());
    auto acc = fb->getConstAccessor();
    uint64_t compared = 0;
    for (auto it = fa->cbeginValueOn(); it; ++it, ++compared) {
        ASSERT_TRUE(acc.isValueOn(it.getCoord())) << it.getCoord();
        ASSERT_EQ(acc.getValue(it.getCoord()), *it) << it.getCoord();
    }
    // And the inactive values (a level set's ±background sides).
    for (auto it = fa->cbeginValueOff(); it; ++it) {
        if (!it.isVoxelValue()) continue;
        ASSERT_EQ(acc.getValue(it.getCoord()), *it) << it.getCoord();
    }
    EXPECT_GT(compared, 1000u);
}

class CliConvert : public ::testing::Test {
protected:
    void SetUp() override
    {
        ASSERT_EQ(runSvo({"scene", "icosphere", "--level", "3", "-o", path("ico.off")}).code, 0);
    }
    std::string path(const std::string& name) const { return tmp_.path(name); }
    /// The folder holds exactly these names: no temporaries left behind.
    void expectOnly(std::vector<std::string> names) const
    {
        std::vector<std::string> got;
        for (const auto& e : fs::directory_iterator(tmp_.dir())) got.push_back(e.path().filename().string());
        std::sort(got.begin(), got.end());
        std::sort(names.begin(), names.end());
        EXPECT_EQ(got, names);
    }
    std::string levelSet()
    {
        const auto r = runSvo({"voxelize", path("ico.off"), "-r", "48", "--sdf", "-o", path("ls.vdb")});
        EXPECT_EQ(r.code, 0) << r.out;
        return path("ls.vdb");
    }
    svo::test::TempDir tmp_{"cli_convert"};
};

} // namespace

TEST_F(CliConvert, ALevelSetConvertedToVdbKeepsItsTypeClassValuesAndMetadata)
{
    const std::string in = levelSet();
    const auto r = runSvo({"convert", in, "-o", path("copy.vdb")});
    ASSERT_EQ(r.code, 0) << r.out;
    const auto a = readAll(in), b = readAll(path("copy.vdb"));
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), 1u);
    EXPECT_EQ(b[0]->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(b[0]->type(), openvdb::FloatGrid::gridType());
    expectSameGrid(*a[0], *b[0]);
    expectOnly({"ico.off", "ls.vdb", "copy.vdb"});
}

TEST_F(CliConvert, ALevelSetConvertedToNanoVdbIsAValidFloatLevelSetWithItsValues)
{
    const std::string in = levelSet();
    const auto r = runSvo({"convert", in, "-o", path("ls.nvdb")});
    ASSERT_EQ(r.code, 0) << r.out;
    const auto src = readAll(in);
    ASSERT_EQ(src.size(), 1u);
    const auto& vdb = static_cast<const openvdb::FloatGrid&>(*src[0]);
    auto handles = nanovdb::io::readGrids(path("ls.nvdb"));
    ASSERT_EQ(handles.size(), 1u);
    const auto* nano = handles[0].grid<float>();
    ASSERT_NE(nano, nullptr) << "not a NanoVDB float grid";
    EXPECT_TRUE(nanovdb::isValid(*nano, /*detailed=*/true, /*verbose=*/true));
    EXPECT_EQ(nano->gridClass(), nanovdb::GridClass::LevelSet);
    EXPECT_EQ(std::string(nano->gridName()), vdb.getName());
    EXPECT_EQ(nano->activeVoxelCount(), vdb.activeVoxelCount());
    EXPECT_DOUBLE_EQ(nano->voxelSize()[0], vdb.voxelSize()[0]);
    auto acc = nano->getAccessor();
    EXPECT_EQ(nano->tree().background(), vdb.background());
    for (auto it = vdb.cbeginValueOn(); it; ++it) {
        const nanovdb::Coord c(it.getCoord().x(), it.getCoord().y(), it.getCoord().z());
        ASSERT_TRUE(acc.isActive(c)) << it.getCoord();
        ASSERT_EQ(acc.getValue(c), *it) << it.getCoord();
    }
    for (auto it = vdb.cbeginValueOff(); it; ++it)
        if (it.isVoxelValue()) {
            const nanovdb::Coord c(it.getCoord().x(), it.getCoord().y(), it.getCoord().z());
            ASSERT_EQ(acc.getValue(c), *it) << it.getCoord();
        }
}

TEST_F(CliConvert, ALevelSetToSvoIsRefusedInOneLineUnlessTopologyOnly)
{
    const std::string in = levelSet();
    auto r = runSvo({"convert", in, "-o", path("x.svo")});
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(lines(r.out), 1u) << r.out;
    EXPECT_NE(r.out.find("the distances of the level set grid 'surface' (float) would be lost"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("--topology-only"), std::string::npos) << r.out;
    // Grids made anew from a .vdb's active voxels need the same consent.
    r = runSvo({"convert", in, "-o", path("x.vdb"), "--fog"});
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_EQ(lines(r.out), 1u) << r.out;
    expectOnly({"ico.off", "ls.vdb"});

    r = runSvo({"convert", in, "-o", path("x.svo"), "--topology-only"});
    EXPECT_EQ(r.code, 0) << r.out;
    r = runSvo({"convert", in, "-o", path("x.vdb"), "--topology-only", "--topology", "mask"});
    EXPECT_EQ(r.code, 0) << r.out;
    const auto grids = readAll(path("x.vdb"));
    ASSERT_EQ(grids.size(), 1u);
    EXPECT_EQ(grids[0]->type(), openvdb::MaskGrid::gridType());
    EXPECT_EQ(grids[0]->activeVoxelCount(), readAll(in)[0]->activeVoxelCount());
}

// A write that runs out of room (EFBIG under a file size limit, as ENOSPC on a
// full disk) fails in one line naming the file and the cause, removes its
// temporary, and leaves the earlier file as it was: .vdb, .nvdb and .svo.
TEST_F(CliConvert, AWriteThatRunsOutOfRoomFailsAndKeepsTheEarlierFile)
{
    ASSERT_EQ(runSvo({"voxelize", path("ico.off"), "-r", "96", "-o", path("in.svo")}).code, 0);
    for (const std::string name : {"out.vdb", "out.nvdb", "out.svo"}) {
        std::ofstream(path(name)) << "the earlier file";
        std::vector<std::string> args = {"convert", path("in.svo"), "-o", path(name)};
        if (name != "out.svo") args.push_back("--fog");
        const auto r = runSvo(args, 16384);
        EXPECT_EQ(r.code, 1) << name << ": " << r.out;
        EXPECT_EQ(lines(r.out), 1u) << r.out;
        EXPECT_NE(r.out.find(path(name) + ": "), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("File too large"), std::string::npos) << r.out;
        EXPECT_EQ(slurp(path(name)), "the earlier file") << name;
        // Without the limit the same command writes the file whole.
        const auto whole = runSvo(args);
        EXPECT_EQ(whole.code, 0) << whole.out;
        EXPECT_GT(fs::file_size(path(name)), 16384u) << name;
    }
    expectOnly({"ico.off", "in.svo", "out.vdb", "out.nvdb", "out.svo"});
}

std::string thousands(uint64_t n)
{
    std::string s = std::to_string(n);
    for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
    return s;
}

// svo info reads a .nvdb that svo wrote: its grids by name, type, class and count.
TEST_F(CliConvert, InfoOnANanoVdbNamesItsGridsTypesClassesAndCounts)
{
    const std::string in = levelSet();
    ASSERT_EQ(runSvo({"convert", in, "-o", path("ls.nvdb")}).code, 0);
    const auto src = readAll(in);
    ASSERT_EQ(src.size(), 1u);
    const auto r = runSvo({"info", path("ls.nvdb")});
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string want = "'" + src[0]->getName() + "' float, level set, " + thousands(src[0]->activeVoxelCount()) +
                             " active voxels, index bbox";
    EXPECT_NE(r.out.find(want), std::string::npos) << want << "\n" << r.out;
    EXPECT_NE(r.out.find("grid '" + src[0]->getName() + "' (Tree_float_5_4_3"), std::string::npos) << r.out;
    expectOnly({"ico.off", "ls.vdb", "ls.nvdb"});
}

// .vdb -> .nvdb -> .vdb keeps a level set voxel for voxel (NanoVDB has no
// string metadata; everything else is compared), read with OpenVDB's reader;
// to .svo the .vdb input's rule holds: refused unless --topology-only.
TEST_F(CliConvert, AVdbToNanoVdbToVdbRoundTripKeepsALevelSetVoxelForVoxel)
{
    const std::string in = levelSet();
    ASSERT_EQ(runSvo({"convert", in, "-o", path("ls.nvdb")}).code, 0);
    const auto r = runSvo({"convert", path("ls.nvdb"), "-o", path("back.vdb")});
    ASSERT_EQ(r.code, 0) << r.out;
    const auto a = readAll(in), b = readAll(path("back.vdb"));
    ASSERT_EQ(a.size(), 1u);
    ASSERT_EQ(b.size(), 1u);
    for (auto it = a[0]->beginMeta(); it != a[0]->endMeta(); ++it) b[0]->insertMeta(it->first, *it->second);
    expectSameGrid(*a[0], *b[0]);

    const auto refused = runSvo({"convert", path("ls.nvdb"), "-o", path("x.svo")});
    EXPECT_EQ(refused.code, 1) << refused.out;
    EXPECT_EQ(lines(refused.out), 1u) << refused.out;
    EXPECT_NE(refused.out.find("--topology-only"), std::string::npos) << refused.out;
    const auto topo = runSvo({"convert", path("ls.nvdb"), "-o", path("x.svo"), "--topology-only"});
    EXPECT_EQ(topo.code, 0) << topo.out;
    expectOnly({"ico.off", "ls.vdb", "ls.nvdb", "back.vdb", "x.svo"});
}

// A cut-short or damaged .nvdb is refused with one svo::Error naming the
// file, never read past its end: cuts (every 7th byte over the headers, then
// every 9,973rd), and byte
// flips over the headers and across the whole file (svo writes a full
// checksum, so each is found). A few through the command line, one line each.
TEST_F(CliConvert, ACutShortOrDamagedNanoVdbIsRefusedInOneLineNeverCrashes)
{
    ASSERT_EQ(runSvo({"voxelize", path("ico.off"), "-r", "12", "--sdf", "-o", path("small.vdb")}).code, 0);
    ASSERT_EQ(runSvo({"convert", path("small.vdb"), "-o", path("small.nvdb")}).code, 0);
    const std::string bytes = slurp(path("small.nvdb"));
    ASSERT_GT(bytes.size(), 1000u);
    ASSERT_EQ(svo::vdb::readNanoVdbGridsFromBytes(bytes, "small.nvdb").size(), 1u);
    auto refused = [&](const std::string& damaged, const std::string& what) {
        try {
            svo::vdb::readNanoVdbGridsFromBytes(damaged, "small.nvdb");
        } catch (const svo::Error& e) {
            const std::string m = e.what();
            EXPECT_EQ(m.rfind("small.nvdb: ", 0), 0u) << what << ": " << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << what << ": " << m;
            return;
        }
        ADD_FAILURE() << what << " was read";
    };
    // Every 7th byte over the headers and the root, then every 9,973rd (each cut copies the 2.4 MB file).
    for (size_t cut = 0; cut < bytes.size(); cut += cut < 4096 ? 7 : 9973)
        refused(bytes.substr(0, cut), "cut at " + std::to_string(cut));
    refused(bytes.substr(0, bytes.size() - 1), "cut by one byte");
    refused(bytes + std::string(16, '\0'), "16 bytes appended");
    std::vector<size_t> flips;
    for (size_t i = 0; i < 1024 && i < bytes.size(); ++i) flips.push_back(i); // segment header, record, grid and tree headers
    for (size_t i = 1024; i < bytes.size(); i += 4099) flips.push_back(i);
    flips.push_back(bytes.size() - 1);
    for (const size_t i : flips) {
        std::string d = bytes;
        d[i] = char(d[i] ^ 0x5a);
        refused(d, "byte " + std::to_string(i) + " flipped");
    }

    for (const size_t at : {size_t(0), size_t(20), size_t(300), bytes.size() / 2, bytes.size() - 3}) {
        {
            std::ofstream(path("cut.nvdb"), std::ios::binary) << bytes.substr(0, at);
        }
        std::string d = bytes;
        d[at] = char(d[at] ^ 0x5a);
        {
            std::ofstream(path("flip.nvdb"), std::ios::binary) << d;
        }
        for (const std::vector<std::string>& args :
             {std::vector<std::string>{"info", path("cut.nvdb")}, {"convert", path("cut.nvdb"), "-o", path("x.vdb")},
              {"info", path("flip.nvdb")}, {"convert", path("flip.nvdb"), "-o", path("x.vdb")}}) {
            const auto r = runSvo(args);
            EXPECT_EQ(r.code, 1) << at << ": " << r.out;
            EXPECT_EQ(lines(r.out), 1u) << at << ": " << r.out;
            EXPECT_NE(r.out.find(args[1] + ": "), std::string::npos) << r.out;
        }
    }
    expectOnly({"ico.off", "small.vdb", "small.nvdb", "cut.nvdb", "flip.nvdb"});
}

// A mesh 1e15 from the origin: OpenVDB cannot hold the grid's transform, so a
// .vdb output is refused in one line before any work (it used to voxelize,
// then fail in the writer with "ArithmeticError: Non-zero scale values
// required"); .svo, which has no such transform, is written.
TEST_F(CliConvert, AGridOpenVdbCannotPlaceIsRefusedBeforeAnyWork)
{
    std::ofstream(path("far.obj")) << "v 1e15 1e15 1e15\nv 1000000000000001 1e15 1e15\nv 1e15 1000000000000001 1e15\n"
                                      "f 1 2 3\n";
    for (const char* out : {"far.vdb", "far.nvdb"}) {
        const auto r = runSvo({"voxelize", path("far.obj"), "-r", "16", "-o", path(out)});
        EXPECT_EQ(r.code, 1) << r.out;
        EXPECT_EQ(messageLines(r.out), 1u) << r.out;
        EXPECT_NE(r.out.find(path(out) + ": the grid lies 1e+15 from the origin"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("farther than an OpenVDB transform holds"), std::string::npos) << r.out;
    }
    const auto svo = runSvo({"voxelize", path("far.obj"), "-r", "16", "-o", path("far.svo")});
    EXPECT_EQ(svo.code, 0) << svo.out;
    expectOnly({"ico.off", "far.obj", "far.svo"});
}
