// The public API (svo/svo.h) on OpenVDB types, against independent references:
// CGAL's exact triangle/box test in the index space that OpenVDB's own
// Transform::worldToIndex gives, and identities that must hold exactly.
#include <atomic>
#include <epoxy/egl.h>
#include <fstream>
#include <gtest/gtest.h>
#include <nanovdb/util/IO.h>
#include <openvdb/math/Maps.h>
#include <set>
#include <thread>

#include "scenes.h"
#include "svo/gl/context.h"
#include "svo/core/voxel_key.h"
#include "svo/svo.h"
#include "svo/validate/exact_reference.h"
#include "temp_dir.h"

namespace svo::test {
namespace {

using Coords = std::set<std::array<int32_t, 3>>;

template <typename GridT>
Coords activeCoords(const GridT& grid)
{
    Coords out;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        out.insert({c.x(), c.y(), c.z()});
    }
    return out;
}

struct VdbMesh {
    std::vector<openvdb::Vec3d> points;
    std::vector<openvdb::Vec3I> triangles;
};

VdbMesh toVdb(const TriangleMesh& m, openvdb::Vec3d offset = openvdb::Vec3d(0.0))
{
    VdbMesh out;
    for (const auto& p : m.positions) out.points.emplace_back(openvdb::Vec3d(p.x, p.y, p.z) + offset);
    for (const auto& t : m.triangles) out.triangles.emplace_back(t[0], t[1], t[2]);
    return out;
}

/// The exact reference in the transform's index space as OpenVDB computes it:
/// voxels whose cube shrunk by eps meets a triangle (required) and those whose
/// cube grown by eps does (allowed), as global index coordinates.
struct Reference {
    Coords required, allowed;
};
Reference exactInIndexSpace(const VdbMesh& mesh, const openvdb::math::Transform& xform, double eps)
{
    TriangleMesh idx;
    idx.source = "index-space mesh";
    for (const auto& p : mesh.points) {
        const openvdb::Vec3d i = xform.worldToIndex(p);
        idx.positions.push_back({i[0], i[1], i[2]});
    }
    for (const auto& t : mesh.triangles) idx.triangles.push_back({t[0], t[1], t[2]});
    const GridSpec grid = makeGridOnLattice(idx, 1.0, {0, 0, 0});
    const validate::ReferenceSets ref = validate::exactReference(idx, grid, eps);
    Reference out;
    auto global = [&](uint64_t key) {
        const auto l = unpackVoxelKey(key);
        const auto g = grid.toGlobal(l);
        return std::array<int32_t, 3>{int32_t(g[0]), int32_t(g[1]), int32_t(g[2])};
    };
    for (uint64_t k : ref.required) out.required.insert(global(k));
    for (uint64_t k : ref.allowed) out.allowed.insert(global(k));
    return out;
}

size_t countMissing(const Coords& from, const Coords& in)
{
    size_t n = 0;
    for (const auto& c : from) n += !in.count(c);
    return n;
}

openvdb::math::Transform::Ptr rotatedScaled()
{
    auto xform = openvdb::math::Transform::createLinearTransform(1.0);
    xform->preScale(openvdb::Vec3d(0.031, 0.047, 0.023)); // non-uniform
    xform->postRotate(0.6, openvdb::math::X_AXIS);
    xform->postRotate(-0.35, openvdb::math::Y_AXIS);
    xform->postRotate(1.1, openvdb::math::Z_AXIS);
    xform->postTranslate(openvdb::Vec3d(1.0 / 64, -13.0 / 64, 26.0 / 64)); // exact after adding 1e9 too
    return xform;
}

class Api : public ::testing::Test {
protected:
    static void SetUpTestSuite() { openvdb::initialize(); }
    static Voxelizer& voxelizer()
    {
        static Voxelizer v;
        return v;
    }
};

TEST_F(Api, AnyAffineTransformIsExactInItsIndexSpace)
{
    const VdbMesh sphereMesh = toVdb(sphere({0.1, -0.2, 0.3}, 0.9, 24, 16));
    const VdbMesh random = toVdb(randomTriangles(150, 11));
    std::vector<std::pair<std::string, openvdb::math::Transform::Ptr>> transforms = {
        {"rotated, non-uniform scale", rotatedScaled()},
        {"uniform scale", openvdb::math::Transform::createLinearTransform(0.037)},
    };
    auto shear = openvdb::math::Transform::createLinearTransform(0.05);
    shear->postShear(0.3, openvdb::math::X_AXIS, openvdb::math::Y_AXIS);
    transforms.emplace_back("sheared", shear);
    for (const VdbMesh* mesh : {&sphereMesh, &random}) {
        for (const auto& [name, xform] : transforms) {
            VoxelizeStats stats;
            VoxelizeOptions o;
            o.stats = &stats;
            const auto grid = voxelizer().meshToMask(mesh->points, mesh->triangles, *xform, o);
            EXPECT_EQ(grid->transform(), *xform) << name;
            const Coords got = activeCoords(*grid);
            const Reference ref = exactInIndexSpace(*mesh, *xform, stats.epsilon);
            EXPECT_GT(ref.required.size(), 100u) << name;
            EXPECT_EQ(countMissing(ref.required, got), 0u) << name << ": voxels the exact test requires are missing";
            EXPECT_EQ(countMissing(got, ref.allowed), 0u) << name << ": voxels no triangle comes near";
        }
    }
}

TEST_F(Api, CpuBackendGivesTheSameVoxelsUpToTheGuardBand)
{
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 20, 12));
    const auto xform = rotatedScaled();
    VoxelizeOptions cpu;
    cpu.backend = Backend::Cpu;
    VoxelizeStats stats;
    VoxelizeOptions gpu;
    gpu.stats = &stats;
    const Coords a = activeCoords(*voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, cpu));
    const Coords b = activeCoords(*voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, gpu));
    const Reference ref = exactInIndexSpace(mesh, *xform, stats.epsilon);
    // The CPU reference has no guard band: it lies between R and A too.
    EXPECT_EQ(countMissing(ref.required, a), 0u);
    EXPECT_EQ(countMissing(a, ref.allowed), 0u);
    EXPECT_EQ(countMissing(a, b), 0u) << "the GPU misses voxels the CPU reference has";
}

TEST_F(Api, ThinModeIsInsideConservativeAndHoldsTheExactThinSet)
{
    // Through the public API with a rotated, non-uniform transform: the thin
    // voxels of every backend hold CGAL's exact thin set (segment tests in
    // the index space OpenVDB's worldToIndex gives) and lie inside the
    // conservative voxels; the statistics name the mode.
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 20, 12));
    const auto xform = rotatedScaled();
    TriangleMesh idx;
    for (const auto& p : mesh.points) {
        const openvdb::Vec3d i = xform->worldToIndex(p);
        idx.positions.push_back({i[0], i[1], i[2]});
    }
    for (const auto& t : mesh.triangles) idx.triangles.push_back({t[0], t[1], t[2]});
    const GridSpec grid = makeGridOnLattice(idx, 1.0, {0, 0, 0});
    const auto ref = validate::exactReference(idx, grid, 0.0, VoxelMode::Thin);
    Coords exact;
    for (uint64_t k : ref.exact) {
        const auto g = grid.toGlobal(unpackVoxelKey(k));
        exact.insert({int32_t(g[0]), int32_t(g[1]), int32_t(g[2])});
    }
    VoxelizeOptions conservative;
    const Coords cube = activeCoords(*voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, conservative));
    for (const Backend backend : {Backend::Raster, Backend::Compute, Backend::Cpu}) {
        VoxelizeStats stats;
        VoxelizeOptions o;
        o.backend = backend;
        o.mode = VoxelMode::Thin;
        o.stats = &stats;
        const Coords thin = activeCoords(*voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, o));
        EXPECT_EQ(stats.mode, "thin");
        EXPECT_EQ(countMissing(exact, thin), 0u) << stats.backend;
        EXPECT_EQ(countMissing(thin, cube), 0u) << stats.backend;
        EXPECT_LT(thin.size(), cube.size());
    }
}

TEST_F(Api, ComputeBackendGivesTheRasterBackendsVoxelsAndAttributes)
{
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 20, 12));
    const auto xform = rotatedScaled();
    VoxelizeOptions raster, compute;
    raster.backend = Backend::Raster;
    // Shader dilation gives every column one fragment, so the two lists hold the
    // same (voxel, triangle) entries and the attribute sums agree exactly.
    raster.dilation = Dilation::Shader;
    compute.backend = Backend::Compute;
    raster.attributes = compute.attributes = kNormals | kTriangles;
    VoxelizeStats stats;
    compute.stats = &stats;
    const auto a = voxelizer().meshToGrids(mesh.points, mesh.triangles, *xform, raster);
    const auto b = voxelizer().meshToGrids(mesh.points, mesh.triangles, *xform, compute);
    EXPECT_EQ(stats.backend, "compute");
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE(a[i]->getName());
        EXPECT_EQ(a[i]->activeVoxelCount(), b[i]->activeVoxelCount());
        // Same voxels, and the same smallest triangle and summed normal at each.
        if (auto ia = openvdb::gridPtrCast<openvdb::Int32Grid>(a[i])) {
            auto ib = openvdb::gridPtrCast<openvdb::Int32Grid>(b[i]);
            ASSERT_TRUE(ib);
            for (auto it = ia->cbeginValueOn(); it; ++it) EXPECT_EQ(ib->tree().getValue(it.getCoord()), *it);
        }
        if (auto na = openvdb::gridPtrCast<openvdb::Vec3SGrid>(a[i])) {
            auto nb = openvdb::gridPtrCast<openvdb::Vec3SGrid>(b[i]);
            ASSERT_TRUE(nb);
            for (auto it = na->cbeginValueOn(); it; ++it) EXPECT_EQ(nb->tree().getValue(it.getCoord()), *it);
        }
    }
    EXPECT_EQ(activeCoords(*voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, raster)),
              activeCoords(*voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, compute)));
}

TEST_F(Api, FarFromTheOriginGivesWhatItGivesAtTheOrigin)
{
    // Coordinates on a 1/64 lattice, so p + 1e9 is exact in double.
    TriangleMesh m = randomTriangles(200, 5);
    for (auto& p : m.positions)
        p = {std::round(p.x * 64) / 64, std::round(p.y * 64) / 64, std::round(p.z * 64) / 64};
    const openvdb::Vec3d offset(1e9, -1e9, 1e9);
    const VdbMesh near = toVdb(m), far = toVdb(m, offset);
    auto lattice = openvdb::math::Transform::createLinearTransform(0.125);
    auto rotated = rotatedScaled();
    for (auto base : {lattice, rotated}) {
        auto moved = base->copy();
        moved->postTranslate(offset);
        const Coords a = activeCoords(*voxelizer().meshToMask(near.points, near.triangles, *base));
        const Coords b = activeCoords(*voxelizer().meshToMask(far.points, far.triangles, *moved));
        EXPECT_GT(a.size(), 100u);
        EXPECT_EQ(a, b) << (base == lattice ? "uniform lattice" : "rotated, non-uniform scale");
    }
}

TEST_F(Api, ReuseGivesIdenticalResultsAndErrorsLeaveItUsable)
{
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 16, 10));
    const auto xform = openvdb::math::Transform::createLinearTransform(0.04);
    Voxelizer v;
    const Coords first = activeCoords(*v.meshToMask(mesh.points, mesh.triangles, *xform));
    auto badIndex = mesh.triangles;
    badIndex.back()[2] = uint32_t(mesh.points.size());
    auto nan = mesh.points;
    nan[3][1] = std::numeric_limits<double>::quiet_NaN();
    auto huge = mesh.points; // 5e6 voxels a side: beyond svo's 2^21
    for (auto& p : huge) p *= 1e5;
    for (int i = 0; i < 12; ++i) {
        switch (i % 4) {
        case 0: EXPECT_THROW(v.meshToMask(mesh.points, badIndex, *xform), svo::Error); break;
        case 1: EXPECT_THROW(v.meshToMask(nan, mesh.triangles, *xform), svo::Error); break;
        case 2: EXPECT_THROW(v.meshToMask(huge, mesh.triangles, *xform), svo::Error); break;
        default: break;
        }
        EXPECT_EQ(activeCoords(*v.meshToMask(mesh.points, mesh.triangles, *xform)), first) << "call " << i;
    }
}

TEST_F(Api, ErrorsNameTheProblemAndTheValue)
{
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 8, 6));
    auto bad = mesh.triangles;
    bad[5][1] = 1234567;
    try {
        voxelizer().meshToMask(mesh.points, bad, *openvdb::math::Transform::createLinearTransform(0.1));
        FAIL() << "no error";
    } catch (const svo::Error& e) {
        EXPECT_NE(std::string(e.what()).find("triangle 5 refers to vertex 1234567"), std::string::npos) << e.what();
    }
    const openvdb::BBoxd box(openvdb::Vec3d(-1), openvdb::Vec3d(1));
    const openvdb::math::Transform frustum(
        std::make_shared<openvdb::math::NonlinearFrustumMap>(box, 0.5, 2.0));
    try {
        voxelizer().meshToMask(mesh.points, mesh.triangles, frustum);
        FAIL() << "no error";
    } catch (const svo::Error& e) {
        EXPECT_NE(std::string(e.what()).find("not linear"), std::string::npos) << e.what();
    }
}

TEST_F(Api, ErrorsAreTypedByWhatFailedAndNameTheOptionApart)
{
    // Bad input: InvalidInput, the option's identifier kept apart from the words.
    LevelSetOptions ls;
    ls.exteriorBand = 0.5;
    try {
        checkLevelSetOptions(ls);
        FAIL() << "no error";
    } catch (const InvalidInput& e) {
        EXPECT_EQ(e.argument(), "LevelSetOptions::exteriorBand");
        EXPECT_EQ(e.detail(), "0.5: a band is a number of voxels from 1 to 1000");
        EXPECT_EQ(std::string(e.what()), "LevelSetOptions::exteriorBand 0.5: a band is a number of voxels from 1 to 1000");
    }
    // A rule checked under a caller's name names it: that name is the argument.
    try {
        checkWindingAccuracy(0, "winding_accuracy");
        FAIL() << "no error";
    } catch (const InvalidInput& e) {
        EXPECT_EQ(e.argument(), "winding_accuracy");
        EXPECT_EQ(std::string(e.what()).rfind("winding_accuracy 0: the winding accuracy", 0), 0u) << e.what();
    }
    // An option named twice is renamed twice by a front end; what() keeps the library's words.
    VoxelizeOptions thin;
    thin.mode = VoxelMode::Thin;
    try {
        checkFieldMode(thin);
        FAIL() << "no error";
    } catch (const InvalidInput& e) {
        EXPECT_EQ(e.argument(), "VoxelizeOptions::mode");
        EXPECT_EQ(std::string(e.what()).rfind("VoxelizeOptions::mode thin: VoxelizeOptions::mode applies", 0), 0u)
            << e.what();
        const std::string renamed = e.message([](const std::string& id) {
            return id == "VoxelizeOptions::mode" ? std::string("mode=") : std::string();
        });
        EXPECT_EQ(renamed.rfind("mode= thin: mode= applies to surface voxels", 0), 0u) << renamed;
    }
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 8, 6));
    const auto xform = openvdb::math::Transform::createLinearTransform(0.1);
    auto bad = mesh.triangles;
    bad[5][1] = 1234567;
    EXPECT_THROW(voxelizer().meshToMask(mesh.points, bad, *xform), InvalidInput);
    // Files: IoError, the missing and the damaged.
    const TempDir dir("api_errors");
    EXPECT_THROW(readOctreeFile(dir.path("missing.svo")), IoError);
    std::ofstream(dir.path("damaged.svo")) << "SVOCTREE and then nothing an octree needs";
    EXPECT_THROW(readOctreeFile(dir.path("damaged.svo")), IoError);
    std::ofstream(dir.path("empty.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\n"; // no faces: a file of no mesh
    EXPECT_THROW(loadMesh(dir.path("empty.obj")), IoError);
    // Work svo has no method for: Unsupported. GPU memory: OutOfMemory.
    // (A level set's distances are world distances only under a uniform scale.)
    EXPECT_THROW(voxelizer().meshToLevelSet(mesh.points, mesh.triangles, *rotatedScaled()), Unsupported);
    VoxelizeOptions tiny;
    tiny.gpuMemory = 1024;
    EXPECT_THROW(voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, tiny), OutOfMemory);
    // No such GPU: DeviceError. Stopped: Interrupted.
    Voxelizer nowhere(DeviceOptions{"no-such-device", false, "off"});
    EXPECT_THROW(nowhere.meshToMask(mesh.points, mesh.triangles, *xform), DeviceError);
    EXPECT_THROW(Checkpoint([](int) { return true; })(0.5, "a test"), Interrupted);
    // Every kind is an svo::Error, and a std::runtime_error.
    EXPECT_THROW(voxelizer().meshToMask(mesh.points, mesh.triangles, *xform, tiny), Error);
    EXPECT_THROW(readOctreeFile(dir.path("missing.svo")), std::runtime_error);
    // The one voxelizer is still usable.
    EXPECT_GT(voxelizer().meshToMask(mesh.points, mesh.triangles, *xform)->activeVoxelCount(), 0u);
}

/// Cancels once the call reports `at` percent; counts the calls it gets.
struct CancelAt : openvdb::util::NullInterrupter {
    explicit CancelAt(int percent) : at(percent) {}
    void start(const char*) override { ++starts; }
    void end() override { ++ends; }
    bool wasInterrupted(int percent) override
    {
        seen.push_back(percent);
        return percent >= at;
    }
    int at, starts = 0, ends = 0;
    std::vector<int> seen;
};

TEST_F(Api, InterrupterStopsTheCallAndIsToldTheShareDone)
{
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 40, 30));
    const auto xform = openvdb::math::Transform::createLinearTransform(0.01);
    Voxelizer v;
    for (int at : {0, 10, 60, 90}) {
        CancelAt stop(at);
        VoxelizeOptions o;
        o.interrupter = &stop;
        EXPECT_THROW(v.meshToMask(mesh.points, mesh.triangles, *xform, o), svo::Interrupted) << at;
        EXPECT_EQ(stop.starts, 1);
        EXPECT_EQ(stop.ends, 1) << "end() must follow start() on the way out";
    }
    CancelAt never(101);
    VoxelizeOptions o;
    o.interrupter = &never;
    const auto grid = v.meshToMask(mesh.points, mesh.triangles, *xform, o);
    EXPECT_GT(grid->activeVoxelCount(), 1000u);
    ASSERT_FALSE(never.seen.empty());
    EXPECT_TRUE(std::is_sorted(never.seen.begin(), never.seen.end())) << "percentages only grow";
    EXPECT_EQ(never.seen.back(), 100);
}

// The CPU reference polls between batches of columns, so a long CPU call is
// cancelled while it voxelizes, not only between stages (0 % and 60 %).
TEST_F(Api, TheCpuBackendIsInterruptedWhileItVoxelizes)
{
    // A unit square at 1/2000: two triangles of about 2 M columns each.
    const std::vector<openvdb::Vec3d> points{{0, 0, 0}, {1, 0, 0.01}, {1, 1, 0.02}, {0, 1, 0.01}};
    const std::vector<openvdb::Vec3I> triangles{{0, 1, 2}, {0, 2, 3}};
    const auto xform = openvdb::math::Transform::createLinearTransform(1.0 / 2000);
    CancelAt stop(5);
    VoxelizeOptions o;
    o.backend = Backend::Cpu;
    o.interrupter = &stop;
    EXPECT_THROW(voxelizer().meshToMask(points, triangles, *xform, o), svo::Interrupted);
    ASSERT_FALSE(stop.seen.empty());
    EXPECT_GT(stop.seen.back(), 0);
    EXPECT_LT(stop.seen.back(), 60) << "cancelled only after the CPU voxelization";
    EXPECT_EQ(stop.ends, 1);
}

// backendFor tells what Auto runs on without creating a context, and the
// call agrees: the CPU on a software renderer, compute on a GPU (design.md,
// "Which backend auto picks"), the GL passes on a named device.
TEST_F(Api, BackendForSaysWhatAutoRunsOn)
{
    const bool software = gl::Context().info().software; // the renderer's own word, apart from the rule
    Voxelizer v;
    const Backend expected = v.backendFor({});
    EXPECT_EQ(expected, software ? Backend::Cpu : Backend::Compute);
    VoxelizeOptions shader;
    shader.dilation = Dilation::Shader;
    EXPECT_EQ(v.backendFor(shader), Backend::Raster);
    VoxelizeOptions cpu;
    cpu.backend = Backend::Cpu;
    EXPECT_EQ(v.backendFor(cpu), Backend::Cpu);
    VoxelizeOptions budget;
    budget.gpuMemory = uint64_t(1) << 30;
    EXPECT_EQ(v.backendFor(budget), software ? Backend::Raster : Backend::Compute);
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 8, 6));
    VoxelizeStats stats;
    VoxelizeOptions o;
    o.stats = &stats;
    v.meshToMask(mesh.points, mesh.triangles, *openvdb::math::Transform::createLinearTransform(0.1), o);
    EXPECT_EQ(stats.backend, nameOf(expected));
    EXPECT_EQ(v.backendFor({}), expected) << "the same with a context";
    Voxelizer named(DeviceOptions{software ? "software" : "hardware", false, "off"});
    EXPECT_EQ(named.backendFor({}), software ? Backend::Raster : Backend::Compute);
}

TEST_F(Api, CallerContextIsCurrentAgainOnEveryPathOut)
{
    // The "host": another GL context, current on this thread as an application's would be.
    gl::Context host;
    const gl::Context::Scope hostScope(host);
    const EGLContext before = eglGetCurrentContext();
    ASSERT_NE(before, EGL_NO_CONTEXT);
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 16, 10));
    const auto xform = openvdb::math::Transform::createLinearTransform(0.05);
    Voxelizer v; // its context is created inside the first call
    EXPECT_GT(v.meshToMask(mesh.points, mesh.triangles, *xform)->activeVoxelCount(), 0u);
    EXPECT_EQ(eglGetCurrentContext(), before);
    CancelAt stop(20); // thrown from inside the GPU stages
    VoxelizeOptions o;
    o.interrupter = &stop;
    EXPECT_THROW(v.meshToMask(mesh.points, mesh.triangles, *xform, o), svo::Interrupted);
    EXPECT_EQ(eglGetCurrentContext(), before);
    VoxelizeOptions hw;
    hw.dilation = Dilation::Hardware;
    try {
        v.meshToMask(mesh.points, mesh.triangles, *xform, hw); // an error where the extension is missing
    } catch (const svo::Error&) {
    }
    EXPECT_EQ(eglGetCurrentContext(), before);
}

TEST_F(Api, TwoThreadsWithTwoVoxelizers)
{
    const VdbMesh a = toVdb(sphere({0, 0, 0}, 1.0, 30, 20)), b = toVdb(randomTriangles(100, 3));
    const auto xform = rotatedScaled();
    const Coords wantA = activeCoords(*voxelizer().meshToMask(a.points, a.triangles, *xform));
    const Coords wantB = activeCoords(*voxelizer().meshToMask(b.points, b.triangles, *xform));
    Coords gotA, gotB;
    std::thread ta([&] {
        Voxelizer v;
        for (int i = 0; i < 2; ++i) gotA = activeCoords(*v.meshToMask(a.points, a.triangles, *xform));
    });
    std::thread tb([&] {
        Voxelizer v;
        for (int i = 0; i < 2; ++i) gotB = activeCoords(*v.meshToMask(b.points, b.triangles, *xform));
    });
    ta.join();
    tb.join();
    EXPECT_EQ(gotA, wantA);
    EXPECT_EQ(gotB, wantB);
}

TEST_F(Api, QuadsAreTwoTrianglesAndInvalidIndexMarksATriangle)
{
    const TriangleMesh cube = box({0, 0, 0}, {1, 1, 1}); // 12 triangles, pairs share a diagonal
    VdbMesh tri = toVdb(cube);
    std::vector<openvdb::Vec4I> quads;
    std::vector<openvdb::Vec3I> none;
    for (size_t t = 0; t + 1 < tri.triangles.size(); t += 2) {
        const auto& p = tri.triangles[t];
        const auto& q = tri.triangles[t + 1];
        // box() emits (a, b, c), (a, c, d): the quad (a, b, c, d).
        ASSERT_EQ(p[0], q[0]);
        ASSERT_EQ(p[2], q[1]);
        quads.emplace_back(p[0], p[1], p[2], q[2]);
    }
    quads.emplace_back(tri.triangles[0][0], tri.triangles[0][1], tri.triangles[0][2], openvdb::util::INVALID_IDX);
    const auto xform = rotatedScaled();
    const Coords fromTriangles = activeCoords(*voxelizer().meshToMask(tri.points, tri.triangles, *xform));
    const Coords fromQuads = activeCoords(*voxelizer().meshToMask(tri.points, none, quads, *xform));
    EXPECT_EQ(fromQuads, fromTriangles);
}

TEST_F(Api, BoolFogAndFloatPointsGiveTheSameVoxels)
{
    // Float input: vertices exactly representable in float, so both precisions agree.
    const TriangleMesh m = sphere({0, 0, 0}, 1.0, 18, 12);
    std::vector<openvdb::Vec3s> pointsF;
    VdbMesh d;
    for (const auto& p : m.positions) {
        pointsF.emplace_back(float(p.x), float(p.y), float(p.z));
        d.points.emplace_back(double(float(p.x)), double(float(p.y)), double(float(p.z)));
    }
    for (const auto& t : m.triangles) d.triangles.emplace_back(t[0], t[1], t[2]);
    const auto xform = openvdb::math::Transform::createLinearTransform(0.03);
    const Coords mask = activeCoords(*voxelizer().meshToMask(d.points, d.triangles, *xform));
    EXPECT_EQ(activeCoords(*voxelizer().meshToMask(pointsF, d.triangles, *xform)), mask);
    const auto boolGrid = voxelizer().meshToBool(d.points, d.triangles, *xform);
    EXPECT_EQ(activeCoords(*boolGrid), mask);
    for (auto it = boolGrid->cbeginValueOn(); it; ++it) EXPECT_TRUE(*it);
    const auto fog = voxelizer().meshToFog(d.points, d.triangles, *xform);
    EXPECT_EQ(fog->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(activeCoords(*fog), mask);
    // One-off free function: the same again.
    EXPECT_EQ(activeCoords(*svo::meshToMask(d.points, d.triangles, *xform)), mask);
}

TEST_F(Api, OctreeToGridsAndBack)
{
    const VdbMesh mesh = toVdb(sphere({0.2, 0.1, 0}, 0.8, 24, 16));
    const auto xform = openvdb::math::Transform::createLinearTransform(0.02);
    VoxelizeOptions o;
    o.attributes = kNormals | kTriangles;
    const Octree octree = voxelizer().meshToOctree(mesh.points, mesh.triangles, {}, *xform, o);
    EXPECT_TRUE(checkOctree(octree).empty());
    GridOptions g;
    g.fog = true;
    const openvdb::GridPtrVec grids = octreeToGrids(octree, g);
    ASSERT_EQ(grids.size(), 4u); // surface, density, normal, triangle_id
    EXPECT_EQ(grids[0]->getName(), "surface");
    EXPECT_EQ(grids[2]->getName(), "normal");
    EXPECT_EQ(grids[0]->transform(), *xform);
    EXPECT_EQ(grids[0]->activeVoxelCount(), octree.voxelCount());
    for (const auto& grid : grids) {
        const Octree back = voxelizer().gridToOctree(*grid);
        EXPECT_EQ(octreeKeys(back).size(), octree.voxelCount()) << grid->getName();
        EXPECT_EQ(activeCoords(*openvdb::gridPtrCast<openvdb::MaskGrid>(octreeToGrids(back)[0])),
                  activeCoords(*openvdb::gridPtrCast<openvdb::MaskGrid>(grids[0])))
            << grid->getName();
    }
}

// A result carries its record of what ran, and the grids made of it say so:
// the octree's backend, mode and renderer; a level set's also its sign method.
TEST_F(Api, GridsCarryTheRecordOfWhatMadeThem)
{
    const VdbMesh mesh = toVdb(sphere({0.2, 0.1, 0}, 0.8, 24, 16));
    const auto xform = openvdb::math::Transform::createLinearTransform(0.05);
    VoxelizeOptions o;
    o.backend = Backend::Cpu;
    o.mode = VoxelMode::Thin;
    const Octree octree = voxelizer().meshToOctree(mesh.points, mesh.triangles, {}, *xform, o);
    EXPECT_EQ(octree.madeBy.backend, "cpu");
    EXPECT_EQ(octree.madeBy.mode, "thin");
    for (const auto& grid : octreeToGrids(octree, GridOptions{})) {
        EXPECT_EQ(grid->metaValue<std::string>("svo:backend"), "cpu");
        EXPECT_EQ(grid->metaValue<std::string>("svo:mode"), "thin");
        EXPECT_EQ(grid->metaValue<std::string>("svo:renderer"), "cpu");
    }
    // A grid read back into an octree was not voxelized: no record to repeat.
    const Octree back = voxelizer().gridToOctree(*octreeToGrids(octree)[0]);
    const openvdb::GridBase::Ptr again = octreeToGrids(back)[0];
    EXPECT_FALSE((*again)["svo:backend"]);
    EXPECT_FALSE((*again)["svo:mode"]);

    VoxelizeStats stats;
    VoxelizeOptions field;
    field.stats = &stats;
    LevelSetOptions ls;
    ls.closestTriangle = true;
    const TriangleMesh ball = icosphere({0.2, 0.1, 0}, 0.8, 3); // closed: parity signs
    GridRequest request;
    request.resolution = 32;
    const openvdb::GridPtrVec grids = voxelizer().levelSet(ball, makeGrid(ball, request), ls, field);
    ASSERT_EQ(grids.size(), 2u);
    for (const auto& grid : grids) {
        EXPECT_EQ(grid->metaValue<std::string>("svo:sign"), stats.sign);
        EXPECT_EQ(grid->metaValue<std::string>("svo:sign").rfind("parity: the mesh is closed", 0), 0u) << stats.sign;
        EXPECT_EQ(grid->metaValue<std::string>("svo:backend"), stats.backend);
    }
}

TEST_F(Api, NanoVdbFileHoldsTheSameVoxels)
{
    const TempDir dir("api");
    const VdbMesh mesh = toVdb(sphere({0, 0, 0}, 1.0, 20, 14));
    const auto xform = openvdb::math::Transform::createLinearTransform(0.05);
    const Octree octree = voxelizer().meshToOctree(mesh.points, mesh.triangles, {}, *xform);
    GridOptions g;
    g.fog = true;
    const std::string path = dir.path("out.nvdb");
    const WriteReport r = writeOctree(path, octree, g);
    EXPECT_EQ(r.format, OutputFormat::NanoVdb);
    const auto mask = openvdb::gridPtrCast<openvdb::MaskGrid>(octreeToGrids(octree)[0]);
    const auto handles = nanovdb::io::readGrids(path);
    ASSERT_EQ(handles.size(), 2u);
    const auto* nanoMask = handles[0].grid<nanovdb::ValueMask>();
    const auto* nanoFog = handles[1].grid<float>();
    ASSERT_TRUE(nanoMask && nanoFog);
    EXPECT_EQ(std::string(nanoMask->gridName()), "surface");
    EXPECT_EQ(nanoMask->activeVoxelCount(), mask->activeVoxelCount());
    EXPECT_EQ(nanoFog->activeVoxelCount(), mask->activeVoxelCount());
    EXPECT_DOUBLE_EQ(nanoMask->voxelSize()[0], 0.05);
    const auto acc = nanoFog->getAccessor();
    for (auto it = mask->cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        const nanovdb::Coord n(c.x(), c.y(), c.z());
        ASSERT_TRUE(acc.isActive(n));
        ASSERT_EQ(acc.getValue(n), 1.0f);
    }
}

} // namespace
} // namespace svo::test
