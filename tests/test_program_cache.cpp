// Start-up: the program binary cache (gl/device/src/program_cache.h) and the
// start-up record of a call (VoxelizeStats::startup). What is expected comes
// from the cache folder itself (its files), from a Voxelizer without a cache,
// and from the driver's own program binaries.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "program_cache.h" // gl/device/src: internal to the device layer
#include "voxelize_shaders.h" // the voxelize layer's shaders (gl/voxelize/src)
#include "scenes.h"
#include "svo/core/octree.h"
#include "svo/gl/context.h"
#include "svo/voxelizer.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace svo;

namespace {

std::vector<fs::path> entries(const fs::path& folder)
{
    std::vector<fs::path> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(folder, ec))
        if (e.is_regular_file()) out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::string readBytes(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A call's voxels and its start-up record, on the raster backend (the one
/// every renderer runs), optionally with attribute channels.
struct CallResult {
    std::vector<uint64_t> keys;
    VoxelizeStats stats;
};
CallResult voxelize(Voxelizer& v, uint32_t attributes = 0)
{
    static const TriangleMesh mesh = test::sphere({0.3, -0.2, 0.1}, 1.0, 24, 16);
    CallResult r;
    VoxelizeOptions o;
    o.backend = Backend::Raster;
    o.attributes = attributes;
    o.stats = &r.stats;
    r.keys = octreeKeys(v.voxelize(mesh, makeGrid(mesh, GridRequest{48, 0.0}), o));
    return r;
}

DeviceOptions withCache(const std::string& folder) { return DeviceOptions{"", false, folder}; }

/// Sets an environment variable for the scope, then restores it.
class EnvVar {
public:
    EnvVar(const char* name, const char* value) : name_(name)
    {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value) setenv(name, value, 1);
        else unsetenv(name);
    }
    ~EnvVar()
    {
        if (old_) setenv(name_, old_->c_str(), 1);
        else unsetenv(name_);
    }

private:
    const char* name_;
    std::optional<std::string> old_;
};

bool driverHasBinaries()
{
    gl::Context c(gl::ContextOptions{"", false, "off"});
    return c.info().programBinaryFormats > 0;
}

} // namespace

TEST(ProgramCache, SecondVoxelizerLoadsEveryProgramFromTheCache)
{
    if (!driverHasBinaries()) GTEST_SKIP() << "the driver offers no program binary formats";
    const test::TempDir tmp("program_cache");
    const std::string folder = tmp.path("programs"); // created by the first store
    CallResult first, firstAgain;
    {
        Voxelizer v(withCache(folder));
        first = voxelize(v);
        firstAgain = voxelize(v);
    }
    const auto files = entries(folder);
    ASSERT_FALSE(files.empty());
    EXPECT_EQ(first.stats.startup.programCache, folder);
    EXPECT_GT(first.stats.startup.eglMs, 0.0);
    EXPECT_GT(first.stats.startup.programMs, 0.0);
    EXPECT_EQ(size_t(first.stats.startup.programsCompiled), files.size()); // one entry per compiled program
    EXPECT_EQ(first.stats.startup.programsLoaded, 0);
    EXPECT_EQ(first.stats.startup.programsRefused, 0);
    // The same Voxelizer again: warm, nothing to start.
    EXPECT_EQ(firstAgain.stats.startup.eglMs, 0.0);
    EXPECT_EQ(firstAgain.stats.startup.programsCompiled + firstAgain.stats.startup.programsLoaded, 0);
    EXPECT_EQ(firstAgain.stats.startup.programMs, 0.0);

    Voxelizer second(withCache(folder));
    const CallResult loaded = voxelize(second);
    EXPECT_EQ(loaded.stats.startup.programsCompiled, 0);
    EXPECT_EQ(size_t(loaded.stats.startup.programsLoaded), files.size());
    EXPECT_EQ(loaded.stats.startup.programsRefused, 0);
    EXPECT_GT(loaded.stats.startup.eglMs, 0.0);
    EXPECT_TRUE(loaded.stats.warnings.empty());
    EXPECT_EQ(entries(folder), files); // nothing rewritten under other names

    Voxelizer none(withCache("off"));
    const CallResult uncached = voxelize(none);
    EXPECT_EQ(uncached.stats.startup.programCache, "");
    EXPECT_EQ(uncached.stats.startup.programsLoaded, 0);
    EXPECT_EQ(size_t(uncached.stats.startup.programsCompiled), files.size());

    ASSERT_GT(first.keys.size(), 100u);
    EXPECT_EQ(loaded.keys, first.keys);
    EXPECT_EQ(uncached.keys, first.keys);
}

TEST(ProgramCache, OnlyTheProgramsACallNeedsAreMade)
{
    if (!driverHasBinaries()) GTEST_SKIP() << "the driver offers no program binary formats";
    const test::TempDir tmp("program_cache");
    Voxelizer v(withCache(tmp.path("programs")));
    const CallResult plain = voxelize(v);
    const size_t plainPrograms = entries(tmp.path("programs")).size();
    EXPECT_EQ(size_t(plain.stats.startup.programsCompiled), plainPrograms);
    // Attribute channels need one more program (the attribute pass), and only it.
    const CallResult withNormals = voxelize(v, kNormals);
    EXPECT_EQ(withNormals.stats.startup.programsCompiled, 1);
    EXPECT_EQ(entries(tmp.path("programs")).size(), plainPrograms + 1);
    EXPECT_EQ(withNormals.keys, plain.keys);
    // The CPU backend needs none.
    VoxelizeStats cpu;
    VoxelizeOptions o;
    o.backend = Backend::Cpu;
    o.stats = &cpu;
    const TriangleMesh mesh = test::box({0, 0, 0}, {1, 2, 3});
    v.voxelize(mesh, makeGrid(mesh, GridRequest{16, 0.0}), o);
    EXPECT_EQ(cpu.startup.programsCompiled + cpu.startup.programsLoaded, 0);
}

TEST(ProgramCache, DamagedEntriesAreCompiledAgainAndReplaced)
{
    if (!driverHasBinaries()) GTEST_SKIP() << "the driver offers no program binary formats";
    const test::TempDir tmp("program_cache");
    const std::string folder = tmp.path("programs");
    CallResult first;
    {
        Voxelizer v(withCache(folder));
        first = voxelize(v);
    }
    const auto files = entries(folder);
    ASSERT_GE(files.size(), 2u);
    // One entry with bytes changed in its middle, one cut short; the rest intact.
    std::string changed = readBytes(files[0]);
    for (size_t i = changed.size() / 2; i < changed.size() / 2 + 16; ++i) changed[i] = char(changed[i] ^ 0x5a);
    std::ofstream(files[0], std::ios::binary | std::ios::trunc) << changed;
    const std::string cut = readBytes(files[1]).substr(0, 40);
    std::ofstream(files[1], std::ios::binary | std::ios::trunc) << cut;

    Voxelizer second(withCache(folder));
    const CallResult repaired = voxelize(second);
    EXPECT_EQ(repaired.stats.startup.programsRefused, 2);
    EXPECT_EQ(repaired.stats.startup.programsCompiled, 2);
    EXPECT_EQ(size_t(repaired.stats.startup.programsLoaded), files.size() - 2);
    EXPECT_TRUE(repaired.stats.warnings.empty());
    EXPECT_EQ(repaired.keys, first.keys);
    EXPECT_NE(readBytes(files[0]), changed);
    EXPECT_NE(readBytes(files[1]), cut);

    // The replaced entries load.
    Voxelizer third(withCache(folder));
    const CallResult again = voxelize(third);
    EXPECT_EQ(again.stats.startup.programsCompiled, 0);
    EXPECT_EQ(size_t(again.stats.startup.programsLoaded), files.size());
    EXPECT_EQ(again.keys, first.keys);
}

TEST(ProgramCache, AFolderThatCannotBeWrittenWarnsOnceAndFailsNothing)
{
    if (!driverHasBinaries()) GTEST_SKIP() << "the driver offers no program binary formats";
    const test::TempDir tmp("program_cache");
    // Below a regular file: no folder can be made there, whoever runs the test.
    const std::string blocker = tmp.write("not_a_folder", "x");
    const std::string folder = blocker + "/programs";
    Voxelizer reference(withCache("off"));
    const CallResult expected = voxelize(reference);

    Voxelizer v(withCache(folder));
    const CallResult plain = voxelize(v);
    EXPECT_EQ(plain.keys, expected.keys);
    EXPECT_GT(plain.stats.startup.programsCompiled, 1); // several stores failed...
    ASSERT_EQ(plain.stats.warnings.size(), 1u);         // ...and one warning says so
    EXPECT_NE(plain.stats.warnings[0].find(folder), std::string::npos) << plain.stats.warnings[0];
    EXPECT_EQ(plain.stats.warnings[0].find('\n'), std::string::npos);
    const CallResult more = voxelize(v, kNormals); // compiles once more: no second warning
    EXPECT_EQ(more.stats.startup.programsCompiled, 1);
    EXPECT_TRUE(more.stats.warnings.empty());
    EXPECT_EQ(more.keys, expected.keys);
    EXPECT_TRUE(fs::is_regular_file(blocker));
}

TEST(ProgramCache, TheDriverRefusingABinaryIsNoError)
{
    gl::Context context(gl::ContextOptions{"", false, "off"});
    if (context.info().programBinaryFormats == 0) GTEST_SKIP() << "the driver offers no program binary formats";
    const gl::Context::Scope scope(context);
    const gl::ProgramSource source = gl::programSource({"octree_fill.comp"}, gl::voxelizeShaders());
    const gl::Program compiled(source, true);
    GLenum format = 0;
    const std::vector<uint8_t> good = compiled.binary(format);
    ASSERT_FALSE(good.empty());

    const std::optional<gl::Program> loaded = gl::Program::fromBinary(source, format, good);
    ASSERT_TRUE(loaded.has_value());
    EXPECT_NO_THROW(loaded->set("uBrickLevel", 3u)); // its uniforms are found, as after a compile

    std::vector<uint8_t> garbage(good.size());
    for (size_t i = 0; i < garbage.size(); ++i) garbage[i] = uint8_t(i * 131 + 7);
    EXPECT_FALSE(gl::Program::fromBinary(source, format, garbage).has_value());
    const std::vector<uint8_t> truncated(good.begin(), good.begin() + std::ptrdiff_t(good.size() / 2));
    EXPECT_FALSE(gl::Program::fromBinary(source, format, truncated).has_value());
    EXPECT_FALSE(gl::Program::fromBinary(source, format ^ 0x5a5a0000u, good).has_value()); // a format not offered
    EXPECT_NO_THROW(gl::checkGl("after refused binaries")); // the refusals left no GL error behind
}

TEST(ProgramCache, FolderFromOptionEnvironmentAndXdg)
{
    const EnvVar xdg("XDG_CACHE_HOME", "/xdg"), home("HOME", "/home/someone");
    {
        const EnvVar env("SVO_PROGRAM_CACHE", nullptr);
        EXPECT_EQ(gl::programCacheFolder(""), "/xdg/svo/programs");
        EXPECT_EQ(gl::programCacheFolder("/mine"), "/mine");
        EXPECT_EQ(gl::programCacheFolder("off"), "");
        const EnvVar noXdg("XDG_CACHE_HOME", "");
        EXPECT_EQ(gl::programCacheFolder(""), "/home/someone/.cache/svo/programs");
    }
    {
        const EnvVar env("SVO_PROGRAM_CACHE", "/from/env");
        EXPECT_EQ(gl::programCacheFolder(""), "/from/env");
        EXPECT_EQ(gl::programCacheFolder("/mine"), "/mine"); // the option wins
        EXPECT_EQ(gl::programCacheFolder("off"), "");
    }
    for (const char* off : {"", "off"}) {
        const EnvVar env("SVO_PROGRAM_CACHE", off);
        EXPECT_EQ(gl::programCacheFolder(""), "") << "SVO_PROGRAM_CACHE='" << off << "'";
    }
}
