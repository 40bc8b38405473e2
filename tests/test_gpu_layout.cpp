// gpu_layout.h as the GPU reads it, against the C++ side: voxel keys, fixed
// point and the octree build state computed by shaders and compared with the
// CPU. Then the shader plumbing: #include expansion with #line directives,
// compiler errors traced to the file and line they come from, and uniforms
// that do not exist; and fillWords, the device layer's own shader.
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <cstdint>
#include <gtest/gtest.h>
#include <memory>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "svo/core/error.h"
#include "svo/core/gpu_layout.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_attributes.h"
#include "svo/core/voxel_key.h"
#include "svo/gl/context.h"
#include "svo/gl/buffer.h"
#include "svo/gl/fill_words.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"
#include "svo/gl/shader_source.h"
#include "voxelize_layout.h"  // the voxelize layer's slots (gl/voxelize/shaders)
#include "voxelize_shaders.h" // and its embedded shaders (gl/voxelize/src)

using namespace svo;
using namespace svo::gl;

namespace {

/// A test's own shader files, then the voxelize layer's.
ShaderFiles withVoxelize(ShaderFiles files)
{
    for (const auto& [name, text] : voxelizeShaders()) files.emplace(name, text);
    return files;
}

class GpuLayout : public ::testing::Test {
protected:
    static void SetUpTestSuite() { context_ = std::make_unique<Context>(); }
    static void TearDownTestSuite() { context_.reset(); }
    // The tests use GL objects directly: the context is current for each test's whole body.
    void SetUp() override { scope_ = std::make_unique<Context::Scope>(*context_); }
    void TearDown() override { scope_.reset(); }
    static std::unique_ptr<Context> context_;
    std::unique_ptr<Context::Scope> scope_;

    /// Waits for the shaders' writes and reads `count` values back.
    template <typename T>
    static std::vector<T> readBack(const Buffer& b, size_t count)
    {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<T> out(count);
        b.read(0, count * sizeof(T), out.data());
        checkGl("test readback");
        return out;
    }
};
std::unique_ptr<Context> GpuLayout::context_;

const char* const kKeyProbe = R"(#version 450 core
layout(local_size_x = 64) in;
#include "gpu_layout.h"
layout(std430, binding = 0) readonly buffer Points { uint points[]; }; // x, y, z
layout(std430, binding = 1) writeonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = 2) writeonly buffer Parts { uvec4 parts[]; }; // brick xyz, leaf bit
uniform uint uCount;
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uCount) return;
    uvec2 key = packVoxelKey(uvec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]));
    keys[i] = key;
    parts[i] = uvec4(brickOfVoxelKey(key), leafBitOfVoxelKey(key));
}
)";

TEST_F(GpuLayout, KeysPackedOnTheGpuMatchTheCpu)
{
    // Corners of the 21-bit range, brick y values on both sides of the word
    // split (bits 4 and 5 of brick y), then random points.
    std::vector<std::array<uint32_t, 3>> points = {
        {0, 0, 0}, {7, 7, 7}, {8, 8, 8}, {2097151, 2097151, 2097151}, {2097151, 0, 0}, {0, 2097151, 0},
        {0, 0, 2097151}, {1, 2, 3}, {0, 255, 0}, {0, 256, 0}, {0, 263, 0}, {5, 0x1FFF00, 9}, {0, 0x1000F8, 0}};
    std::mt19937 rng(7);
    std::uniform_int_distribution<uint32_t> coord(0, 2097151);
    while (points.size() < 1000) points.push_back({coord(rng), coord(rng), coord(rng)});

    const Buffer in("test points", points.size() * sizeof points[0], points.data(), 0);
    const Buffer keys("test keys", points.size() * 8);
    const Buffer parts("test key parts", points.size() * 16);
    const Program program({{"key_probe.comp", kKeyProbe}}, {"key_probe.comp"});
    in.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    keys.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    parts.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    program.set("uCount", uint32_t(points.size()));
    program.dispatch(uint32_t(points.size() + 63) / 64);
    const auto gpuKeys = readBack<uint64_t>(keys, points.size()); // uvec2(low, high) is a little-endian uint64
    const auto gpuParts = readBack<std::array<uint32_t, 4>>(parts, points.size());

    for (size_t i = 0; i < points.size(); ++i) {
        const auto& p = points[i];
        const uint64_t key = packVoxelKey(p[0], p[1], p[2]);
        ASSERT_EQ(gpuKeys[i], key) << "point (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
        const auto brick = unpackVoxelKey(brickOfKey(key));
        EXPECT_EQ(gpuParts[i][0], brick[0] >> 3);
        EXPECT_EQ(gpuParts[i][1], brick[1] >> 3);
        EXPECT_EQ(gpuParts[i][2], brick[2] >> 3);
        EXPECT_EQ(gpuParts[i][3], uint32_t(key & 511));
    }
}

TEST_F(GpuLayout, FixedPointOnTheGpuMatchesTheCpu)
{
    const char* const probe = R"(#version 450 core
layout(local_size_x = 64) in;
#include "gpu_layout.h"
layout(std430, binding = 0) readonly buffer Values { float values[]; };
layout(std430, binding = 1) writeonly buffer Fixed { int fixedValues[]; };
uniform uint uCount;
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < uCount) fixedValues[i] = toFixed(values[i]);
}
)";
    // Ties (k + 1/2 units of 2^-16) round to even on both sides.
    const float unit = 1.0f / 65536.0f;
    std::vector<float> values = {0.0f, 1.0f, -1.0f, 0.5f * unit, 1.5f * unit, 2.5f * unit, -2.5f * unit,
                                 0.1f, -0.7f, 0.99999f};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> v(-1.0f, 1.0f);
    while (values.size() < 1000) values.push_back(v(rng));

    const Buffer in("test values", values.size() * 4, values.data(), 0);
    const Buffer out("test fixed values", values.size() * 4);
    const Program program({{"fixed_probe.comp", probe}}, {"fixed_probe.comp"});
    in.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    out.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    program.set("uCount", uint32_t(values.size()));
    program.dispatch(uint32_t(values.size() + 63) / 64);
    const auto gpu = readBack<int32_t>(out, values.size());
    for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(gpu[i], toFixed(values[i])) << "value " << values[i];
    EXPECT_EQ(toFixed(2.5f * unit), 2);
    EXPECT_EQ(toFixed(1.0f), 65536);
}

TEST_F(GpuLayout, BuildStateFieldsLandWhereCppReadsThem)
{
    const char* const probe = R"(#version 450 core
layout(local_size_x = 1) in;
#include "gpu_layout.h"
#include "voxelize_layout.h"
layout(std430, binding = SVO_BIND_BUILD_STATE) writeonly buffer BuildState { SVO_BUILD_STATE_FIELDS } state;
void main()
{
    for (uint k = 0u; k < 3u; ++k) {
        state.entryDispatch[k] = 100u + k;
        state.levelDispatch[k] = 200u + k;
    }
    state.entryCount = 300u;
    state.nodeCount = 301u;
    state.brickCount = 302u;
    state.pad = kNoChild; // and the marker, while here
    for (uint k = 0u; k < uint(state.levelStart.length()); ++k) state.levelStart[k] = 400u + k;
}
)";
    const Buffer buffer("test build state", sizeof(gpu::BuildState));
    const Program program(withVoxelize({{"state_probe.comp", probe}}), {"state_probe.comp"});
    buffer.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_BUILD_STATE);
    program.dispatch(1);
    const gpu::BuildState s = readBack<gpu::BuildState>(buffer, 1)[0];
    for (uint32_t k = 0; k < 3; ++k) {
        EXPECT_EQ(s.entryDispatch[k], 100 + k);
        EXPECT_EQ(s.levelDispatch[k], 200 + k);
    }
    EXPECT_EQ(s.entryCount, 300u);
    EXPECT_EQ(s.nodeCount, 301u);
    EXPECT_EQ(s.brickCount, 302u);
    EXPECT_EQ(s.pad, kNoChild);
    for (uint32_t k = 0; k < SVO_BUILD_LEVEL_SLOTS; ++k) EXPECT_EQ(s.levelStart[k], 400 + k);
}

// "file:line(" (Mesa), "file(line)" (NVIDIA) or "file:line:" (others).
std::regex locationOf(const std::string& file, int line)
{
    const std::string f = std::regex_replace(file, std::regex(R"([.])"), R"(\.)");
    const std::string l = std::to_string(line);
    return std::regex(f + "(:" + l + "\\(|\\(" + l + "\\)|:" + l + ":)");
}

std::string compileError(const ShaderFiles& files, const char* stage)
{
    try {
        Program program(withVoxelize(files), {stage});
    } catch (const Error& e) {
        return e.what();
    }
    return "(it compiled)";
}

TEST_F(GpuLayout, CompileErrorsNameTheIncludedFileAndLine)
{
    // Mesa reports the two kinds of error with different source numbers.
    for (const char* broken : {"const uint kBroken = undefinedName;", "const uint kBroken = ;"}) {
        const ShaderFiles files = {
            {"probe.comp", "#version 450 core\n// line 2\n#include \"broken.glsl\"\nlayout(local_size_x = 1) in;\n"
                           "void main() {}\n"},
            {"broken.glsl", std::string("// line 1\nconst uint kFine = 1u;\n") + broken + "\n"}};
        const std::string message = compileError(files, "probe.comp");
        EXPECT_TRUE(std::regex_search(message, locationOf("broken.glsl", 3))) << message;
    }
}

TEST_F(GpuLayout, CompileErrorsAfterAnIncludeNameTheStageAndLine)
{
    // octree_common.glsl includes gpu_layout.h, which is long and full of
    // preprocessor branches: the stage's own numbering must resume after both.
    const ShaderFiles files = {{"probe.comp", "#version 450 core\nlayout(local_size_x = 1) in;\n"
                                             "#include \"octree_common.glsl\"\n"
                                             "void main() { uint x = undefinedName; }\n"}};
    const std::string message = compileError(files, "probe.comp");
    EXPECT_TRUE(std::regex_search(message, locationOf("probe.comp", 4))) << message;
}

TEST_F(GpuLayout, MissingUniformsAreErrorsNamingThemAndTheProgram)
{
    const ShaderFiles files = {{"probe.comp", "#version 450 core\nlayout(local_size_x = 1) in;\n"
                                              "layout(std430, binding = 0) buffer Out { uint value; };\n"
                                              "uniform uint uUsed;\nuniform uint uUnused;\n"
                                              "void main() { value = uUsed; }\n"}};
    const Program program(files, {"probe.comp"});
    EXPECT_NO_THROW(program.set("uUsed", 1u));
    for (const char* name : {"uUnused", "uMisspelt"}) {
        try {
            program.set(name, 1u);
            ADD_FAILURE() << name << " was set";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("probe.comp"), std::string::npos) << e.what();
        }
    }
}

TEST_F(GpuLayout, EveryProjectProgramBuilds)
{
    for (const char* stage : {"octree_prepare.comp", "octree_flag.comp", "octree_alloc.comp", "octree_fill.comp",
                              "octree_attributes.comp"})
        EXPECT_NO_THROW(Program(voxelizeShaders(), {stage})) << stage;
    EXPECT_NO_THROW(Program(voxelizeShaders(), {"raster.vert", "raster.geom", "raster.frag"}));
}

// ---- Without a GL context -------------------------------------------------

TEST(ShaderSource, IncludesAreWrappedInLineDirectives)
{
    const ShaderFiles files = {{"top.comp", "#version 450 core\n#include \"a.glsl\"\nx\n"},
                               {"a.glsl", "#include \"b.glsl\"\ny\n  #include \"b.glsl\"\n"},
                               {"b.glsl", "z\n"}};
    const ShaderSource s = shaderSource("top.comp", files);
    // Each directive sets the source string and gives the next line its own number.
    EXPECT_EQ(s.text, "#version 450 core\n" // 1
                      "#line 3 1\n"         // 2
                      "#line 4 2\n"         // 3
                      "z\n"                 // 4
                      "#line 6 1\n"         // 5
                      "y\n"                 // 6
                      "#line 8 2\n"         // 7
                      "z\n"                 // 8
                      "#line 10 1\n"        // 9
                      "#line 11 0\n"        // 10
                      "x\n");               // 11
    EXPECT_EQ(s.files, (std::vector<std::string>{"top.comp", "a.glsl", "b.glsl"}));
    ASSERT_EQ(s.lines.size(), 11u);
    const std::pair<uint32_t, uint32_t> expected[] = {{0, 1}, {0, 2}, {1, 1}, {2, 1}, {1, 1}, {1, 2},
                                                      {1, 3}, {2, 1}, {1, 3}, {0, 2}, {0, 3}};
    for (size_t k = 0; k < 11; ++k) {
        EXPECT_EQ(s.lines[k].file, expected[k].first) << "line " << k + 1;
        EXPECT_EQ(s.lines[k].line, expected[k].second) << "line " << k + 1;
    }
}

TEST(ShaderSource, FilesInTheShaderDirReplaceTheEmbeddedOnes)
{
    const ShaderFiles files = {{"top.comp", "#version 450 core\n#include \"a.glsl\"\n"}, {"a.glsl", "embedded\n"}};
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "svo_shader_dir_test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "a.glsl") << "replaced\n";
    setenv("SVO_SHADER_DIR", dir.c_str(), 1);
    const std::string withDir = shaderSource("top.comp", files).text;
    unsetenv("SVO_SHADER_DIR");
    const std::string without = shaderSource("top.comp", files).text;
    std::filesystem::remove_all(dir);
    EXPECT_NE(withDir.find("replaced\n"), std::string::npos) << withDir;
    EXPECT_EQ(withDir.find("embedded"), std::string::npos) << withDir;
    // A file the folder lacks stays the embedded one, and so does everything without the variable.
    EXPECT_NE(withDir.find("#version 450 core"), std::string::npos);
    EXPECT_NE(without.find("embedded\n"), std::string::npos) << without;
}

TEST_F(GpuLayout, FillWordsSetsTheWordsAskedAndKeepsBindingZero)
{
    // 1 M + 3 words: more than one row of work groups' worth of x, and a tail.
    const uint64_t words = (uint64_t(1) << 20) + 3;
    const std::vector<uint32_t> before(words + 5, 0xA5A5A5A5u);
    const Buffer target("fill target", 4 * before.size(), before.data());
    const Buffer bound("bound at 0", 64);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, bound.id(), 16, 32);
    fillWords(*context_, target, 0x7F800000u, 4 * words);
    const std::vector<uint32_t> after = readBack<uint32_t>(target, before.size());
    for (uint64_t i = 0; i < after.size(); ++i)
        ASSERT_EQ(after[i], i < words ? 0x7F800000u : 0xA5A5A5A5u) << "word " << i;
    GLint name = 0;
    GLint64 at = 0, size = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &name);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 0, &at);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 0, &size);
    EXPECT_EQ(GLuint(name), bound.id());
    EXPECT_EQ(at, 16);
    EXPECT_EQ(size, 32);
    // Past the driver's storage block limit: ranges of it, each bound at binding 0.
    setenv("SVO_GL_MAX_STORAGE_BLOCK", "1048576", 1);
    fillWords(*context_, target, 0x3F800000u, 4 * (words - 1));
    unsetenv("SVO_GL_MAX_STORAGE_BLOCK");
    const std::vector<uint32_t> ranged = readBack<uint32_t>(target, before.size());
    for (uint64_t i = 0; i < ranged.size(); ++i)
        ASSERT_EQ(ranged[i], i < words - 1 ? 0x3F800000u : i < words ? 0x7F800000u : 0xA5A5A5A5u) << "word " << i;
    EXPECT_THROW(fillWords(*context_, target, 0, 6), InvalidInput);              // not whole words
    EXPECT_THROW(fillWords(*context_, target, 0, target.bytes() + 4), InvalidInput); // past the end
    checkGl("fillWords test");
}

TEST_F(GpuLayout, LentScratchIsReusedWhenGivenBackAndNeverShared)
{
    const char* name = "lent scratch test";
    Buffer first = context_->lendScratch(name, 1000);
    ASSERT_GE(first.bytes(), 1000u);
    const GLuint id = first.id();
    // While lent, the context holds none: a second lend is another buffer.
    Buffer second = context_->lendScratch(name, 500);
    EXPECT_NE(second.id(), id);
    context_->returnScratch(name, std::move(first));
    context_->returnScratch(name, std::move(second)); // smaller than the one held: freed
    // Given back, it serves any size it holds, and the context holds it no more.
    Buffer again = context_->lendScratch(name, 800);
    EXPECT_EQ(again.id(), id);
    EXPECT_NE(context_->lendScratch(name, 10).id(), id);
    context_->returnScratch(name, std::move(again));
    // A larger request frees it and makes one of that size.
    const Buffer larger = context_->lendScratch(name, 4000);
    EXPECT_GE(larger.bytes(), 4000u);
    context_->releaseScratch(name);
    checkGl("lent scratch test");
}

TEST(ShaderSource, CyclesAndUnknownFilesAreErrors)
{
    EXPECT_THROW(shaderSource("a.glsl", {{"a.glsl", "#include \"b.glsl\"\n"}, {"b.glsl", "#include \"a.glsl\"\n"}}),
                 Error);
    EXPECT_THROW(shaderSource("a.glsl", {{"a.glsl", "#include \"nowhere.glsl\"\n"}}), Error);
}

TEST(ShaderSource, DriverLogsNameFilesAndTheirLines)
{
    const ShaderSource s = shaderSource("top.frag", {{"top.frag", "#version 450 core\n#include \"lib.glsl\"\nvoid main() {}\n"},
                                                     {"lib.glsl", "a\nb\n"}});
    // Expanded: 1 #version, 2 #line, 3 a, 4 b, 5 #line, 6 main. The source
    // number is not trusted (Mesa says 0 for most errors).
    EXPECT_EQ(nameFilesInLog("0:4(3): error: `x' undeclared\n1:6(1): warning: w\n", s),
              "lib.glsl:2(3): error: `x' undeclared\ntop.frag:3(1): warning: w\n");
    EXPECT_EQ(nameFilesInLog("1(3) : error C0000: syntax error\n", s), "lib.glsl(1) : error C0000: syntax error\n");
    EXPECT_EQ(nameFilesInLog("ERROR: 0:6: 'x' : undeclared\n", s), "ERROR: top.frag:3: 'x' : undeclared\n");
    // Lines past the text, and lines without a location, stay as they are.
    EXPECT_EQ(nameFilesInLog("0:99(1): error\nlink failed\n", s), "0:99(1): error\nlink failed\n");
}

} // namespace
