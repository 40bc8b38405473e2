// Light injection and the lighting volume (svo/gl/octree_view.h,
// Illumination; design §7d) against values computed on the CPU from the
// voxel set alone: the radiance injected into a lit plane (directional and
// point lights, and the shadow of an occluder from the voxels above each
// one), the anisotropic mip-map and the six-way radiance of random octrees
// level by level, and lit
// pictures: deterministic, and one diffuse bounce only adds light.
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/grid.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_key.h"
#include "svo/gl/context.h"
#include "svo/gl/octree_view.h"
#include "svo/voxelizer.h"

namespace {

using svo::Vec3d;
using svo::gl::Illumination;
using svo::gl::LightVolume;
using svo::gl::LightVolumeLevel;
using Voxel = std::array<uint32_t, 3>;

svo::gl::Context& context()
{
    static svo::gl::Context c;
    return c;
}

svo::GridSpec unitGrid(uint32_t x, uint32_t y, uint32_t z)
{
    svo::GridSpec g;
    g.voxelSize = 1.0;
    g.dims = {x, y, z};
    return g;
}

/// An octree of `voxels` whose normal channel is `normal` at every voxel.
svo::Octree octreeOf(const svo::GridSpec& grid, const std::vector<Voxel>& voxels, const std::vector<svo::Vec3f>& normals)
{
    std::vector<uint64_t> keys;
    for (const Voxel& v : voxels) keys.push_back(svo::packVoxelKey(v[0], v[1], v[2]));
    svo::Octree o = svo::buildOctree(grid, keys);
    o.attributes.normals = normals;
    o.attributes.normals.resize(o.voxelCount(), normals.empty() ? svo::Vec3f{0, 1, 0} : normals.back());
    return o;
}

/// `mesh` voxelized on the GPU at `resolution` with its normal channel, as
/// `svo view` does (lit modes need the normals).
svo::Octree voxelizedWithNormals(const svo::TriangleMesh& mesh, int resolution)
{
    svo::VoxelizeOptions options;
    options.attributes = svo::kNormals;
    return svo::Voxelizer().voxelize(mesh, svo::makeGrid(mesh, svo::GridRequest{resolution, 0}), options);
}

size_t texel(const LightVolumeLevel& l, int x, int y, int z)
{
    return 4 * ((size_t(z) * size_t(l.size[1]) + size_t(y)) * size_t(l.size[0]) + size_t(x));
}

double halfTolerance(double v) { return 2e-3 * std::abs(v) + 1e-4; } // rgba16f: 11 significant bits

/// The two rooms (svo::twoRooms) as svo-bench-ao sees them: from inside the
/// dark room, looking at the wall, with a point light in the other room.
svo::gl::ViewCamera darkRoomCamera()
{
    svo::gl::ViewCamera camera;
    camera.eye = {0.9, 0.7, 0.9};
    camera.target = {0.0, 0.35, -0.3};
    camera.fovYDegrees = 70;
    return camera;
}
svo::gl::ViewLayers twoRoomsLit(Illumination::Mode mode)
{
    svo::gl::ViewLayers layers;
    layers.outlines = false;
    layers.light.mode = mode;
    layers.light.lights.point.push_back({{-0.5, 0.8, 0.0}, {M_PI, M_PI, M_PI}});
    layers.light.gamma = 1.0;
    return layers;
}

} // namespace

TEST(Lighting, InjectionIntoALitPlaneIsTheRadianceComputedOnTheCpu)
{
    // A plane of voxels at y = 4 across a 32³ grid, normal +y, and above part
    // of it an occluder at y = 20 over x, z in [8, 16).
    const svo::GridSpec grid = unitGrid(32, 32, 32);
    std::vector<Voxel> voxels;
    std::set<std::pair<uint32_t, uint32_t>> occluded;
    for (uint32_t x = 0; x < 32; ++x)
        for (uint32_t z = 0; z < 32; ++z) voxels.push_back({x, 4, z});
    for (uint32_t x = 8; x < 16; ++x)
        for (uint32_t z = 8; z < 16; ++z) {
            voxels.push_back({x, 20, z});
            occluded.insert({x, z});
        }
    const svo::Octree octree = octreeOf(grid, voxels, {{0, 1, 0}});
    svo::gl::OctreeView view(context(), octree);

    const Vec3d albedo{0.5, 0.6, 0.7};
    // A sun straight down: the occluder's shadow is exactly the columns under it.
    Illumination sun;
    sun.mode = Illumination::Mode::Direct;
    sun.albedo = albedo;
    sun.directional = true; // the lit side is checked below
    sun.lights.directional.push_back({{0, -2, 0}, {2.0, 1.0, 0.5}});
    // A point light off to the side, above the plane: radiance falls off as cos / r².
    Illumination point = sun;
    point.lights.directional.clear();
    point.lights.point.push_back({{40.0, 12.0, 16.0}, {300.0, 200.0, 100.0}});

    for (const Illumination* light : {&sun, &point}) {
        const LightVolume volume = view.readLightVolume(*light);
        ASSERT_EQ(volume.texelVoxels, 1u);
        ASSERT_EQ(volume.levels.size(), 6u); // 32³ down to 1³
        const LightVolumeLevel& l0 = volume.levels[0];
        ASSERT_EQ(l0.size[0], 32);
        int lit = 0, dark = 0;
        for (int z = 0; z < 32; ++z)
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x) {
                    const size_t i = texel(l0, x, y, z);
                    const bool plane = y == 4, top = y == 20 && x >= 8 && x < 16 && z >= 8 && z < 16;
                    const double cover = plane || top ? 1.0 : 0.0;
                    // Six-way volumes keep optical depth, at most that of opacity 0.999.
                    ASSERT_NEAR(l0.opacity[i], cover, 1.01e-3) << x << "," << y << "," << z;
                    ASSERT_EQ(l0.opacity[i + 3], cover);
                    ASSERT_EQ(l0.radiance[i + 3], cover);
                    Vec3d expected{0, 0, 0};
                    if (plane || top) {
                        if (light == &sun) {
                            // cos = 1; a plane voxel under the occluder sees none of the sun.
                            const bool shadow = plane && occluded.count({uint32_t(x), uint32_t(z)});
                            if (!shadow) expected = {albedo.x / M_PI * 2.0, albedo.y / M_PI * 1.0, albedo.z / M_PI * 0.5};
                        } else {
                            // The light at (40, 12, 16) is above the plane (y = 4) and
                            // level with nothing between: no shadow on the plane beyond
                            // the occluder's reach; the test looks at the plane only.
                            const Vec3d c{double(x), double(y), double(z)}; // world = local voxel centre
                            const Vec3d to = light->lights.point[0].position - c;
                            const double r2 = svo::dot(to, to), cosTheta = std::abs(to.y) / std::sqrt(r2);
                            const Vec3d& i0 = light->lights.point[0].intensity;
                            expected = {albedo.x / M_PI * i0.x * cosTheta / r2, albedo.y / M_PI * i0.y * cosTheta / r2,
                                        albedo.z / M_PI * i0.z * cosTheta / r2};
                            if (!plane) continue; // the occluder's own lighting is not checked here
                            // The occluder's shadow from the side: skip plane voxels whose
                            // ray to the light passes under it (x in [8, 16) region, far side).
                            if (x < 16 && z >= 6 && z < 18) continue;
                        }
                    }
                    const double got[3] = {l0.radiance[i], l0.radiance[i + 1], l0.radiance[i + 2]};
                    const double want[3] = {expected.x, expected.y, expected.z};
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(got[c], want[c], halfTolerance(want[c])) << x << "," << y << "," << z;
                    if (light == &sun) { // lit from above: the lit side is +y, stored times the texel's light
                        const double light = (want[0] + want[1] + want[2]) / 3;
                        for (int c = 0; c < 3; ++c)
                            ASSERT_NEAR(l0.litSide[i + size_t(c)], c == 1 ? light : 0.0, halfTolerance(light));
                    }
                    if (plane) (expected.x > 0 ? lit : dark) += 1;
                }
        if (light == &sun) {
            EXPECT_EQ(dark, 64); // the occluder's 8 x 8 shadow
            EXPECT_EQ(lit, 32 * 32 - 64);
        }

        // The picture's direct light (Illumination::Direct, linear) is each
        // visible voxel's injected irradiance on the side the camera sees,
        // times ρ/π: from above, the volume's radiance of the plane, or of the
        // occluder's top where the light is above it (the sun; the point
        // light at y = 12 lights only its underside); from below, nothing.
        svo::gl::ViewLayers layers;
        layers.outlines = false;
        layers.light = *light;
        layers.light.gamma = 1.0;
        for (const double side : {1.0, -1.0}) {
            svo::gl::ViewCamera camera; // one pixel a voxel, pixel centres on voxel centres
            camera.orthographic = true;
            camera.target = {15.5, 10.0, 15.5};
            camera.eye = camera.target + Vec3d{0, 100.0 * side, 0};
            camera.up = {0, 0, -side};
            camera.height = 32;
            const svo::gl::Image picture = view.render(camera, 32, 32, layers);
            for (int row = 0; row < 32; ++row)
                for (int col = 0; col < 32; ++col) {
                    const uint8_t* px = picture.pixel(col, row);
                    if (side < 0) {
                        for (int c = 0; c < 3; ++c) ASSERT_EQ(px[c], 0) << "from below " << col << "," << row;
                        continue;
                    }
                    const int x = col, z = row;
                    const int y = x >= 8 && x < 16 && z >= 8 && z < 16 ? 20 : 4;
                    const size_t i = texel(l0, x, y, z);
                    const bool facesLight = y == 4 || light == &sun;
                    // 1/255: GL converts a colour to 8 bits as either of the two
                    // nearest values (GL 4.5, 2.3.5.2): on the H100, 0.54 of a step came out as 0.
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(px[c] / 255.0, facesLight ? std::min(1.0, double(l0.radiance[i + size_t(c)])) : 0.0,
                                    1.0 / 255 + halfTolerance(l0.radiance[i + size_t(c)]))
                            << "from above " << col << "," << row << " channel " << c;
                }
        }
    }
}

/// A surface two voxels deep (a slab at x = 16 and 17, normal +x, as a
/// tilted surface's conservative voxels lie) lit by a sun travelling along
/// -x: only the layer on the light's side shows it. The layer behind (x =
/// 16) reaches the sun only through its push along the normal, which enters
/// the lit layer, so it is left out of the volume's radiance (its texels
/// dark) but still occludes; the picture's direct light of both layers'
/// front is the sun's.
TEST(Lighting, VoxelsBehindTheirOwnSurfaceAreNotLit)
{
    const svo::GridSpec grid = unitGrid(32, 32, 32);
    std::vector<Voxel> voxels;
    for (uint32_t x = 16; x < 18; ++x)
        for (uint32_t y = 0; y < 32; ++y)
            for (uint32_t z = 0; z < 32; ++z) voxels.push_back({x, y, z});
    const svo::Octree octree = octreeOf(grid, voxels, {{1, 0, 0}});
    svo::gl::OctreeView view(context(), octree);
    Illumination sun;
    sun.mode = Illumination::Mode::Direct;
    sun.albedo = {0.5, 0.6, 0.7};
    sun.lights.directional.push_back({{-1, 0, 0}, {2.0, 1.0, 0.5}});
    const LightVolume volume = view.readLightVolume(sun);
    ASSERT_EQ(volume.texelVoxels, 1u);
    const LightVolumeLevel& l0 = volume.levels[0];
    const double lit[3] = {0.5 / M_PI * 2.0, 0.6 / M_PI * 1.0, 0.7 / M_PI * 0.5};
    for (int y = 0; y < 32; ++y)
        for (int z = 0; z < 32; ++z)
            for (int x = 16; x < 18; ++x) {
                const size_t i = texel(l0, x, y, z);
                ASSERT_NEAR(l0.opacity[i + 3], 1.0, 1e-3) << x << "," << y << "," << z; // both occlude
                for (int c = 0; c < 3; ++c) {
                    const double want = x == 17 ? lit[c] : 0.0;
                    ASSERT_NEAR(l0.radiance[i + size_t(c)], want, halfTolerance(want)) << x << "," << y << "," << z;
                }
            }
    // Texels of 2³ voxels hold both layers: the texel's radiance is the mean
    // over the voxels that show a side (the lit layer's), not over all 8.
    sun.volumeResolution = 16;
    const LightVolume coarse = view.readLightVolume(sun);
    ASSERT_EQ(coarse.texelVoxels, 2u);
    const LightVolumeLevel& c0 = coarse.levels[0];
    for (int y = 0; y < 16; ++y)
        for (int z = 0; z < 16; ++z) {
            const size_t i = texel(c0, 8, y, z);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(c0.radiance[i + size_t(c)], lit[c], halfTolerance(lit[c])) << y << "," << z;
        }
}

TEST(Lighting, MipMapKeepsRadianceAndOpacityAsTheFilterSays)
{
    // Random voxels with random normals in grids of several shapes (one flat,
    // so an axis reaches one texel before the others), lit by a sun and a
    // point light. Each level must be the filter of the level below as read
    // back: radiance and coverage the mean of the children, opacity along an
    // axis the mean over columns of 1 - Π(1 - a) along it.
    std::mt19937 rng(7);
    for (const auto& dims : std::vector<std::array<uint32_t, 3>>{{32, 32, 32}, {64, 8, 32}, {24, 40, 16}}) {
        const svo::GridSpec grid = unitGrid(dims[0], dims[1], dims[2]);
        std::vector<Voxel> voxels;
        std::uniform_int_distribution<uint32_t> x(0, dims[0] - 1), y(0, dims[1] - 1), z(0, dims[2] - 1);
        for (int i = 0; i < 3000; ++i) voxels.push_back({x(rng), y(rng), z(rng)});
        std::normal_distribution<float> g;
        std::vector<svo::Vec3f> normals;
        for (int i = 0; i < 3000; ++i) normals.push_back({g(rng), g(rng), g(rng)});
        svo::Octree octree = octreeOf(grid, voxels, {});
        normals.resize(octree.voxelCount());
        octree.attributes.normals = normals;
        svo::gl::OctreeView view(context(), octree);
        Illumination light;
        light.mode = Illumination::Mode::Global;
        light.directional = true;
        light.lights.directional.push_back({{0.3, -1, 0.2}, {3, 2, 1}});
        light.lights.point.push_back({{10, 30, 5}, {400, 400, 400}});
        const LightVolume v = view.readLightVolume(light);
        ASSERT_GE(v.levels.size(), 6u);
        double total0 = 0;
        for (size_t i = 0; i < v.levels[0].radiance.size(); i += 4) total0 += v.levels[0].radiance[i];
        ASSERT_GT(total0, 0);
        for (size_t level = 1; level < v.levels.size(); ++level) {
            const LightVolumeLevel& in = v.levels[level - 1];
            const LightVolumeLevel& out = v.levels[level];
            int n[3];
            for (int a = 0; a < 3; ++a) {
                ASSERT_EQ(out.size[a], std::max(1, in.size[a] / 2));
                n[a] = in.size[a] > 1 ? 2 : 1;
            }
            double total = 0;
            for (int pz = 0; pz < out.size[2]; ++pz)
                for (int py = 0; py < out.size[1]; ++py)
                    for (int px = 0; px < out.size[0]; ++px) {
                        auto child = [&](int i, int j, int k) {
                            return texel(in, n[0] > 1 ? 2 * px + i : px, n[1] > 1 ? 2 * py + j : py,
                                         n[2] > 1 ? 2 * pz + k : pz);
                        };
                        double radiance[4] = {0, 0, 0, 0}, through[3] = {0, 0, 0};
                        for (int k = 0; k < n[2]; ++k)
                            for (int j = 0; j < n[1]; ++j)
                                for (int i = 0; i < n[0]; ++i)
                                    for (int c = 0; c < 4; ++c) radiance[c] += in.radiance[child(i, j, k) + size_t(c)];
                        for (int k = 0; k < n[2]; ++k)
                            for (int j = 0; j < n[1]; ++j) {
                                double t = 1;
                                for (int i = 0; i < n[0]; ++i) t *= 1 - in.opacity[child(i, j, k)];
                                through[0] += t;
                            }
                        for (int k = 0; k < n[2]; ++k)
                            for (int i = 0; i < n[0]; ++i) {
                                double t = 1;
                                for (int j = 0; j < n[1]; ++j) t *= 1 - in.opacity[child(i, j, k) + 1];
                                through[1] += t;
                            }
                        for (int j = 0; j < n[1]; ++j)
                            for (int i = 0; i < n[0]; ++i) {
                                double t = 1;
                                for (int k = 0; k < n[2]; ++k) t *= 1 - in.opacity[child(i, j, k) + 2];
                                through[2] += t;
                            }
                        const double count = n[0] * n[1] * n[2];
                        const double columns[3] = {double(n[1] * n[2]), double(n[0] * n[2]), double(n[0] * n[1])};
                        const size_t o = texel(out, px, py, pz);
                        for (int c = 0; c < 4; ++c)
                            ASSERT_NEAR(out.radiance[o + c], radiance[c] / count, halfTolerance(radiance[c] / count))
                                << "level " << level << " texel " << px << "," << py << "," << pz;
                        // Six-way: along each direction, the children composited front
                        // to back (premultiplied) in the ray's order, columns averaged.
                        // Level 1 composites level 0's isotropic radiance.
                        for (int d = 0; d < 6; ++d) {
                            const int axis = d / 2, u = (axis + 1) % 3, w = (axis + 2) % 3;
                            const std::vector<float>& below = level == 1 ? in.radiance : in.along[size_t(d)];
                            double sum[4] = {0, 0, 0, 0}, slack[3] = {0, 0, 0};
                            for (int i = 0; i < n[u]; ++i)
                                for (int j = 0; j < n[w]; ++j) {
                                    double t = 1;
                                    for (int k = 0; k < n[axis]; ++k) {
                                        int c[3];
                                        c[u] = i, c[w] = j, c[axis] = d % 2 == 0 ? k : n[axis] - 1 - k;
                                        const size_t ci = child(c[0], c[1], c[2]);
                                        // From level 0, only the light leaving back towards the
                                        // ray: its lit side m (stored times the texel's light, the
                                        // mean of its premultiplied rgb) gives
                                        // clamp(1 - |m| + m·back, 0, 1), the cosine for a texel
                                        // lit from one side.
                                        double towards = 1;
                                        if (level == 1) {
                                            const double back = d % 2 == 0 ? -1.0 : 1.0;
                                            const double light = (double(below[ci]) + below[ci + 1] + below[ci + 2]) / 3;
                                            double m[3] = {0, 0, 0};
                                            if (light > 0)
                                                for (int a = 0; a < 3; ++a) m[a] = in.litSide[ci + size_t(a)] / light;
                                            const double length = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
                                            towards = std::clamp(1 - length + back * m[axis], 0.0, 1.0);
                                        }
                                        for (int ch = 0; ch < 3; ++ch) {
                                            sum[ch] += t * towards * below[ci + size_t(ch)];
                                            // The shader divides in its own float rounding: the
                                            // weight may move by a few halves' steps.
                                            if (level == 1) slack[ch] += t * 4e-3 * below[ci + size_t(ch)];
                                        }
                                        t *= 1 - in.opacity[ci + size_t(axis)];
                                    }
                                    sum[3] += 1 - t;
                                }
                            const double across = n[u] * n[w];
                            for (int ch = 0; ch < 4; ++ch)
                                ASSERT_NEAR(out.along[size_t(d)][o + size_t(ch)], sum[ch] / across,
                                            halfTolerance(sum[ch] / across) + (ch == 3 ? 1e-3 : slack[ch] / across))
                                    << "level " << level << " direction " << d << " channel " << ch;
                        }
                        // rgba8: GL may round a value to either neighbouring step of 1/255
                        // (the H100 stored 87/255 for 0.3433, llvmpipe rounds to nearest).
                        for (int a = 0; a < 3; ++a)
                            ASSERT_NEAR(out.opacity[o + a], 1 - through[a] / columns[a], 1.0 / 255 + 1e-6)
                                << "level " << level << " axis " << a;
                        total += out.radiance[o] * count;
                    }
            // The box filter keeps the level's total radiance (times texel volume).
            double totalIn = 0;
            for (size_t i = 0; i < in.radiance.size(); i += 4) totalIn += in.radiance[i];
            EXPECT_NEAR(total, totalIn, 4e-3 * totalIn);
        }
    }
}

TEST(Lighting, LitPicturesAreDeterministicAndOneBounceOnlyAddsLight)
{
    const svo::Octree octree = voxelizedWithNormals(svo::cornellBox(), 64);
    svo::gl::OctreeView view(context(), octree);
    const auto box = svo::gl::gridWorldBox(octree.grid);
    // Looking in through the open front, so that every surface seen is inside
    // the room (the outside of its walls gets no light, direct or bounced).
    svo::gl::ViewCamera camera;
    camera.eye = {0, 1, 3.2};
    camera.target = {0, 1, 0};
    camera.fovYDegrees = 36;
    svo::gl::ViewLayers layers;
    layers.outlines = false;
    layers.light.mode = Illumination::Mode::Direct;
    layers.light.lights = svo::gl::defaultLights(box, true);
    layers.light.gamma = 1.0;
    const svo::gl::Image direct = view.render(camera, 96, 96, layers);
    EXPECT_EQ(direct.rgba, view.render(camera, 96, 96, layers).rgba);
    for (const bool directional : {false, true}) {
    layers.light.mode = Illumination::Mode::Global;
    layers.light.directional = directional;
    const svo::gl::Image global = view.render(camera, 96, 96, layers);
    EXPECT_EQ(global.rgba, view.render(camera, 96, 96, layers).rgba);
    // Every voxel pixel of the GI picture is at least its direct light; the
    // pixels in shadow (black in the direct picture) get some bounce light.
    int voxelPixels = 0, shadowed = 0, bounced = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            const uint8_t* d = direct.pixel(x, y);
            const uint8_t* g = global.pixel(x, y);
            const bool voxel = d[0] == d[1] && d[1] == d[2]; // grey: the background is bluish
            if (!voxel) continue;
            ++voxelPixels;
            ASSERT_GE(g[1], d[1]) << x << "," << y;
            if (d[1] == 0) {
                ++shadowed;
                bounced += g[1] > 0;
            }
        }
    EXPECT_GT(voxelPixels, 96 * 96 / 4);
    EXPECT_GT(shadowed, 50);
    EXPECT_GT(bounced, shadowed * 3 / 4);
    }
    // Without six-way radiance the volume has none to read back.
    Illumination isotropic = layers.light;
    isotropic.directional = false;
    const LightVolume v = view.readLightVolume(isotropic);
    EXPECT_TRUE(v.levels[1].along[0].empty());
    EXPECT_FALSE(v.levels[0].radiance.empty());
}

/// Two rooms sealed from each other by a one-voxel wall, a point light in
/// one: no light reaches the other, directly or after a bounce, so its
/// pixels are exactly black in the path tracer. Isotropic radiance lets the
/// lit room's light through the coarse texels that straddle the wall;
/// six-way radiance, with its opacity kept as optical depth and level 0's
/// light sent out of its lit side by the cosine, keeps nearly all of it out,
/// and with cones clear of voxels (Illumination::clearance) all but 1 %.
TEST(Lighting, SixWayRadianceKeepsALitRoomsLightOutOfTheNextRoom)
{
    const svo::Octree octree = voxelizedWithNormals(svo::twoRooms(), 64);
    svo::gl::OctreeView view(context(), octree);
    const svo::gl::ViewCamera camera = darkRoomCamera();
    svo::gl::ViewLayers layers = twoRoomsLit(Illumination::Mode::Global);
    auto darkRoomMean = [&](bool directional) {
        layers.light.directional = directional;
        const svo::gl::Image image = view.render(camera, 96, 96, layers);
        double sum = 0;
        int pixels = 0;
        for (int y = 0; y < 96; ++y)
            for (int x = 0; x < 96; ++x) {
                const uint8_t* p = image.pixel(x, y);
                if (p[0] != p[1] || p[1] != p[2]) continue; // the background is bluish
                sum += p[1] / 255.0;
                ++pixels;
            }
        EXPECT_GT(pixels, 96 * 96 * 9 / 10); // the room fills the picture
        return sum / std::max(pixels, 1);
    };
    const double isotropic = darkRoomMean(false), sixWay = darkRoomMean(true);
    EXPECT_GT(isotropic, 0.02); // the leak this guards against is there to see
    EXPECT_LT(sixWay, 0.1 * isotropic);
    // What six-way radiance leaves comes from coarse texels that straddle
    // the wall; cones that read none (Illumination::clearance) leave under
    // the 1 % of the isotropic leak.
    layers.light.clearance = true;
    const double clear = darkRoomMean(true);
    EXPECT_GT(sixWay, 0.01 * isotropic); // without it, more: the test can fail
    EXPECT_LT(clear, 0.01 * isotropic) << "isotropic " << isotropic << ", six-way " << sixWay;
}

/// Illumination::clearance's levels (LightVolume::clearLevel): a level-L
/// sample anywhere in a texel of level 0 reads the 2³ level-L texels around
/// it (outside the volume, the empty border); none of them may hold a texel
/// of level 0 with a voxel. Checked at points across each texel, against
/// level 0's opacity as read back, on sparse random voxels in volumes of
/// several shapes and texel sizes; and the level is the one the max-norm
/// distance to the nearest such texel gives (1.5 · 2^L <= D - 1), by brute
/// force on the CPU.
TEST(Lighting, ClearanceLevelsReadNoVoxel)
{
    std::mt19937 rng(11);
    struct Case {
        std::array<uint32_t, 3> dims;
        uint32_t volume;
        int voxels;
    };
    for (const Case& c : std::vector<Case>{{{32, 32, 32}, 256, 12}, {{64, 8, 32}, 256, 6}, {{96, 40, 16}, 32, 20},
                                           {{64, 64, 64}, 64, 0}}) {
        SCOPED_TRACE(c.dims[0]);
        std::vector<Voxel> voxels;
        std::uniform_int_distribution<uint32_t> x(0, c.dims[0] - 1), y(0, c.dims[1] - 1), z(0, c.dims[2] - 1);
        for (int i = 0; i < c.voxels; ++i) voxels.push_back({x(rng), y(rng), z(rng)});
        if (c.voxels == 0) voxels.push_back({0, 0, 0}); // one in a corner: distances up to the cap
        const svo::Octree octree = octreeOf(unitGrid(c.dims[0], c.dims[1], c.dims[2]), voxels, {});
        svo::gl::OctreeView view(context(), octree);
        Illumination light;
        light.mode = Illumination::Mode::Global;
        light.directional = true;
        light.clearance = true;
        light.volumeResolution = c.volume;
        light.lights.directional.push_back({{0.3, -1, 0.2}, {1, 1, 1}});
        const LightVolume v = view.readLightVolume(light);
        const LightVolumeLevel& base = v.levels[0];
        const int* n = base.size;
        ASSERT_EQ(v.clearLevel.size(), size_t(n[0]) * size_t(n[1]) * size_t(n[2]));
        std::vector<std::array<int, 3>> occupied;
        std::vector<uint8_t> full(v.clearLevel.size(), 0);
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const float* t = &base.opacity[texel(base, i, j, k)];
                    if (t[0] + t[1] + t[2] + t[3] > 0) {
                        occupied.push_back({i, j, k});
                        full[texel(base, i, j, k) / 4] = 1;
                    }
                }
        ASSERT_EQ(occupied.empty(), voxels.empty());
        // Voxel texels in a box [lo, hi), by a summed-volume table.
        const size_t sx = size_t(n[0]) + 1, sy = size_t(n[1]) + 1;
        std::vector<int> sum(sx * sy * (size_t(n[2]) + 1), 0);
        auto at = [&](int i, int j, int k) -> int& { return sum[(size_t(k) * sy + size_t(j)) * sx + size_t(i)]; };
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i)
                    at(i + 1, j + 1, k + 1) = full[texel(base, i, j, k) / 4] + at(i, j + 1, k + 1) + at(i + 1, j, k + 1) +
                                              at(i + 1, j + 1, k) - at(i, j, k + 1) - at(i, j + 1, k) -
                                              at(i + 1, j, k) + at(i, j, k);
        auto inBox = [&](const int* lo, const int* hi) {
            return at(hi[0], hi[1], hi[2]) - at(lo[0], hi[1], hi[2]) - at(hi[0], lo[1], hi[2]) - at(hi[0], hi[1], lo[2]) +
                   at(lo[0], lo[1], hi[2]) + at(lo[0], hi[1], lo[2]) + at(hi[0], lo[1], lo[2]) - at(lo[0], lo[1], lo[2]);
        };
        int coarse = 0;
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    const int level = v.clearLevel[texel(base, i, j, k) / 4];
                    // The brute-force level.
                    int d = 255;
                    for (const auto& o : occupied)
                        d = std::min(d, std::max({std::abs(o[0] - i), std::abs(o[1] - j), std::abs(o[2] - k)}));
                    int expected = 0;
                    while (3 * (1 << (expected + 1)) <= 2 * (d - 1)) ++expected;
                    ASSERT_EQ(level, expected) << "texel " << i << "," << j << "," << k << ", distance " << d;
                    coarse += level >= 2;
                    if (level == 0 || size_t(level) >= v.levels.size()) continue;
                    // Points across the texel: the 2 level-L texels around each along each axis.
                    for (int corner = 0; corner < 27; ++corner) {
                        const double f[3] = {0.001 + 0.499 * (corner % 3), 0.001 + 0.499 * (corner / 3 % 3),
                                             0.001 + 0.499 * (corner / 9)};
                        int lo[3], hi[3];
                        for (int a = 0; a < 3; ++a) {
                            const int m = std::max(1, n[a] >> level), w = n[a] / m; // level-L texels, their width
                            const double u = ((a == 0 ? i : a == 1 ? j : k) + f[a]) / w - 0.5;
                            const int first = std::max(0, int(std::floor(u))), last = std::min(m - 1, int(std::floor(u)) + 1);
                            lo[a] = first * w;
                            hi[a] = (last + 1) * w;
                        }
                        ASSERT_EQ(inBox(lo, hi), 0) << "level " << level << " at texel " << i << "," << j << ","
                                                    << k << " reads a voxel's texel";
                    }
                }
        EXPECT_GT(coarse, 0); // the check above reaches coarse levels
    }
}

/// Direct light on the mesh's triangles in the dark room of the two rooms
/// is exactly 0, as on the path tracer's: the wall between them is closed.
/// At 256³ the wall's plane lies on a voxel boundary and its one voxel
/// layer on the dark side, so a point of the dark room's ceiling or floor
/// by the wall lies in the wall's voxel, where the opacity's gradient points
/// across the wall; its shadow ray's start moved down it into the lit room
/// (awayFromBeside), and 142 of 320 x 240 crease pixels came out lit.
TEST(Lighting, MeshCreasesByAClosedWallGetNoLightFromBehindIt)
{
    const svo::TriangleMesh mesh = svo::twoRooms();
    const svo::Octree octree = voxelizedWithNormals(mesh, 256);
    svo::gl::OctreeView view(context(), octree, &mesh);
    svo::gl::ViewLayers layers = twoRoomsLit(Illumination::Mode::Direct);
    layers.surface = svo::gl::Surface::Mesh;
    const int w = 240, h = 180;
    const svo::gl::Image image = view.render(darkRoomCamera(), w, h, layers);
    int room = 0, lit = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint8_t* p = image.pixel(x, y);
            if (p[0] != p[1] || p[1] != p[2]) continue; // the background is bluish
            ++room;
            if (p[0] > 0) ++lit;
        }
    EXPECT_GT(room, w * h * 9 / 10); // the room fills the picture
    EXPECT_EQ(lit, 0);
}

/// The glossy cone (Illumination::specular) reflects a lit wall. A floor at
/// y = 8 and a wall at x = 16, both across the grid, lit by a sun travelling
/// along (-1, -1/4, 0): the wall's lit face (+x) has radiance
/// L = ρ/π E cos θ = 0.75 · 0.970. Seen from above at 45° (looking along
/// (-1, -1, 0)), the floor's mirror direction (-1, 1, 0) meets the wall
/// about 20 voxels away, so with reflectance k the floor gains up to k L.
/// The cone model's bias: a cone at 45° to a one-voxel wall sees it through
/// the anisotropic opacity (opaque along x, a quarter along y at the cone's
/// level), so the composite reaches L only in part; at least half, by the
/// filter's numbers. The gain is linear in k.
TEST(Lighting, SpecularConeReflectsTheLitWall)
{
    const svo::GridSpec grid = unitGrid(64, 64, 64);
    std::vector<Voxel> voxels;
    std::vector<svo::Vec3f> normals;
    for (uint32_t x = 0; x < 64; ++x)
        for (uint32_t z = 0; z < 64; ++z)
            if (x != 16) voxels.push_back({x, 8, z});
    for (uint32_t y = 8; y < 64; ++y)
        for (uint32_t z = 0; z < 64; ++z) voxels.push_back({16, y, z});
    // The wall's normal is +x, the floor's +y, in voxel order (bricks by
    // index, bits x, y, z within a brick).
    svo::Octree octree = octreeOf(grid, voxels, {});
    std::vector<std::array<uint32_t, 3>> origin(octree.bricks.size());
    for (const auto& ref : svo::occupiedBricks(octree)) origin[ref.index] = ref.origin;
    size_t i = 0;
    for (size_t b = 0; b < octree.bricks.size(); ++b)
        for (uint32_t bit = 0; bit < 512; ++bit)
            if (octree.bricks[b].words[bit >> 6] >> (bit & 63) & 1)
                octree.attributes.normals[i++] = origin[b][0] + (bit >> 6) == 16 ? svo::Vec3f{1, 0, 0}
                                                                                 : svo::Vec3f{0, 1, 0};
    ASSERT_EQ(i, voxels.size());
    svo::gl::OctreeView view(context(), octree);

    svo::gl::ViewCamera camera;
    camera.orthographic = true;
    camera.target = {34, 8.5, 32};
    camera.eye = camera.target + Vec3d{60, 60, 0};
    camera.height = 8;
    svo::gl::ViewLayers layers;
    layers.outlines = false;
    layers.light.mode = Illumination::Mode::Global;
    layers.light.lights.directional.push_back({{-1, -0.25, 0}, {M_PI, M_PI, M_PI}});
    layers.light.gamma = 1.0;
    layers.light.specularApertureDegrees = 10;
    const svo::gl::Image matte = view.render(camera, 32, 32, layers);
    auto gain = [&](double k) { // the mean gain over the middle of the picture
        layers.light.specular = {k, k, k};
        const svo::gl::Image glossy = view.render(camera, 32, 32, layers);
        double sum = 0;
        int n = 0;
        for (int y = 8; y < 24; ++y)
            for (int x = 8; x < 24; ++x) {
                sum += (glossy.pixel(x, y)[1] - matte.pixel(x, y)[1]) / 255.0;
                ++n;
            }
        return sum / n;
    };
    const double wall = 0.75 * (1.0 / std::sqrt(1.0 + 0.0625));
    const double half = gain(0.5), full = gain(1.0);
    EXPECT_GT(half, 0.5 * 0.5 * wall);
    EXPECT_LT(half, 0.5 * wall);
    EXPECT_NEAR(full, 2 * half, 1.5 / 255); // 8-bit rounding of each pixel
}

/// A square of `size` at height y over [x0, x0 + size] x [z0, z0 + size], two triangles.
void addSquare(svo::TriangleMesh& m, double x0, double y, double z0, double size)
{
    const auto first = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {{x0, y, z0}, {x0 + size, y, z0}, {x0 + size, y, z0 + size}, {x0, y, z0 + size}});
    m.triangles.push_back({first, first + 1, first + 2});
    m.triangles.push_back({first, first + 2, first + 3});
}

/// ViewLayers::surface = Mesh shades the mesh's own triangles. Seen from
/// straight above (orthographic, a pixel per voxel): a floor [0, 1]² and a
/// square occluder over [0.4, 0.6]² at height 0.5, voxelized at 64, lit by a
/// sun travelling along (-0.6, -0.8, 0) with irradiance π:
///   - the picture covers exactly the floor's pixels (its edges lie on pixel
///     edges), not the voxels' wider squares;
///   - lit floor and occluder reflect ρ/π E cos θ = 0.75 · 0.8 = 0.6; the
///     occluder's shadow, [0.025, 0.225] x [0.4, 0.6] on the floor, is 0:
///     each pixel marches its own shadow ray from its point on the floor.
/// With a wall along x = 0 added, the floor's AO beside the wall (the concave
/// edge) stays above 0.35 (a wall half the hemisphere blocks gives 0.5 for a
/// wall of any height): cones starting among the wall's texels composited it
/// again and again, and such pixels came out at 0.1; and a sun straight down
/// lights the floor beside the wall fully.
TEST(Lighting, MeshSurfaceIsShadedOnItsTriangles)
{
    svo::TriangleMesh mesh;
    addSquare(mesh, 0, 0, 0, 1);
    addSquare(mesh, 0.4, 0.5, 0.4, 0.2);
    const svo::Octree octree = voxelizedWithNormals(mesh, 64);
    ASSERT_NEAR(octree.grid.voxelSize, 1.0 / 64, 1e-12);
    svo::gl::OctreeView view(context(), octree, &mesh);
    svo::gl::ViewCamera above;
    above.orthographic = true;
    above.target = {0.5, 0, 0.5};
    above.eye = {0.5, 5, 0.5};
    above.up = {0, 0, -1}; // image right = +x, image down = +z
    above.height = 1.5;    // 96 pixels of 1/64: the floor is pixels [16, 80)²
    svo::gl::ViewLayers layers;
    layers.outlines = false;
    layers.surface = svo::gl::Surface::Mesh;
    layers.light.mode = Illumination::Mode::Direct;
    layers.light.lights.directional.push_back({{-0.6, -0.8, 0}, {M_PI, M_PI, M_PI}});
    layers.light.gamma = 1.0;
    const svo::gl::Image image = view.render(above, 96, 96, layers);
    EXPECT_EQ(image.rgba, view.render(above, 96, 96, layers).rgba);
    auto world = [](int pixel) { return (pixel + 0.5 - 16) / 64.0; }; // pixel centre -> x or z
    auto near = [](double v, double lo, double hi) { return v > lo - 2.5 / 64 && v < hi + 2.5 / 64; };
    int lit = 0, shadowed = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            const uint8_t* p = image.pixel(x, y);
            const bool surface = p[0] == p[1] && p[1] == p[2]; // grey: the background is bluish
            const double wx = world(x), wz = world(y);
            ASSERT_EQ(surface, wx > 0 && wx < 1 && wz > 0 && wz < 1) << x << "," << y;
            if (!surface || near(wx, 0, 0) || near(wx, 1, 1) || near(wz, 0, 0) || near(wz, 1, 1)) continue;
            const bool occluder = wx > 0.4 && wx < 0.6 && wz > 0.4 && wz < 0.6;
            const bool shadow = !occluder && wx > 0.025 && wx < 0.225 && wz > 0.4 && wz < 0.6;
            if (near(wx, 0.4, 0.6) && near(wz, 0.4, 0.6) && !occluder) continue; // the occluder's rim
            if (near(wx, 0.025, 0.225) && near(wz, 0.4, 0.6) && !shadow) continue; // the shadow's rim
            if (shadow && (wx < 0.025 + 2.5 / 64 || wx > 0.225 - 2.5 / 64 || wz < 0.4 + 2.5 / 64 || wz > 0.6 - 2.5 / 64))
                continue;
            if (shadow) {
                EXPECT_LE(p[1], 1) << x << "," << y;
                ++shadowed;
            } else {
                EXPECT_NEAR(p[1], 0.6 * 255, 1.01) << x << "," << y;
                ++lit;
            }
        }
    EXPECT_GT(lit, 2000);
    EXPECT_GT(shadowed, 50);

    // The concave edge: a wall along x = 0 on the floor; AO alone, 7 cones.
    svo::TriangleMesh corner;
    addSquare(corner, 0, 0, 0, 1);
    const auto first = uint32_t(corner.positions.size());
    corner.positions.insert(corner.positions.end(), {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});
    corner.triangles.push_back({first, first + 1, first + 2});
    corner.triangles.push_back({first, first + 2, first + 3});
    const svo::Octree cornerOctree = voxelizedWithNormals(corner, 64);
    svo::gl::OctreeView cornerView(context(), cornerOctree, &corner);
    svo::gl::ViewLayers ao;
    ao.outlines = false;
    ao.surface = svo::gl::Surface::Mesh;
    ao.ao.cones = 7;
    ao.ao.only = true;
    ao.ao.distance = 16;
    const svo::gl::Image occlusion = cornerView.render(above, 96, 96, ao);
    double lowest = 1;
    for (int y = 40; y < 56; ++y)       // the middle of the edge, away from its ends
        for (int x = 16; x < 19; ++x) { // floor points within 3 voxels of the wall
            const uint8_t* p = occlusion.pixel(x, y);
            ASSERT_TRUE(p[0] == p[1] && p[1] == p[2]) << x << "," << y;
            lowest = std::min(lowest, p[1] / 255.0);
        }
    EXPECT_GT(lowest, 0.35);
    // Away from the wall the floor is open: AO 1.
    EXPECT_GT(occlusion.pixel(70, 48)[1], 250);
    // The first picture's sun, from above and beyond the floor's far side, lights the whole
    // floor, the wall casts no shadow: ρ/π E cos θ = 0.75 · 0.8 = 0.6 at every
    // floor pixel, those beside the wall too. Their shadow rays, pushed out
    // along the normal alone, started among the wall's voxels, and the edge
    // came out black (awayFromBeside).
    svo::gl::ViewCamera edge = above; // 4 pixels a voxel; the wall at pixel column 9.6
    edge.target = {0.15, 0, 0.5};
    edge.eye = {0.15, 5, 0.5};
    edge.height = 0.375;
    const svo::gl::Image sunlit = cornerView.render(edge, 96, 96, layers); // the sun above
    for (int y = 40; y < 56; ++y)
        for (int x = 10; x < 21; ++x) // floor points 0.1 to 2.6 voxels from the wall
            EXPECT_NEAR(sunlit.pixel(x, y)[1], 0.6 * 255, 1.01) << x << "," << y;

    // Without the mesh there is nothing to shade.
    svo::gl::OctreeView voxelsOnly(context(), octree);
    try {
        voxelsOnly.render(above, 8, 8, layers);
        ADD_FAILURE() << "Surface::Mesh drew without a mesh";
    } catch (const svo::Error& e) {
        EXPECT_NE(std::string(e.what()).find("needs the mesh"), std::string::npos) << e.what();
    }
}

TEST(Lighting, BadLightingIsAClearError)
{
    const svo::GridSpec grid = unitGrid(16, 16, 16);
    const svo::Octree withNormals = octreeOf(grid, {{1, 2, 3}, {4, 5, 6}}, {{0, 1, 0}});
    svo::Octree without = withNormals;
    without.attributes = {};
    Illumination ok;
    ok.mode = Illumination::Mode::Global;
    ok.lights.directional.push_back({});
    auto message = [](const svo::Octree& o, const Illumination& l) {
        try {
            svo::gl::OctreeView view(context(), o);
            view.readLightVolume(l);
        } catch (const svo::Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(message(withNormals, ok), "");
    EXPECT_NE(message(without, ok).find("no normal channel"), std::string::npos);
    auto bad = [&](auto change, const char* expected) {
        Illumination l = ok;
        change(l);
        const std::string m = message(withNormals, l);
        EXPECT_NE(m.find(expected), std::string::npos) << m;
    };
    bad([](Illumination& l) { l.lights = {}; }, "no light");
    bad([](Illumination& l) { l.lights.directional[0].direction = {0, 0, 0}; }, "is zero");
    bad([](Illumination& l) { l.lights.environment = {1, 1, 1}; }, "environment");
    bad([](Illumination& l) { l.cones = 0; }, "Illumination::cones 0"); // the field, as the rule names it
    bad([](Illumination& l) { l.volumeResolution = 100; }, "power of two");
    bad([](Illumination& l) { l.albedo = {1.5, 0, 0}; }, "albedo");
    bad([](Illumination& l) { l.exposure = 0; }, "exposure");
    bad([](Illumination& l) { l.specular = {0, 2, 0}; }, "specular");
    bad([](Illumination& l) { l.step = 0; }, "Illumination::step 0");
    bad([](Illumination& l) { l.specularApertureDegrees = 180; }, "Illumination::specularApertureDegrees 180");
    // A grid too wide for the volume: a texel holds at most 8³ voxels.
    const svo::Octree wide = octreeOf(unitGrid(1024, 8, 8), {{1000, 1, 1}}, {{1, 0, 0}});
    Illumination small = ok;
    small.volumeResolution = 64;
    EXPECT_NE(message(wide, small).find("at least 128"), std::string::npos) << message(wide, small);
}

/// llvmpipe ends every loop of an invocation, silently, once they have run
/// 65,535 iterations in all (ContextInfo::loopLimit). A picture whose rays or
/// light injection passed that budget is refused, not drawn with voxels,
/// occlusion or light missing. Two cases that pass it on llvmpipe: cones of
/// 1° stepping a hundredth of their width for 2000 voxels, and a lighting
/// volume of 64 texels over the Cornell box at 256³ (4³ voxels a texel, each
/// marching its shadow ray). On a GPU there is no limit and both draw; the
/// defaults draw everywhere.
TEST(Lighting, LoopsACpuRasterizerCutShortAreRefused)
{
    const bool limited = context().info().loopLimit != 0;
    const svo::TriangleMesh mesh = svo::cornellBox();
    svo::gl::ViewCamera camera;
    camera.eye = {0, 1, 3.2};
    camera.target = {0, 1, 0};
    camera.fovYDegrees = 36;
    auto refusedOrDrawn = [&](const svo::gl::OctreeView& view, const svo::gl::ViewLayers& layers,
                              const char* expected) {
        try {
            const svo::gl::Image image = view.render(camera, 48, 48, layers);
            EXPECT_FALSE(limited) << "drawn on " << context().info().renderer;
            EXPECT_EQ(view.cutPixels(), 0u);
        } catch (const svo::Error& e) {
            EXPECT_TRUE(limited) << e.what();
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    };

    const svo::Octree coarse = voxelizedWithNormals(mesh, 64);
    svo::gl::OctreeView view(context(), coarse);
    svo::gl::ViewLayers layers;
    layers.outlines = false;
    layers.ao.cones = 7;
    layers.ao.only = true;
    (void)view.render(camera, 48, 48, layers);
    EXPECT_EQ(view.cutPixels(), 0u);
    layers.ao.apertureDegrees = 1;
    layers.ao.step = 0.01;
    layers.ao.distance = 2000;
    refusedOrDrawn(view, layers, "ended the rays of");
    if (limited) {
        EXPECT_GT(view.cutPixels(), 0u);
    }

    const svo::Octree fine = voxelizedWithNormals(mesh, 256);
    view.setOctree(fine);
    svo::gl::ViewLayers lit;
    lit.outlines = false;
    lit.light.mode = Illumination::Mode::Direct;
    lit.light.lights = svo::gl::defaultLights(svo::gl::gridWorldBox(fine.grid), true);
    (void)view.render(camera, 48, 48, lit);
    lit.light.volumeResolution = 64;
    refusedOrDrawn(view, lit, "ended the light injection of");
}
