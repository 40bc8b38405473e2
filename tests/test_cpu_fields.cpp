// Level sets, unsigned distance fields and solids on the CPU (Backend::Cpu:
// svo/core/band_distances.h, parity_crossings.h, winding_signs.h) against the
// GPU path (llvmpipe in CI) on the scenes the GPU suites use: the same band
// bricks, the same active voxels, bit-identical distances and closest
// triangles, the same signs everywhere (band bricks, runs, whole bricks and
// voxel-by-voxel bricks beyond the band), and the same solids. The GPU path
// is itself held to CGAL in test_level_set; holding the CPU path to the GPU's
// bits holds it to CGAL too.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <functional>
#include <map>
#include <gtest/gtest.h>

#include "gl_backend.h"
#include "scenes.h"
#include "stability_scenes.h"
#include "svo/core/mesh_io.h"
#include "svo/core/cpu_voxelizer.h"
#include "svo/core/band_bricks.h"
#include "svo/core/local_positions.h"
#include "svo/core/voxel_key.h"
#include "svo/core/winding_columns.h"
#include "svo/core/winding_signs.h"
#include "svo/core/winding_tree_cache.h"
#include "svo/gl/device.h"
#include "svo/gl/field_pipeline.h"
#include "svo/svo.h"

namespace svo::test {
namespace {

using Clock = std::chrono::steady_clock;

struct Run {
    DistanceBricks field;
    VoxelizeStats stats;
    double ms = 0;
};

Run levelSet(gl::Device& device, const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
             Backend backend)
{
    VoxelizeSettings settings;
    settings.backend = backend;
    Run r;
    const auto t0 = Clock::now();
    r.field = gl::levelSetBricks(device, mesh, grid, ls, settings, Checkpoint{}, r.stats);
    r.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return r;
}

/// Per brick coordinate, the voxels inside beyond the band: whole bricks,
/// voxel-by-voxel bricks (empty ones left out).
std::map<BrickCoord, Brick> beyondBand(const FieldSigns& s)
{
    std::map<BrickCoord, Brick> out;
    Brick full;
    std::fill(full.words, full.words + 8, ~uint64_t(0));
    for (const auto& b : s.insideBricks) out[b] = full;
    for (const auto& [b, m] : s.partial)
        if (m.count()) out[b] = m;
    return out;
}

/// Where two winding-number signs may differ: a centre whose exact winding
/// number (every triangle's solid angle in double) is 1/2 to within float
/// rounding, as on a face of a closed mesh, where either side is the answer
/// (test_level_set excludes such centres from its CGAL checks too). On
/// llvmpipe the CPU's sums are the GPU's bit for bit (the same operations and
/// Mesa's arctangent polynomial), and no such centre differs but on the one
/// triangle spanning a 512³ grid, where llvmpipe fuses a multiply-add in the
/// double solid angle; a hardware GPU's own arctangent can move others.
/// A centre on the surface (within 1e-6 voxel, test_level_set's tolerance)
/// is a tie too: there the winding number jumps, and a solid angle summed
/// from a point in a triangle's plane is 0 or +-1/2 as rounding has it.
struct WindingTies {
    std::vector<Vec3d> local;
    const TriangleMesh* mesh = nullptr;
    uint64_t seen = 0;
    bool allowed(const BrickCoord& b, uint32_t v)
    {
        const Vec3d q{double(8 * b[0] + (v >> 6)), double(8 * b[1] + ((v >> 3) & 7)), double(8 * b[2] + (v & 7))};
        ++seen;
        return std::abs(windingNumber(local, mesh->triangles, q) - 0.5) < 1e-4 || surfaceDistance(q) < 1e-6;
    }
    static double segment2(const Vec3d& p, const Vec3d& a, const Vec3d& b)
    {
        const Vec3d ab = b - a;
        const double l2 = dot(ab, ab);
        const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
        const Vec3d d = p - (a + t * ab);
        return dot(d, d);
    }
    double surfaceDistance(const Vec3d& p) const
    {
        double best = 1e300;
        for (const auto& f : mesh->triangles) {
            const Vec3d &a = local[f[0]], &b = local[f[1]], &c = local[f[2]];
            const Vec3d n = cross(b - a, c - a);
            const double n2 = dot(n, n);
            double d2;
            if (n2 > 0 && dot(cross(b - a, p - a), n) >= 0 && dot(cross(c - b, p - b), n) >= 0 &&
                dot(cross(a - c, p - c), n) >= 0)
                d2 = dot(p - a, n) * dot(p - a, n) / n2;
            else
                d2 = std::min({segment2(p, a, b), segment2(p, b, c), segment2(p, c, a)});
            best = std::min(best, d2);
        }
        return std::sqrt(best);
    }
};

/// The two FieldSigns give every voxel the same side (winding signs: but
/// for WindingTies).
void expectSameSigns(const FieldSigns& gpu, const FieldSigns& cpu, const std::vector<BrickCoord>& bricks,
                     WindingTies* ties, const std::function<bool(const BrickCoord&, uint32_t, bool)>& alsoAllowed = nullptr)
{
    ASSERT_EQ(gpu.inside.size(), cpu.inside.size());
    uint64_t differ = 0, inside = 0;
    const auto compare = [&](const BrickCoord& c, const Brick& a, const Brick& b) {
        for (uint32_t w = 0; w < 8; ++w)
            for (uint64_t d = a.words[w] ^ b.words[w]; d; d &= d - 1) {
                const uint32_t v = 64 * w + uint32_t(__builtin_ctzll(d));
                if (alsoAllowed && alsoAllowed(c, v, (a.words[w] >> (v & 63)) & 1)) continue;
                if (ties && ties->allowed(c, v)) continue;
                if (++differ < 5)
                    ADD_FAILURE() << "brick (" << c[0] << ", " << c[1] << ", " << c[2] << ") voxel " << v << ": gpu "
                                  << ((a.words[w] >> (v & 63)) & 1) << ", cpu " << ((b.words[w] >> (v & 63)) & 1);
            }
    };
    for (size_t i = 0; i < gpu.inside.size(); ++i) {
        inside += gpu.inside[i].count();
        compare(bricks[i], gpu.inside[i], cpu.inside[i]);
    }
    // Parity: runs of whole bricks between band bricks.
    ASSERT_EQ(gpu.runs.size(), cpu.runs.size());
    for (size_t i = 0; i < gpu.runs.size(); ++i) {
        EXPECT_EQ(gpu.runs[i].first, cpu.runs[i].first);
        EXPECT_EQ(gpu.runs[i].bricks, cpu.runs[i].bricks);
        EXPECT_EQ(gpu.runs[i].columns, cpu.runs[i].columns);
    }
    EXPECT_EQ(gpu.openColumns, cpu.openColumns);
    // Winding: the bricks beyond the band, voxel for voxel.
    const auto a = beyondBand(gpu), b = beyondBand(cpu);
    for (const auto& [c, m] : a) {
        const auto it = b.find(c);
        compare(c, m, it == b.end() ? Brick{} : it->second);
    }
    for (const auto& [c, m] : b)
        if (!a.count(c)) compare(c, Brick{}, m);
    EXPECT_EQ(differ, 0u) << "voxels on different sides (of " << inside << " inside in the band)";
}

/// Both paths' level sets (or unsigned fields) agree, bit for bit.
void expectSameLevelSet(gl::Device& device, const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls)
{
    SCOPED_TRACE(mesh.source + (ls.unsignedDistance ? " (unsigned)" : " (signed)"));
    const Run cpu = levelSet(device, mesh, grid, ls, Backend::Cpu);
    Run gpu;
    try {
        gpu = levelSet(device, mesh, grid, ls, kGl);
    } catch (const DeviceError& e) {
        // llvmpipe's loop limit refuses some winding walks the CPU has no limit on.
        ASSERT_NE(std::string(e.what()).find("ends a shader's loops"), std::string::npos) << e.what();
        std::cout << "[ cpu fields ] " << mesh.source << ": the GPU path refused (" << e.what() << "); the CPU made "
                  << cpu.field.distances.size() << " band voxels\n";
        EXPECT_FALSE(cpu.field.bricks.empty());
        return;
    }
    EXPECT_EQ(cpu.stats.backend, "cpu");
    EXPECT_EQ(cpu.stats.device, "cpu");
    EXPECT_EQ(cpu.stats.sign, gpu.stats.sign);
    EXPECT_EQ(cpu.stats.bandBricks, gpu.stats.bandBricks);
    EXPECT_EQ(cpu.stats.windingBricks, gpu.stats.windingBricks);
    EXPECT_EQ(cpu.stats.openColumns, gpu.stats.openColumns);
    EXPECT_EQ(cpu.stats.warnings, gpu.stats.warnings);
    EXPECT_EQ(cpu.field.grid.anchor, gpu.field.grid.anchor);
    EXPECT_EQ(cpu.field.grid.dims, gpu.field.grid.dims);
    EXPECT_EQ(cpu.field.signedField, gpu.field.signedField);
    EXPECT_EQ(cpu.field.winding, gpu.field.winding);
    EXPECT_EQ(cpu.field.closestTriangle, gpu.field.closestTriangle);
    ASSERT_EQ(cpu.field.bricks, gpu.field.bricks);
    ASSERT_EQ(cpu.field.near.size(), gpu.field.near.size());
    ASSERT_EQ(cpu.field.distances.size(), gpu.field.distances.size());
    ASSERT_EQ(cpu.field.closest.size(), gpu.field.closest.size());
    EXPECT_EQ(cpu.field.closest.empty(), !ls.closestTriangle);
    // The GPU packs bricks in the order they finish: compare brick by brick.
    uint64_t maskDiffer = 0, distanceDiffer = 0, closestDiffer = 0, nearZero = 0;
    float worst = 0;
    for (size_t i = 0; i < gpu.field.near.size(); ++i) {
        if (!(gpu.field.near[i] == cpu.field.near[i])) {
            ++maskDiffer;
            continue;
        }
        for (uint32_t k = 0, n = gpu.field.near[i].count(); k < n; ++k) {
            const size_t a = gpu.field.offsets[i] + k, b = cpu.field.offsets[i] + k;
            const float dg = gpu.field.distances[a], dc = cpu.field.distances[b];
            if (dg != dc) {
                // A driver may fuse a multiply-add that the CPU rounds twice
                // (llvmpipe rarely, NVIDIA's often): the doubles then differ
                // in their last bits, which only a distance of a cancelling
                // few ulps (a centre on the triangle's plane) keeps after
                // rounding to float. Such a difference is far below any
                // distance's own rounding: allowed, counted and reported.
                if (std::max(dg, dc) > 1e-3f || std::abs(dg - dc) > 1e-12f) ++distanceDiffer;
                else ++nearZero;
                worst = std::max(worst, std::abs(dg - dc));
            }
            if (ls.closestTriangle) closestDiffer += gpu.field.closest[a] != cpu.field.closest[b];
        }
    }
    EXPECT_EQ(maskDiffer, 0u) << "bricks whose band voxels differ";
    EXPECT_EQ(distanceDiffer, 0u) << "distances not bit-identical, worst by " << worst << " voxel";
    EXPECT_EQ(closestDiffer, 0u) << "closest triangles differ";
    WindingTies ties{localPositions(mesh, gpu.field.grid), &mesh};
    if (!ls.unsignedDistance)
        expectSameSigns(gpu.field.signs, cpu.field.signs, gpu.field.bricks, gpu.field.winding ? &ties : nullptr);
    std::cout << "[ cpu fields ] " << mesh.source << (ls.unsignedDistance ? " unsigned" : " signed") << ": "
              << gpu.field.distances.size() << " band voxels, " << gpu.field.bricks.size() << " bricks, "
              << cpu.stats.sign << "; " << ties.seen << " sign ties, " << nearZero
              << " distances under 1e-3 not bit-identical (by " << worst << " at most); gpu " << gpu.ms << " ms, cpu " << cpu.ms
              << " ms\n";
}

/// Both paths' solids agree voxel for voxel.
void expectSameSolid(gl::Device& device, const TriangleMesh& mesh, const GridSpec& grid, SignOptions sign = {})
{
    SCOPED_TRACE(mesh.source + " (solid)");
    VoxelizeSettings gpuSettings, cpuSettings;
    gpuSettings.backend = kGl;
    cpuSettings.backend = Backend::Cpu;
    VoxelizeStats gpuStats, cpuStats;
    const SolidBricks cpu = gl::solidBricks(device, mesh, grid, cpuSettings, sign, Checkpoint{}, cpuStats);
    SolidBricks gpu;
    try {
        gpu = gl::solidBricks(device, mesh, grid, gpuSettings, sign, Checkpoint{}, gpuStats);
    } catch (const DeviceError& e) {
        ASSERT_NE(std::string(e.what()).find("ends a shader's loops"), std::string::npos) << e.what();
        std::cout << "[ cpu fields ] " << mesh.source << " solid: the GPU path refused (" << e.what() << ")\n";
        EXPECT_FALSE(cpu.bricks.empty());
        return;
    }
    EXPECT_EQ(cpuStats.backend, "cpu");
    EXPECT_EQ(cpuStats.sign, gpuStats.sign);
    EXPECT_EQ(cpuStats.bandBricks, gpuStats.bandBricks);
    EXPECT_EQ(cpuStats.windingBricks, gpuStats.windingBricks);
    EXPECT_EQ(cpu.grid.anchor, gpu.grid.anchor);
    ASSERT_EQ(cpu.bricks, gpu.bricks);
    const bool winding = gpuStats.sign.rfind("winding", 0) == 0;
    WindingTies ties{localPositions(mesh, gpu.grid), &mesh};
    // The surface voxels differ by design: the GPU grows each voxel's cube
    // by its guard band (GridSpec::epsilon() / 2) against float rounding,
    // the CPU voxelizer is exact. A voxel only the GPU's solid has must be
    // one the CPU voxelizer finds with a guard of epsilon.
    const Voxelization guarded = voxelizeCpu(mesh, gpu.grid, gpu.grid.epsilon());
    uint64_t guardOnly = 0;
    const auto inGuard = [&](const BrickCoord& b, uint32_t v, bool gpuHasIt) {
        if (!gpuHasIt) return false;
        const uint64_t key = packVoxelKey(8 * b[0] + (v >> 6), 8 * b[1] + ((v >> 3) & 7), 8 * b[2] + (v & 7));
        const bool found = std::binary_search(guarded.keys.begin(), guarded.keys.end(), key);
        guardOnly += found;
        return found;
    };
    expectSameSigns(gpu.signs, cpu.signs, gpu.bricks, winding ? &ties : nullptr, inGuard);
    std::cout << "[ cpu fields ] " << mesh.source << " solid: " << gpu.bricks.size() << " band bricks, "
              << cpuStats.sign << "; " << ties.seen << " sign ties, " << guardOnly << " guard-band voxels\n";
}

/// `mesh` with the triangles whose first corner lies above z = `cut` left out
/// (a hole) and every seventh flipped: winding numbers that take every value.
TriangleMesh holedAndFlipped(TriangleMesh mesh, double cut)
{
    std::vector<std::array<uint32_t, 3>> kept;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        auto t = mesh.triangles[i];
        if (mesh.positions[t[0]].z > cut) continue;
        if (i % 7 == 0) std::swap(t[1], t[2]);
        kept.push_back(t);
    }
    mesh.triangles = kept;
    mesh.source += ", holed and flipped";
    return mesh;
}

TriangleMesh joined(TriangleMesh a, const TriangleMesh& b, const std::string& name)
{
    const auto base = uint32_t(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    for (auto t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    a.source = name;
    return a;
}

TriangleMesh named(TriangleMesh m, const std::string& name)
{
    m.source = name;
    return m;
}

/// The octahedron of test_level_set's tie test: vertices on voxel centres.
TriangleMesh octahedron()
{
    const int c = 8, r = 5;
    TriangleMesh o;
    o.source = "octahedron on voxel centres";
    o.positions = {{c + r, c, c}, {c - r, c, c}, {c, c + r, c}, {c, c - r, c}, {c, c, c + r}, {c, c, c - r}};
    for (uint32_t sx : {0u, 1u})
        for (uint32_t sy : {2u, 3u})
            for (uint32_t sz : {4u, 5u}) {
                const bool flip = ((sx == 1) + (sy == 3) + (sz == 5)) % 2 == 1;
                o.triangles.push_back(flip ? std::array<uint32_t, 3>{sx, sz, sy} : std::array<uint32_t, 3>{sx, sy, sz});
            }
    return o;
}

LevelSetOptions options(double exterior, double interior, SignMethod method = SignMethod::Auto,
                        bool closest = false, bool unsignedDistance = false)
{
    LevelSetOptions ls;
    ls.exteriorBand = exterior;
    ls.interiorBand = interior;
    ls.sign = method;
    ls.closestTriangle = closest;
    ls.unsignedDistance = unsignedDistance;
    return ls;
}

// Closed meshes: parity under auto, and winding as asked; closest triangles.
TEST(CpuFields, ClosedMeshLevelSetsAreTheGpusBitForBit)
{
    gl::Device device;
    const TriangleMesh ico3 = named(icosphere({0.1, -0.2, 0.3}, 1.0, 3), "icosphere 3");
    const TriangleMesh ico0 = named(icosphere({0.1, -0.2, 0.3}, 1.0, 0), "icosahedron");
    const TriangleMesh b = named(box({-1.3, 0.2, 0.7}, {0.4, 1.1, 2.9}), "box");
    expectSameLevelSet(device, ico3, makeGrid(ico3, GridRequest{40, 0}), options(3, 3, SignMethod::Auto, true));
    expectSameLevelSet(device, b, makeGrid(b, GridRequest{32, 0}), options(2, 4.5));
    expectSameLevelSet(device, ico0, makeGrid(ico0, GridRequest{96, 0}), options(3, 2.5, SignMethod::Auto, true));
    expectSameLevelSet(device, ico3, makeGrid(ico3, GridRequest{40, 0}), options(3, 3, SignMethod::Winding));
    expectSameLevelSet(device, b, makeGrid(b, GridRequest{32, 0}), options(2, 4.5, SignMethod::Winding));
    // Many small triangles (llvmpipe's loop-limit scene of test_level_set).
    const TriangleMesh ico7 = named(icosphere({0.1, -0.2, 0.3}, 1.0, 7), "icosphere 7");
    expectSameLevelSet(device, ico7, makeGrid(ico7, GridRequest{40, 0}), options(3, 3, SignMethod::Auto, true));
#ifdef SVO_CGAL_MESHES
    const TriangleMesh elephant = loadMesh(std::string(SVO_CGAL_MESHES) + "/elephant.off");
    expectSameLevelSet(device, elephant, makeGrid(elephant, GridRequest{48, 0}), options(3, 3, SignMethod::Auto, true));
    expectSameLevelSet(device, elephant, makeGrid(elephant, GridRequest{40, 0}), options(2, 2, SignMethod::Winding));
#endif
}

// Faces, edges and vertices on voxel centres and columns: the tie rules of
// distances (the smallest triangle index at equal distance) and of parity
// crossings; and the winding number exactly 1/2 on the faces.
TEST(CpuFields, TiesOnFacesEdgesAndVerticesAreTheGpus)
{
    gl::Device device;
    const TriangleMesh b = named(box({2, 3, 4}, {10, 9, 12}), "box on voxel centres");
    const TriangleMesh o = octahedron();
    for (const TriangleMesh* m : {&b, &o}) {
        const GridSpec grid = makeGrid(*m, GridRequest{0, 1.0});
        expectSameLevelSet(device, *m, grid, options(3, 3, SignMethod::Auto, true));
        expectSameLevelSet(device, *m, grid, options(3, 3, SignMethod::Winding, true));
        expectSameLevelSet(device, *m, grid, options(3, 3, SignMethod::Auto, true, true));
        expectSameSolid(device, *m, grid);
        expectSameSolid(device, *m, grid, SignOptions(SignMethod::Winding));
    }
}

// Open, flipped and overlapping meshes take winding numbers (auto): the same
// signs in the band and beyond it, including the bricks beyond the band
// classified voxel by voxel.
TEST(CpuFields, OpenMeshLevelSetsAreTheGpus)
{
    gl::Device device;
    const TriangleMesh closed = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    TriangleMesh holed = closed;
    holed.source = "holed sphere";
    holed.triangles.clear();
    for (const auto& t : closed.triangles) {
        const Vec3d c = (1.0 / 3) * (closed.positions[t[0]] + closed.positions[t[1]] + closed.positions[t[2]]);
        if (c.z < 0.3 + 0.95) holed.triangles.push_back(t);
    }
    const TriangleMesh two = joined(closed, icosphere({0.7, -0.2, 0.3}, 0.8, 3), "two spheres");
    const TriangleMesh messy = holedAndFlipped(joined(closed, icosphere({0.6, 0.1, 0.2}, 0.7, 3), "two spheres"), 0.6);
    TriangleMesh openBox = box({0, 0, 0}, {1, 1, 1});
    openBox.triangles.erase(openBox.triangles.begin() + 2, openBox.triangles.begin() + 4);
    openBox.source = "open box";
    for (const TriangleMesh* m : std::vector<const TriangleMesh*>{&holed, &two, &messy, &openBox}) {
        const GridSpec grid = makeGrid(*m, GridRequest{40, 0});
        expectSameLevelSet(device, *m, grid, options(3, 3, SignMethod::Auto, true));
        expectSameSolid(device, *m, grid);
    }
    // Every triangle exact (beta = infinity), as test_level_set's walks run too.
    LevelSetOptions exact = options(3, 3, SignMethod::Winding);
    exact.sign.windingAccuracy = 1e300;
    expectSameLevelSet(device, messy, makeGrid(messy, GridRequest{32, 0}), exact);
#ifdef SVO_CGAL_MESHES
    for (const char* name : {"cube-ouvert.off", "bunny00.off"}) {
        const TriangleMesh m = loadMesh(std::string(SVO_CGAL_MESHES) + "/" + name);
        const GridSpec grid = makeGrid(m, GridRequest{48, 0});
        expectSameLevelSet(device, m, grid, options(3, 3, SignMethod::Auto, true));
        expectSameSolid(device, m, grid);
    }
#endif
}

TEST(CpuFields, UnsignedFieldsAndClosestTrianglesAreTheGpus)
{
    gl::Device device;
    const TriangleMesh needles = boxAndNeedles();
    expectSameLevelSet(device, needles, makeGrid(needles, GridRequest{24, 0}), options(3, 3, SignMethod::Auto, true, true));
    expectSameLevelSet(device, needles, makeGrid(needles, GridRequest{24, 0}), options(7.5, 1, SignMethod::Auto, true, true));
#ifdef SVO_CGAL_MESHES
    const TriangleMesh elephant = loadMesh(std::string(SVO_CGAL_MESHES) + "/elephant.off");
    expectSameLevelSet(device, elephant, makeGrid(elephant, GridRequest{64, 0}), options(2, 2, SignMethod::Auto, true, true));
#endif
}

/// The voxels of a field nearer than @a band, per brick coordinate.
std::map<BrickCoord, Brick> nearerThan(const DistanceBricks& f, double band)
{
    std::map<BrickCoord, Brick> out;
    for (size_t i = 0; i < f.bricks.size(); ++i) {
        Brick in;
        for (uint32_t v = 0, k = 0; v < 512; ++v)
            if ((f.near[i].words[v >> 6] >> (v & 63)) & 1u)
                if (f.distances[f.offsets[i] + k++] < float(band)) in.words[v >> 6] |= uint64_t(1) << (v & 63);
        if (in.count()) out[f.bricks[i]] = in;
    }
    return out;
}

// A band's topology (gl::bandTopologyBricks) on the CPU and on the GPU's
// packed path: a voxel found nearer than the band takes no more triangles,
// so the distances need not be the least, but the voxels nearer than the
// band are the unsigned field's exactly (the CPU's full field the
// reference), and a distance was skipped somewhere on each.
TEST(CpuFields, ABandsTopologyIsTheUnsignedFieldsVoxels)
{
    gl::Device device;
    std::vector<TriangleMesh> meshes = {boxAndNeedles(), icosphere({0.1, -0.2, 0.3}, 1.0, 5)};
#ifdef SVO_CGAL_MESHES
    meshes.push_back(loadMesh(std::string(SVO_CGAL_MESHES) + "/elephant.off"));
#endif
    for (const TriangleMesh& m : meshes) {
        SCOPED_TRACE(m.source);
        const GridSpec grid = makeGrid(m, GridRequest{48, 0});
        const double band = 2.5;
        const auto full = levelSet(device, m, grid, options(band, band, SignMethod::Auto, false, true), Backend::Cpu);
        const auto want = nearerThan(full.field, band);
        ASSERT_GT(want.size(), 50u);
        for (const Backend backend : {Backend::Cpu, Backend::Compute}) {
            SCOPED_TRACE(backend == Backend::Cpu ? "cpu" : "compute");
            VoxelizeSettings settings;
            settings.backend = backend;
            VoxelizeStats stats;
            const DistanceBricks got = gl::bandTopologyBricks(device, m, grid, band, settings, Checkpoint{}, stats);
            EXPECT_TRUE(nearerThan(got, band) == want) << "the voxels nearer than the band differ from the field's";
            // Bricks in the same order on both (the band's brick list): some distance kept larger than the least.
            ASSERT_EQ(got.bricks, full.field.bricks);
            uint64_t larger = 0;
            for (size_t i = 0; i < got.bricks.size(); ++i)
                if (got.near[i] == full.field.near[i])
                    for (uint32_t k = 0, n = got.near[i].count(); k < n; ++k)
                        larger += got.distances[got.offsets[i] + k] > full.field.distances[full.field.offsets[i] + k];
            EXPECT_GT(larger, 0u) << "no distance was skipped";
        }
    }
}

TEST(CpuFields, SolidsAreTheGpus)
{
    gl::Device device;
    const TriangleMesh ico = named(icosphere({0.3, 0.1, -0.2}, 1.0, 3), "icosphere 3");
    const TriangleMesh b = named(box({-1.3, 0.2, 0.7}, {0.4, 1.1, 2.9}), "box");
    expectSameSolid(device, ico, makeGrid(ico, GridRequest{48, 0}));
    expectSameSolid(device, b, makeGrid(b, GridRequest{40, 0}));
    expectSameSolid(device, ico, makeGrid(ico, GridRequest{48, 0}), SignOptions(SignMethod::Winding));
    expectSameSolid(device, b, makeGrid(b, GridRequest{40, 0}), SignOptions(SignMethod::Winding));
    const TriangleMesh big = named(box({0, 0, 0}, {1, 1, 1}), "unit box");
    expectSameSolid(device, big, makeGrid(big, GridRequest{160, 0}));
    expectSameSolid(device, big, makeGrid(big, GridRequest{160, 0}), SignOptions(SignMethod::Winding));
#ifdef SVO_CGAL_MESHES
    const TriangleMesh elephant = loadMesh(std::string(SVO_CGAL_MESHES) + "/elephant.off");
    expectSameSolid(device, elephant, makeGrid(elephant, GridRequest{64, 0}));
    expectSameSolid(device, elephant, makeGrid(elephant, GridRequest{64, 0}), SignOptions(SignMethod::Winding));
#endif
}

// The stability scenes (degenerate, on the lattice, axis ties, sizes,
// placements, resolutions, topology): signed (auto) and unsigned level sets
// and solids. The two largest (1.3 million triangles; a grid 2 million
// voxels long) are left to test_stability: llvmpipe takes minutes on them.
TEST(CpuFields, StabilityScenesAreTheGpus)
{
    gl::Device device;
    for (const Scene& s : stabilityScenes()) {
        if (s.group == "scale" || s.group == "grid size") continue;
        SCOPED_TRACE(s.group + ": " + s.name);
        const TriangleMesh mesh = named(s.mesh, s.name);
        const GridSpec grid = makeGrid(mesh, s.grid);
        expectSameLevelSet(device, mesh, grid, options(3, 3, SignMethod::Auto, true, true));
        expectSameLevelSet(device, mesh, grid, options(2, 3, SignMethod::Auto, true));
        expectSameSolid(device, mesh, grid);
    }
}

/// The CPU's climb up the columns (windingInsideAlongColumns) gives every
/// centre of `bricks` the side the walk at every centre (windingInside)
/// gives it, but for WindingTies (a centre on the surface, where the climb
/// takes the crossings' side of it and the walk either); returns the centres walked.
uint64_t expectClimbIsTheWalk(const TriangleMesh& mesh, const GridSpec& grid, double beta,
                              std::vector<BrickCoord> bricks = {})
{
    const std::vector<Vec3d> local = localPositions(mesh, grid);
    const bool searched = bricks.empty(); // the whole grid searched: a brick not listed holds no triangle
    if (searched) bricks = bricksNearTriangles(local, mesh, grid, 3.0);
    const WindingTree tree = buildWindingTree(local, mesh.triangles);
    const std::vector<Brick> walked = windingInside(tree, bricks, beta, Checkpoint{});
    const WindingColumns columns = windingColumns(local, mesh, grid, bricks);
    uint64_t centres = 0;
    const std::vector<Brick> climbed = windingInsideAlongColumns(tree, bricks, columns, beta, Checkpoint{}, &centres);
    FieldSigns a, b;
    a.inside = walked, b.inside = climbed;
    WindingTies ties{local, &mesh};
    expectSameSigns(a, b, bricks, &ties);
    // The brick centres of the grid's box: the same class (bricksBeyondBand's)
    // climbed as walked, but on the surface.
    const std::vector<float> everyCentre = windingAtBrickCentres(tree, grid, beta, Checkpoint{});
    const BrickCentreColumns centreColumns = brickCentreColumns(local, mesh, grid);
    uint64_t centresWalked = 0;
    std::vector<float> doubts;
    const std::vector<float> climbedCentres =
        windingAtBrickCentres(tree, grid, beta, Checkpoint{}, &centreColumns, &centresWalked, &doubts);
    // Runs entered from the brick below (its centre's number, doubt and
    // gradient bound) in place of their lowest layer's walks: the same sides.
    uint64_t anchoredWalks = 0;
    if (searched) {
        ClimbAnchors anchors{&centreColumns, &climbedCentres, &doubts};
        for (int axis = 0; axis < 3; ++axis) anchors.hi[axis] = grid.dims[axis] / 8;
        FieldSigns c;
        c.inside = windingInsideAlongColumns(tree, bricks, columns, beta, Checkpoint{}, &anchoredWalks, &anchors);
        expectSameSigns(a, c, bricks, &ties);
        EXPECT_LE(anchoredWalks, centres);
    }
    EXPECT_LE(centresWalked, everyCentre.size());
    const auto classOf = [](float w) { return std::abs(w - 0.5f) < kWindingMargin ? 1 : w >= 0.5f ? 2 : 0; };
    const auto& d = centreColumns.dims;
    uint64_t centreTies = 0;
    for (uint64_t g = 0; g < everyCentre.size(); ++g) {
        if (classOf(everyCentre[g]) == classOf(climbedCentres[g])) continue;
        const Vec3d q{8.0 * double(g % d[0]) + 3.5, 8.0 * double(g / d[0] % d[1]) + 3.5, 8.0 * double(g / (uint64_t(d[0]) * d[1])) + 3.5};
        if (ties.surfaceDistance(q) < 1e-6) {
            ++centreTies;
            continue;
        }
        ADD_FAILURE() << "brick centre " << q.x << ", " << q.y << ", " << q.z << ": walked " << everyCentre[g]
                      << ", climbed " << climbedCentres[g];
    }
    std::cout << "[ cpu fields ] " << mesh.source << ", beta " << beta << ": climbed " << bricks.size() * 512
              << " centres, walked " << centres << " (entered from below: " << anchoredWalks << "), " << ties.seen
              << " differ on the surface; brick centres "
              << everyCentre.size() << ", walked " << centresWalked << ", " << centreTies << " differ on the surface\n";
    return centres;
}

// Winding signs on the CPU climb each column of a run of bricks from its
// lowest centres (walked, or entered from the brick below) by the signed
// crossings and a bound on the boundary's field, and walk only where that
// does not decide: the same
// sides as a walk at every centre, on open, flipped, overlapping, welded
// and unwelded meshes, sheets, ties on voxel centres, a brick list out of
// order with gaps, and at several accuracies (beta 1: nothing decided by a
// climb, every centre walked).
TEST(CpuFields, ClimbingColumnsGivesTheWalksSides)
{
    const TriangleMesh closed = named(icosphere({0.1, -0.2, 0.3}, 1.0, 3), "icosphere 3");
    const TriangleMesh two = joined(closed, icosphere({0.7, -0.2, 0.3}, 0.8, 3), "two spheres");
    const TriangleMesh messy = holedAndFlipped(two, 0.6);
    TriangleMesh openBox = box({0, 0, 0}, {1, 1, 1});
    openBox.triangles.erase(openBox.triangles.begin() + 2, openBox.triangles.begin() + 4);
    openBox.source = "open box";
    TriangleMesh sheet;
    sheet.source = "a tilted square sheet";
    sheet.positions = {{0, 0, 0}, {1, 0, 0.3}, {1, 1, 0.5}, {0, 1, 0.2}};
    sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
    for (const TriangleMesh* m : std::vector<const TriangleMesh*>{&closed, &two, &messy, &openBox, &sheet}) {
        SCOPED_TRACE(m->source);
        const GridSpec grid = makeGrid(*m, GridRequest{48, 0});
        const uint64_t walked = expectClimbIsTheWalk(*m, grid, 1.5);
        // A closed mesh has no boundary: its columns climb by crossings alone.
        if (m == &closed || m == &two) {
            EXPECT_LT(walked, bricksNearTriangles(localPositions(*m, grid), *m, grid, 3.0).size() * 512 / 4);
        }
    }
    {
        // A cup (a sphere open at the bottom): above the opening, runs enter
        // from bricks whose number changes fast near the rim, so the
        // gradient's bound matters there.
        TriangleMesh cup = icosphere({0.1, -0.2, 0.3}, 1.0, 4);
        cup.triangles.erase(std::remove_if(cup.triangles.begin(), cup.triangles.end(),
                                           [&](const auto& t) { return cup.positions[t[0]].z < 0.3 - 0.4; }),
                            cup.triangles.end());
        cup.source = "cup";
        for (uint32_t n : {96u, 128u}) expectClimbIsTheWalk(cup, makeGrid(cup, GridRequest{n, 0}), 1.5);
    }
    expectClimbIsTheWalk(asSoup(messy), makeGrid(messy, GridRequest{40, 0}), 1.5);
    expectClimbIsTheWalk(messy, makeGrid(messy, GridRequest{40, 0}), 3.0);
    expectClimbIsTheWalk(messy, makeGrid(messy, GridRequest{40, 0}), 1e300);
    EXPECT_EQ(expectClimbIsTheWalk(messy, makeGrid(messy, GridRequest{32, 0}), 1.0),
              bricksNearTriangles(localPositions(messy, makeGrid(messy, GridRequest{32, 0})), messy,
                                  makeGrid(messy, GridRequest{32, 0}), 3.0).size() * 512);
    {
        // Out of order, every third brick left out: runs start past each gap.
        const GridSpec grid = makeGrid(messy, GridRequest{48, 0});
        std::vector<BrickCoord> bricks = bricksNearTriangles(localPositions(messy, grid), messy, grid, 3.0), some;
        for (size_t i = 0; i < bricks.size(); ++i)
            if (i % 3) some.push_back(bricks[i]);
        std::reverse(some.begin(), some.end());
        expectClimbIsTheWalk(messy, grid, 1.5, some);
    }
    expectClimbIsTheWalk(octahedron(), makeGrid(octahedron(), GridRequest{16, 0}), 1.5);
    for (const Scene& s : stabilityScenes()) {
        if (s.group == "scale" || s.group == "grid size") continue;
        SCOPED_TRACE(s.group + ": " + s.name);
        expectClimbIsTheWalk(named(s.mesh, s.name), makeGrid(s.mesh, s.grid), 1.5);
    }
#ifdef SVO_CGAL_MESHES
    for (const char* name : {"cube-ouvert.off", "bunny00.off", "elephant.off"}) {
        const TriangleMesh m = loadMesh(std::string(SVO_CGAL_MESHES) + "/" + name);
        expectClimbIsTheWalk(m, makeGrid(m, GridRequest{64, 0}), 1.5);
    }
#endif
}

/// The exact winding number at p (double, every triangle's solid angle by
/// Van Oosterom and Strackee's formula): the reference for the bounds.
double exactWinding(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const Vec3d& p)
{
    double sum = 0;
    for (const auto& t : mesh.triangles) {
        const Vec3d a = local[t[0]] - p, b = local[t[1]] - p, c = local[t[2]] - p;
        const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
        const double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
        sum += 2.0 * std::atan2(dot(a, cross(b, c)), den);
    }
    return sum / (4.0 * M_PI);
}

// BrickCentreColumns::gradientAt bounds how far the winding number moves
// over a brick's box that holds no triangle (one beyond a band of a voxel):
// from the centre to each top centre of its columns, which is what a run
// entered from that brick relies on; on open meshes, against the exact
// number, and 0 for a closed mesh.
TEST(CpuFields, GradientBoundHoldsOverBricksBeyondTheBand)
{
    TriangleMesh cup = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    cup.triangles.erase(std::remove_if(cup.triangles.begin(), cup.triangles.end(),
                                       [&](const auto& t) { return cup.positions[t[0]].z < 0.3 - 0.4; }),
                        cup.triangles.end());
    TriangleMesh sheet;
    sheet.positions = {{0, 0, 0}, {1, 0, 0.3}, {1, 1, 0.5}, {0, 1, 0.2}};
    sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
    const TriangleMesh closed = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    for (const TriangleMesh* m : std::vector<const TriangleMesh*>{&cup, &sheet, &closed}) {
        const GridSpec grid = makeGrid(*m, GridRequest{64, 0});
        const std::vector<Vec3d> local = localPositions(*m, grid);
        const std::vector<BrickCoord> band = bricksNearTriangles(local, *m, grid, 1.0);
        const BrickCentreColumns columns = brickCentreColumns(local, *m, grid);
        const auto& d = columns.dims;
        double worst = 0; // the largest move found, as a share of its bound
        uint64_t checked = 0;
        for (uint32_t z = 0; z < grid.dims[2] / 8; ++z)
            for (uint32_t y = 0; y < grid.dims[1] / 8; ++y)
                for (uint32_t x = 0; x < grid.dims[0] / 8; ++x) {
                    if (std::binary_search(band.begin(), band.end(), BrickCoord{x, y, z})) continue;
                    const float bound = columns.gradientAt(x + uint64_t(d[0]) * (y + uint64_t(d[1]) * z));
                    if (m == &closed) {
                        EXPECT_EQ(bound, 0.0f);
                    }
                    if (!std::isfinite(bound)) continue;
                    const Vec3d c{8.0 * x + 3.5, 8.0 * y + 3.5, 8.0 * z + 3.5};
                    const double wc = exactWinding(local, *m, c);
                    for (const Vec3d& top : {Vec3d{8.0 * x, 8.0 * y, 8.0 * z + 7}, Vec3d{8.0 * x + 7, 8.0 * y + 7, 8.0 * z + 7},
                                             Vec3d{8.0 * x + 7, 8.0 * y, 8.0 * z + 7}, Vec3d{8.0 * x + 3, 8.0 * y + 4, 8.0 * z + 7}}) {
                        const double moved = std::abs(exactWinding(local, *m, top) - wc);
                        const double allowed = double(bound) * std::sqrt(dot(top - c, top - c));
                        EXPECT_LE(moved, allowed + 1e-9) << "brick " << x << ", " << y << ", " << z;
                        if (allowed > 0) worst = std::max(worst, moved / allowed);
                        ++checked;
                    }
                }
        std::cout << "[ cpu fields ] gradient bound: " << checked << " moves checked, the largest " << worst
                  << " of its bound\n";
        EXPECT_GT(checked, 100u);
        if (m != &closed) {
            EXPECT_GT(worst, 0.01); // the bound is not vacuous
        }
    }
}

// The CPU path makes no GL context, polls the checkpoint with the fraction
// done (rising to the end of its part), and stops with svo::Interrupted.
/// Whether @a stats ran a stage named @a name.
bool ranStage(const VoxelizeStats& stats, const std::string& name)
{
    return std::any_of(stats.stages.begin(), stats.stages.end(), [&](const StageTime& s) { return s.name == name; });
}

/// WindingTreeCache's key is its whole input, bit for bit: the same input
/// gets the kept tree (the same object, the nodes buildWindingTree gives);
/// a coordinate's zero turned negative, another triangle order and clear()
/// each build again.
TEST(CpuFields, WindingTreeCacheKeysOnTheWholeInput)
{
    const TriangleMesh ico = icosphere({0.0, 0.5, -0.25}, 1.0, 2);
    std::vector<Vec3d> positions = ico.positions;
    positions[0] = {0.0, positions[0][1], positions[0][2]};
    WindingTreeCache cache;
    bool built = false;
    const WindingTree* first = &cache.treeFor(positions, ico.triangles, &built);
    EXPECT_TRUE(built);
    const WindingTree fresh = buildWindingTree(positions, ico.triangles);
    ASSERT_EQ(first->nodes.size(), fresh.nodes.size());
    EXPECT_EQ(0, std::memcmp(first->nodes.data(), fresh.nodes.data(), 4 * fresh.nodes.size()));
    EXPECT_EQ(first->links, fresh.links);
    EXPECT_EQ(first->order, fresh.order);
    EXPECT_EQ(&cache.treeFor(positions, ico.triangles, &built), first);
    EXPECT_FALSE(built);
    positions[0][0] = -0.0; // equal as a number
    (void)cache.treeFor(positions, ico.triangles, &built);
    EXPECT_TRUE(built);
    std::vector<std::array<uint32_t, 3>> turned = ico.triangles;
    std::swap(turned[0][1], turned[0][2]);
    (void)cache.treeFor(positions, turned, &built);
    EXPECT_TRUE(built);
    (void)cache.treeFor(positions, turned, &built);
    EXPECT_FALSE(built);
    cache.clear();
    (void)cache.treeFor(positions, turned, &built);
    EXPECT_TRUE(built);
}

/// The device keeps the last winding tree (svo/core/winding_tree_cache.h):
/// a call over the same triangles in the same frame (another region of the
/// same grid, or a solid of it) walks the kept tree, and its signs are a
/// fresh device's bit for bit; a moved vertex and releaseScratch() each
/// build it again.
TEST(CpuFields, RegionsOfOneGridShareTheWindingTree)
{
    TriangleMesh open = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    std::vector<std::array<uint32_t, 3>> kept;
    for (const auto& t : open.triangles)
        if (open.positions[t[0]][2] + open.positions[t[1]][2] + open.positions[t[2]][2] < 3 * (0.3 + 0.5)) kept.push_back(t);
    open.triangles = std::move(kept); // a hole: winding numbers
    const GridSpec grid = makeGrid(open, GridRequest{48, 0});
    for (const Backend backend : {Backend::Cpu, kGl}) {
        SCOPED_TRACE(backend == Backend::Cpu ? "cpu" : "gl");
        gl::Device device;
        VoxelizeSettings settings;
        settings.backend = backend;
        const LevelSetOptions ls = options(3, 3, SignMethod::Winding);
        VoxelizeStats first, second, third;
        settings.region = IndexBox{{grid.anchor[0] - 16, grid.anchor[1] - 16, grid.anchor[2] - 16},
                                   {grid.anchor[0] + 24, grid.anchor[1] + 64, grid.anchor[2] + 64}};
        (void)gl::levelSetBricks(device, open, grid, ls, settings, Checkpoint{}, first);
        EXPECT_TRUE(ranStage(first, "winding tree"));
        settings.region->lo[0] += 40, settings.region->hi[0] += 40; // the next region along x
        const DistanceBricks kept2 = gl::levelSetBricks(device, open, grid, ls, settings, Checkpoint{}, second);
        EXPECT_TRUE(ranStage(second, "winding tree (kept)"));
        EXPECT_FALSE(ranStage(second, "winding tree"));
        gl::Device fresh;
        VoxelizeStats freshStats;
        const DistanceBricks built = gl::levelSetBricks(fresh, open, grid, ls, settings, Checkpoint{}, freshStats);
        ASSERT_EQ(kept2.bricks, built.bricks);
        ASSERT_GT(kept2.signs.inside.size(), 10u);
        EXPECT_EQ(0, std::memcmp(kept2.signs.inside.data(), built.signs.inside.data(), sizeof(Brick) * built.signs.inside.size()));
        EXPECT_EQ(kept2.signs.insideBricks, built.signs.insideBricks);
        // A solid of the same mesh and grid: the same local frame, the same tree.
        VoxelizeStats solidStats;
        (void)gl::solidBricks(device, open, grid, settings, SignOptions(SignMethod::Winding), Checkpoint{}, solidStats);
        EXPECT_TRUE(ranStage(solidStats, "winding tree (kept)"));
        // One vertex moved: another key.
        TriangleMesh moved = open;
        moved.positions[open.triangles[0][0]][0] += 1e-3;
        (void)gl::levelSetBricks(device, moved, grid, ls, settings, Checkpoint{}, third);
        EXPECT_TRUE(ranStage(third, "winding tree"));
        device.releaseScratch();
        VoxelizeStats fourth;
        (void)gl::levelSetBricks(device, moved, grid, ls, settings, Checkpoint{}, fourth);
        EXPECT_TRUE(ranStage(fourth, "winding tree"));
    }
}

TEST(CpuFields, NoContextProgressAndInterrupts)
{
    gl::Device device;
    const TriangleMesh ico = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    const GridSpec grid = makeGrid(ico, GridRequest{48, 0});
    VoxelizeSettings cpu;
    cpu.backend = Backend::Cpu;
    for (const SignMethod method : {SignMethod::Parity, SignMethod::Winding}) {
        std::vector<int> seen;
        const Checkpoint progress([&](int percent) {
            seen.push_back(percent);
            return false;
        });
        VoxelizeStats stats;
        const DistanceBricks f = gl::levelSetBricks(device, ico, grid, options(3, 3, method), cpu, progress, stats);
        EXPECT_FALSE(f.bricks.empty());
        ASSERT_GT(seen.size(), 3u);
        EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
        EXPECT_GE(seen.back(), 80);
        const Checkpoint stop([](int percent) { return percent >= 40; });
        VoxelizeStats stopped;
        EXPECT_THROW((void)gl::levelSetBricks(device, ico, grid, options(3, 3, method), cpu, stop, stopped),
                     Interrupted);
        VoxelizeStats solidStats;
        EXPECT_THROW((void)gl::solidBricks(device, ico, grid, cpu, SignOptions(method), stop, solidStats), Interrupted);
        std::vector<std::string> stages;
        for (const auto& st : stats.stages) stages.push_back(st.name);
        std::cout << "[ cpu fields ] stages:";
        for (const auto& n : stages) std::cout << " \"" << n << "\"";
        std::cout << "\n";
        EXPECT_NE(std::find(stages.begin(), stages.end(), "band distance (cpu)"), stages.end());
    }
    VoxelizeStats solidStats;
    (void)gl::solidBricks(device, ico, grid, cpu, {}, Checkpoint{}, solidStats);
    EXPECT_FALSE(device.started()) << "the CPU backend made a GL context";
}

// Through the public API: Voxelizer::levelSet and ::solid with Backend::Cpu
// give the GL passes' grids, value for value.
TEST(CpuFields, PublicApiGridsAreTheGlPassesGrids)
{
    Voxelizer v;
    const TriangleMesh ico = icosphere({0.1, -0.2, 0.3}, 1.0, 3);
    const GridSpec grid = makeGrid(ico, GridRequest{40, 0});
    VoxelizeOptions cpu;
    cpu.backend = Backend::Cpu;
    LevelSetOptions ls = options(3, 3, SignMethod::Auto, true);
    const auto a = v.levelSet(ico, grid, ls, onGl());
    const auto b = v.levelSet(ico, grid, ls, cpu);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i]->activeVoxelCount(), b[i]->activeVoxelCount());
        EXPECT_EQ(a[i]->getName(), b[i]->getName());
    }
    const auto fa = openvdb::gridPtrCast<openvdb::FloatGrid>(a.front());
    const auto fb = openvdb::gridPtrCast<openvdb::FloatGrid>(b.front());
    const auto acc = fb->getConstAccessor();
    uint64_t differ = 0;
    for (auto it = fa->cbeginValueAll(); it; ++it)
        if (it.isVoxelValue()) differ += acc.getValue(it.getCoord()) != *it || acc.isValueOn(it.getCoord()) != it.isValueOn();
    EXPECT_EQ(differ, 0u);
    EXPECT_TRUE(fa->tree().hasSameTopology(fb->tree()));
    const auto sa = v.solid(ico, grid, onGl());
    const auto sb = v.solid(ico, grid, cpu);
    EXPECT_EQ(sa->activeVoxelCount(), sb->activeVoxelCount());
    EXPECT_TRUE(sa->tree().hasSameTopology(sb->tree()));
}

} // namespace
} // namespace svo::test
