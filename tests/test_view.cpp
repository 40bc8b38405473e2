// The octree viewer's renderer (svo/gl/octree_view.h) against pictures
// computed on the CPU from the voxel set alone: orthographic axis views of a
// single voxel, a tilted plane and a GPU-voxelized box must cover exactly the
// pixels of the voxels' projection (up to a one-pixel border), node outlines
// must lie on the boxes of the chosen level's occupied nodes, voxels and mesh
// must hide each other by depth, and one camera must give the same bytes twice.
// What svo view opens with: a level set at its zero crossing (against
// OpenVDB's interior mask and erosion), an unsigned field within half a voxel
// (an analytic plane), the Cornell box through its open front with the red
// wall on the left and the green one on the right.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "../apps/view_keys.h" // the window's key table, header-only
#include "svo/gl/gl_api.h"       // plain GL, through epoxy, for the reference drawing
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/Morphology.h>

#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/grid.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_key.h"
#include "svo/gl/context.h"
#include "svo/gl/octree_view.h"
#include "svo/load_octree.h"
#include "svo/vdb_io/zero_crossing.h"
#include "svo/voxelizer.h"
#include "temp_dir.h"

namespace {

using svo::GridSpec;
using svo::Vec3d;
using svo::gl::Image;
using svo::gl::ViewCamera;
using svo::gl::ViewLayers;
using Voxel = std::array<uint32_t, 3>; // local coordinates

svo::gl::Context& context()
{
    static svo::gl::Context c;
    return c;
}

svo::Octree octreeOf(const GridSpec& grid, const std::vector<Voxel>& voxels)
{
    std::vector<uint64_t> keys;
    for (const Voxel& v : voxels) keys.push_back(svo::packVoxelKey(v[0], v[1], v[2]));
    return svo::buildOctree(grid, keys);
}

GridSpec unitGrid(uint32_t dim)
{
    GridSpec g;
    g.voxelSize = 1.0;
    g.dims = {dim, dim, dim};
    return g;
}

Vec3d cross(const Vec3d& a, const Vec3d& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// An orthographic view down axis `axis` (from its + side), `pixel` world
/// units per pixel, with the image frame the header promises, written out
/// here on its own so the test does not reuse the renderer's matrices.
struct AxisView {
    ViewCamera camera;
    int width, height;
    double pixel;
    Vec3d right, up;

    AxisView(int axis, const Vec3d& target, double pixelSize, int w, int h) : width(w), height(h), pixel(pixelSize)
    {
        Vec3d dir{0, 0, 0};
        dir[axis] = 1;
        camera.orthographic = true;
        camera.target = target;
        camera.eye = target + 100.0 * dir;
        camera.up = axis == 1 ? Vec3d{0, 0, -1} : Vec3d{0, 1, 0};
        camera.height = pixel * h;
        const Vec3d forward = -1.0 * dir;
        right = cross(forward, camera.up);
        up = cross(right, forward);
    }
    /// Continuous image position of a world point: x from the left, y from the top, in pixels.
    std::array<double, 2> project(const Vec3d& p) const
    {
        const Vec3d d = p - camera.target;
        return {width / 2.0 + dot(d, right) / pixel, height / 2.0 - dot(d, up) / pixel};
    }
};

/// World corners of local voxel v's cube.
std::array<Vec3d, 2> voxelCube(const GridSpec& g, const Voxel& v)
{
    std::array<Vec3d, 2> c;
    const auto t = g.translation();
    for (int i = 0; i < 3; ++i) {
        const double centre = double(g.anchor[size_t(i)] + int64_t(v[size_t(i)]));
        c[0][i] = g.voxelSize * (centre - 0.5) + t[size_t(i)];
        c[1][i] = g.voxelSize * (centre + 0.5) + t[size_t(i)];
    }
    return c;
}

/// The image rectangle [x0, x1) x [y0, y1) (continuous pixels) of a world box in an axis view.
std::array<double, 4> rectangle(const AxisView& view, const std::array<Vec3d, 2>& box)
{
    std::array<double, 4> r{1e300, 1e300, -1e300, -1e300};
    for (int c = 0; c < 8; ++c) {
        const Vec3d p{box[c & 1].x, box[(c >> 1) & 1].y, box[c >> 2].z};
        const auto q = view.project(p);
        r[0] = std::min(r[0], q[0]);
        r[1] = std::min(r[1], q[1]);
        r[2] = std::max(r[2], q[0]);
        r[3] = std::max(r[3], q[1]);
    }
    return r;
}

bool isGreen(const uint8_t* p) { return p[1] > p[0] + 50 && p[1] > p[2] + 50; }
bool isRed(const uint8_t* p) { return p[0] > p[1] + 76 && p[0] > p[2] + 76; }

using Mask = std::vector<uint8_t>;

/// Pixels whose centres lie inside some voxel's projected square: the CPU projection.
Mask projection(const AxisView& view, const GridSpec& g, const std::vector<Voxel>& voxels)
{
    Mask m(size_t(view.width) * size_t(view.height), 0);
    for (const Voxel& v : voxels) {
        const auto r = rectangle(view, voxelCube(g, v));
        for (int y = std::max(0, int(std::floor(r[1]))); y < std::min(view.height, int(std::ceil(r[3]))); ++y)
            for (int x = std::max(0, int(std::floor(r[0]))); x < std::min(view.width, int(std::ceil(r[2]))); ++x)
                if (x + 0.5 > r[0] && x + 0.5 < r[2] && y + 0.5 > r[1] && y + 0.5 < r[3])
                    m[size_t(y) * size_t(view.width) + size_t(x)] = 1;
    }
    return m;
}

/// Every pixel of `m`'s 3x3 neighbourhood equal to `value`.
bool allAround(const Mask& m, int w, int h, int x, int y, uint8_t value)
{
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            const uint8_t got = xx < 0 || yy < 0 || xx >= w || yy >= h ? 0 : m[size_t(yy) * size_t(w) + size_t(xx)];
            if (got != value) return false;
        }
    return true;
}

struct Coverage {
    size_t expected = 0, interior = 0, green = 0, missed = 0, extra = 0;
};

/// Compares the green pixels with the projection: a pixel whose 3x3
/// neighbourhood is all covered must be green (missed otherwise), one whose
/// neighbourhood is all uncovered must not be (extra otherwise).
Coverage compare(const Image& image, const Mask& expected)
{
    Coverage c;
    const int w = image.width, h = image.height;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool green = isGreen(image.pixel(x, y));
            c.green += green;
            c.expected += expected[size_t(y) * size_t(w) + size_t(x)];
            if (allAround(expected, w, h, x, y, 1)) {
                ++c.interior;
                if (!green) ++c.missed;
            }
            if (allAround(expected, w, h, x, y, 0) && green) ++c.extra;
        }
    return c;
}

/// The three axis views of a voxel set, each checked against its projection.
void expectAxisViewsMatch(const GridSpec& grid, const std::vector<Voxel>& voxels, const svo::Octree& octree)
{
    ASSERT_FALSE(voxels.empty());
    svo::gl::OctreeView view(context(), octree);
    // Aim at the voxels' centre, moved off the lattice so that no voxel edge
    // falls on a pixel centre in every row.
    std::array<Vec3d, 2> box = voxelCube(grid, voxels[0]);
    for (const Voxel& v : voxels) {
        const auto c = voxelCube(grid, v);
        for (int i = 0; i < 3; ++i) {
            box[0][i] = std::min(box[0][i], c[0][i]);
            box[1][i] = std::max(box[1][i], c[1][i]);
        }
    }
    const Vec3d target = 0.5 * (box[0] + box[1]) + Vec3d{0.13 * grid.voxelSize, 0.07 * grid.voxelSize, 0.11 * grid.voxelSize};
    ViewLayers layers;
    layers.outlines = false;
    for (int axis = 0; axis < 3; ++axis) {
        const AxisView av(axis, target, 0.25 * grid.voxelSize, 160, 120);
        const Image image = view.render(av.camera, av.width, av.height, layers);
        const Mask expected = projection(av, grid, voxels);
        const Coverage c = compare(image, expected);
        SCOPED_TRACE("axis " + std::to_string(axis));
        EXPECT_GT(c.interior, 0u) << "the projection has no interior pixel: the test would prove nothing";
        EXPECT_EQ(c.missed, 0u) << c.expected << " pixels expected, " << c.green << " green";
        EXPECT_EQ(c.extra, 0u) << c.expected << " pixels expected, " << c.green << " green";
        // The border allows at most the projection's outline: the counts agree to that.
        EXPECT_LE(c.green, c.expected + (c.expected - c.interior) * 2 + 8);
    }
}

TEST(View, SingleVoxelCoversItsSquareInEachAxisView)
{
    const GridSpec g = unitGrid(16);
    const std::vector<Voxel> voxels = {{5, 6, 7}};
    expectAxisViewsMatch(g, voxels, octreeOf(g, voxels));
}

TEST(View, TiltedPlaneCoversItsProjectionInEachAxisView)
{
    // A staircase plane z = 4 + x / 3: its three projections are a full
    // rectangle (down z), a band of steps (down y) and a rectangle (down x).
    const GridSpec g = unitGrid(32);
    std::vector<Voxel> voxels;
    for (uint32_t x = 2; x < 28; ++x)
        for (uint32_t y = 3; y < 25; ++y) voxels.push_back({x, y, 4 + x / 3});
    expectAxisViewsMatch(g, voxels, octreeOf(g, voxels));
}

TEST(View, GpuVoxelizedBoxCoversItsProjectionInEachAxisView)
{
    // A box mesh voxelized on the GPU (anchor below 0, so local != global).
    svo::TriangleMesh box;
    box.source = "box";
    const Vec3d lo{0.3, 1.2, 2.1}, hi{10.7, 7.9, 12.4};
    for (int c = 0; c < 8; ++c) box.positions.push_back({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        box.triangles.push_back({q[0], q[1], q[2]});
        box.triangles.push_back({q[0], q[2], q[3]});
    }
    const GridSpec g = svo::makeGrid(box, svo::GridRequest{0, 1.0});
    svo::Voxelizer voxelizer;
    const svo::Octree octree = voxelizer.voxelize(box, g);
    std::vector<Voxel> voxels;
    for (uint64_t k : svo::octreeKeys(octree)) voxels.push_back(svo::unpackVoxelKey(k));
    ASSERT_GT(voxels.size(), 100u);
    expectAxisViewsMatch(g, voxels, octree);
}

/// A reference drawing written here with plain GL and no svo code: every
/// voxel's cube as an instanced, rasterized box, seen by a perspective camera
/// with the image frame the header promises. Returns the covered pixels,
/// rows from the top.
Mask cubeCoverage(const GridSpec& g, const std::vector<Voxel>& voxels, const ViewCamera& cam, int w, int h)
{
    const svo::gl::Context::Scope scope(context());
    auto shader = [](GLenum type, const char* src) {
        const GLuint s = glCreateShader(type);
        glShaderSource(s, 1, &src, nullptr);
        glCompileShader(s);
        GLint ok = 0;
        glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
        EXPECT_TRUE(ok);
        return s;
    };
    // 36 vertices of a unit cube from gl_VertexID; the instance's cube from the buffer.
    const GLuint vs = shader(GL_VERTEX_SHADER, R"(#version 450 core
layout(std430, binding = 0) readonly buffer Cubes { vec4 cubes[]; }; // lo.xyz, size
uniform mat4 uViewProjection;
const int kFaces[36] = int[](0,2,3, 0,3,1, 4,5,7, 4,7,6, 0,1,5, 0,5,4, 2,6,7, 2,7,3, 0,4,6, 0,6,2, 1,3,7, 1,7,5);
void main() {
    int c = kFaces[gl_VertexID];
    vec4 cube = cubes[gl_InstanceID];
    vec3 p = cube.xyz + cube.w * vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    gl_Position = uViewProjection * vec4(p, 1.0);
})");
    const GLuint fs = shader(GL_FRAGMENT_SHADER, R"(#version 450 core
out vec4 color; void main() { color = vec4(1.0); })");
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);

    // Positions relative to the target, so floats keep their precision.
    std::vector<float> cubes;
    for (const Voxel& v : voxels) {
        const auto c = voxelCube(g, v);
        const Vec3d lo = c[0] - cam.target;
        cubes.insert(cubes.end(), {float(lo.x), float(lo.y), float(lo.z), float(g.voxelSize)});
    }
    const Vec3d f0 = cam.target - cam.eye;
    const Vec3d f = (1.0 / std::sqrt(dot(f0, f0))) * f0;
    Vec3d r = cross(f, cam.up);
    r = (1.0 / std::sqrt(dot(r, r))) * r;
    const Vec3d u = cross(r, f), e = cam.eye - cam.target;
    const double dist = std::sqrt(dot(f0, f0)), n = 0.01 * dist, fa = 10 * dist;
    const double t = 1.0 / std::tan(cam.fovYDegrees * M_PI / 360.0), aspect = double(w) / h;
    const double view[16] = {r.x, u.x, -f.x, 0, r.y, u.y, -f.y, 0, r.z, u.z, -f.z, 0,
                             -dot(r, e), -dot(u, e), dot(f, e), 1};
    const double proj[16] = {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0};
    float vp[16];
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += proj[k * 4 + row] * view[c * 4 + k];
            vp[c * 4 + row] = float(sum);
        }

    GLuint buffer = 0, vao = 0, fbo = 0, rb = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, GLsizeiptr(cubes.size() * 4), cubes.data(), 0);
    glCreateVertexArrays(1, &vao);
    glCreateRenderbuffers(1, &rb);
    glNamedRenderbufferStorage(rb, GL_RGBA8, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(program);
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "uViewProjection"), 1, GL_FALSE, vp);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glBindVertexArray(vao);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 36, GLsizei(voxels.size()));
    std::vector<uint8_t> rgba(size_t(w) * size_t(h) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &buffer);
    glDeleteProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    Mask m(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) m[size_t(y) * size_t(w) + size_t(x)] = rgba[4 * (size_t(h - 1 - y) * size_t(w) + size_t(x))] > 127;
    return m;
}

/// In perspective, from oblique directions, the ray march covers the pixels
/// that the voxels drawn as instanced cubes cover (up to a one-pixel border).
TEST(View, RayMarchCoversWhatInstancedCubesCoverInPerspective)
{
    const svo::TriangleMesh mesh = svo::cornellBox();
    const GridSpec g = svo::makeGrid(mesh, svo::GridRequest{40, 0});
    svo::Voxelizer voxelizer;
    const svo::Octree octree = voxelizer.voxelize(mesh, g);
    std::vector<Voxel> voxels;
    for (uint64_t k : svo::octreeKeys(octree)) voxels.push_back(svo::unpackVoxelKey(k));
    ASSERT_GT(voxels.size(), 1000u);
    svo::gl::OctreeView view(context(), octree);
    ViewLayers layers;
    layers.outlines = false;
    for (const Vec3d dir : {Vec3d{-0.4, -0.5, -1.0}, Vec3d{0.7, 0.2, -0.3}, Vec3d{0.1, 1.0, 0.35}}) {
        ViewCamera cam = svo::gl::frameBox(svo::gl::gridWorldBox(g), dir, false, 4.0 / 3.0);
        cam.eye = cam.eye + Vec3d{0.013, -0.007, 0.011}; // off the lattice's symmetries
        const Image image = view.render(cam, 160, 120, layers);
        const Coverage c = compare(image, cubeCoverage(g, voxels, cam, 160, 120));
        SCOPED_TRACE("direction " + std::to_string(dir.x) + "," + std::to_string(dir.y) + "," + std::to_string(dir.z));
        EXPECT_GT(c.interior, 1000u);
        EXPECT_EQ(c.missed, 0u) << c.expected << " pixels covered by cubes, " << c.green << " green";
        EXPECT_EQ(c.extra, 0u) << c.expected << " pixels covered by cubes, " << c.green << " green";
    }
}

/// Distance from a point to the outline of a rectangle {x0, y0, x1, y1}.
double distanceToOutline(const std::array<double, 4>& r, double x, double y)
{
    const double dx = std::max({r[0] - x, 0.0, x - r[2]}), dy = std::max({r[1] - y, 0.0, y - r[3]});
    if (dx > 0 || dy > 0) return std::hypot(dx, dy);
    return std::min({x - r[0], r[2] - x, y - r[1], r[3] - y}); // inside: to the nearest side
}

TEST(View, OutlinesLieOnTheOccupiedNodeBoxesOfTheChosenLevel)
{
    const GridSpec g = unitGrid(32); // brick level 2: node edges 32, 16, 8 voxels
    const std::vector<Voxel> voxels = {{1, 1, 1}, {20, 3, 5}, {9, 25, 17}, {27, 28, 29}};
    const svo::Octree octree = octreeOf(g, voxels);
    ASSERT_EQ(octree.brickLevel, 2u);
    svo::gl::OctreeView view(context(), octree);
    for (uint32_t level : {1u, 2u}) {
        const uint32_t size = 8u << (octree.brickLevel - level);
        // The occupied nodes' boxes, from the voxels alone.
        std::set<Voxel> origins;
        for (const Voxel& v : voxels) origins.insert({v[0] / size * size, v[1] / size * size, v[2] / size * size});
        ViewLayers layers;
        layers.voxels = false;
        layers.firstLevel = layers.lastLevel = level;
        const AxisView av(2, Vec3d{15.6, 15.3, 15.1}, 0.25, 160, 160);
        const Image image = view.render(av.camera, av.width, av.height, layers);
        std::vector<std::array<double, 4>> rects;
        for (const Voxel& o : origins) {
            const Vec3d a{double(o[0]) - 0.5, double(o[1]) - 0.5, double(o[2]) - 0.5};
            rects.push_back(rectangle(av, {a, a + Vec3d{double(size), double(size), double(size)}}));
        }
        SCOPED_TRACE("level " + std::to_string(level));
        // Every red pixel lies within 1.5 pixels of an expected box edge.
        size_t red = 0, stray = 0;
        for (int y = 0; y < av.height; ++y)
            for (int x = 0; x < av.width; ++x) {
                if (!isRed(image.pixel(x, y))) continue;
                ++red;
                double best = 1e300;
                for (const auto& r : rects) best = std::min(best, distanceToOutline(r, x + 0.5, y + 0.5));
                stray += best > 1.5;
            }
        EXPECT_EQ(stray, 0u) << red << " red pixels";
        // Every expected edge inside the picture shows red near its quarter points.
        size_t samples = 0, found = 0;
        for (const auto& r : rects)
            for (int side = 0; side < 4; ++side)
                for (double f : {0.25, 0.5, 0.75}) {
                    const double x = side < 2 ? r[0] + f * (r[2] - r[0]) : r[side == 2 ? 0 : 2];
                    const double y = side < 2 ? r[side == 0 ? 1 : 3] : r[1] + f * (r[3] - r[1]);
                    if (x < 2 || y < 2 || x > av.width - 2 || y > av.height - 2) continue;
                    ++samples;
                    bool hit = false;
                    for (int dy = -2; dy <= 1 && !hit; ++dy)
                        for (int dx = -2; dx <= 1 && !hit; ++dx) {
                            const int xx = int(std::floor(x)) + dx, yy = int(std::floor(y)) + dy;
                            if (xx >= 0 && yy >= 0 && xx < av.width && yy < av.height)
                                hit = isRed(image.pixel(xx, yy));
                        }
                    found += hit;
                }
        EXPECT_GT(samples, 8u);
        EXPECT_EQ(found, samples);
    }
}

TEST(View, SameCameraGivesTheSameBytesAndEveryLayerDraws)
{
    const svo::TriangleMesh mesh = svo::cornellBox();
    const GridSpec g = svo::makeGrid(mesh, svo::GridRequest{32, 0});
    svo::Voxelizer voxelizer;
    const svo::Octree octree = voxelizer.voxelize(mesh, g);
    svo::gl::OctreeView view(context(), octree, &mesh);
    const ViewCamera camera = svo::gl::frameBox(svo::gl::gridWorldBox(g), Vec3d{-0.4, -0.5, -1.0}, false, 4.0 / 3.0);
    ViewLayers all;
    all.mesh = true;
    const Image a = view.render(camera, 200, 150, all);
    const Image b = view.render(camera, 200, 150, all);
    EXPECT_EQ(a.rgba, b.rgba);
    size_t green = 0, red = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            green += isGreen(a.pixel(x, y));
            red += isRed(a.pixel(x, y));
        }
    EXPECT_GT(green, size_t(a.width * a.height / 10));
    EXPECT_GT(red, 50u);
    // The mesh alone: grey pixels, no green or red.
    ViewLayers meshOnly;
    meshOnly.voxels = meshOnly.outlines = false;
    meshOnly.mesh = true;
    const Image m = view.render(camera, 200, 150, meshOnly);
    size_t grey = 0, coloured = 0;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const uint8_t* p = m.pixel(x, y);
            grey += p[0] > 60 && std::abs(int(p[0]) - int(p[1])) < 8;
            coloured += isGreen(p) || isRed(p);
        }
    EXPECT_GT(grey, size_t(m.width * m.height / 10));
    EXPECT_EQ(coloured, 0u);
}

/// The voxels' depth is the mesh's: a patch of voxels hides a mesh square
/// behind it and is hidden by it from the other side (the rays write their
/// depth through the copy into the framebuffer, view_pixels.frag).
TEST(View, VoxelsAndMeshShareOneDepth)
{
    const GridSpec g = unitGrid(16);
    std::vector<Voxel> patch; // x, y in [0, 8), z = 8
    for (uint32_t x = 0; x < 8; ++x)
        for (uint32_t y = 0; y < 8; ++y) patch.push_back({x, y, 8});
    const svo::Octree octree = octreeOf(g, patch);
    svo::TriangleMesh square; // x, y in [3.5, 11.5], at z = 2, inside the grid's box below the patch
    square.positions = {{3.5, 3.5, 2.0}, {11.5, 3.5, 2.0}, {11.5, 11.5, 2.0}, {3.5, 11.5, 2.0}};
    square.triangles = {{0, 1, 2}, {0, 2, 3}};
    svo::gl::OctreeView view(context(), octree, &square);
    ViewLayers layers;
    layers.outlines = false;
    layers.mesh = true;
    const auto grey = [](const uint8_t* p) { return p[0] > 60 && std::abs(int(p[0]) - int(p[1])) < 8; };
    // Pixels of 1 world unit centred on the grid's middle; the image's x runs
    // along +x (from +z) or -x (from -z), its y along -y.
    for (const double side : {1.0, -1.0}) {
        AxisView v(2, {7.5, 7.5, 5.0}, 1.0, 16, 16);
        if (side < 0) {
            v.camera.eye = v.camera.target - Vec3d{0, 0, 100.0};
            v.right = -1.0 * v.right;
        }
        const Image img = view.render(v.camera, 16, 16, layers);
        int greens = 0, greys = 0;
        for (int row = 0; row < 16; ++row)
            for (int col = 0; col < 16; ++col) {
                // The world point under this pixel's centre.
                const double x = 7.5 + (col + 0.5 - 8.0) * (side > 0 ? 1.0 : -1.0), y = 7.5 - (row + 0.5 - 8.0);
                const bool inPatch = x > -0.5 && x < 7.5 && y > -0.5 && y < 7.5;
                const bool inSquare = x > 3.5 && x < 11.5 && y > 3.5 && y < 11.5;
                const uint8_t* p = img.pixel(col, row);
                const bool voxelInFront = side > 0 ? inPatch : inPatch && !inSquare;
                const bool meshInFront = side > 0 ? inSquare && !inPatch : inSquare;
                if (voxelInFront) {
                    EXPECT_TRUE(isGreen(p)) << side << ": " << col << "," << row;
                }
                if (meshInFront) {
                    EXPECT_TRUE(grey(p)) << side << ": " << col << "," << row;
                }
                greens += isGreen(p);
                greys += grey(p);
            }
        EXPECT_EQ(greens, side > 0 ? 64 : 64 - 16) << side; // 4 x 4 of the patch behind the square from below
        EXPECT_EQ(greys, side > 0 ? 64 - 16 : 64) << side;
    }
}

/// A Context that adopts the context current on the thread (as svo view's
/// window does with its own) draws what a Context of its own draws, makes
/// the adopted context current again wherever it is used, and leaves it alive.
TEST(View, AdoptedContextDrawsTheSameAndIsMadeCurrentAgain)
{
    EXPECT_THROW(
        [] {
            svo::gl::ContextOptions o;
            o.adoptCurrent = true;
            svo::gl::Context nothingCurrent(o);
        }(),
        svo::Error);

    const svo::TriangleMesh mesh = svo::cornellBox();
    const GridSpec g = svo::makeGrid(mesh, svo::GridRequest{24, 0});
    svo::Voxelizer voxelizer;
    const svo::Octree octree = voxelizer.voxelize(mesh, g);
    const ViewCamera camera = svo::gl::frameBox(svo::gl::gridWorldBox(g), Vec3d{-0.4, -0.5, -1.0}, false, 1.0);
    const Image own = svo::gl::OctreeView(context(), octree).render(camera, 96, 96);

    svo::gl::Context host; // stands in for a window's context
    std::optional<svo::gl::Context> adopted;
    {
        const svo::gl::Context::Scope current(host);
        svo::gl::ContextOptions o;
        o.adoptCurrent = true;
        adopted.emplace(o);
    }
    EXPECT_TRUE(adopted->info().adopted);
    EXPECT_EQ(adopted->info().renderer, host.info().renderer);
    // Used with nothing current, and with another context current.
    svo::gl::OctreeView view(*adopted, octree);
    EXPECT_EQ(view.render(camera, 96, 96).rgba, own.rgba);
    {
        const svo::gl::Context::Scope other(context());
        EXPECT_EQ(view.render(camera, 96, 96).rgba, own.rgba);
    }
    const auto times = view.timeFrames(camera, 96, 96, {}, 3);
    ASSERT_EQ(times.size(), 3u);
    for (const auto& t : times) EXPECT_TRUE(t.gpuMs > 0 && t.wallMs > 0);
    EXPECT_THROW(view.timeFrames(camera, 96, 96, {}, 0), svo::Error);
}

/// Voxels coloured by an attribute channel show, at each voxel's projected
/// centre in an axis view (lit 1.0 there), exactly that voxel's value:
/// colours as they are, normals as 0.5 + 0.5 n. The values go in voxel order
/// (bricks by index, bits in order), which the shader finds by rank.
TEST(View, AttributeColoursAreEachVoxelsOwnValue)
{
    const GridSpec g = unitGrid(24);
    // One voxel per (x, y) column, spread over several bricks and within them.
    std::vector<Voxel> voxels;
    for (uint32_t x = 1; x < 23; x += 3)
        for (uint32_t y = 2; y < 23; y += 4) voxels.push_back({x, y, (x * 7 + y * 3) % 24});
    svo::Octree octree = octreeOf(g, voxels);
    std::vector<std::array<uint32_t, 3>> origin(octree.bricks.size());
    for (const svo::BrickRef& b : svo::occupiedBricks(octree)) origin[b.index] = b.origin;
    auto value = [](const Voxel& v) { return svo::Vec3f{v[0] / 24.0f, v[1] / 24.0f, 1.0f - v[2] / 24.0f}; };
    std::map<Voxel, svo::Vec3f> expected;
    for (size_t i = 0; i < octree.bricks.size(); ++i)
        for (uint32_t bit = 0; bit < 512; ++bit)
            if (octree.bricks[i].words[bit >> 6] >> (bit & 63) & 1) {
                const Voxel v{origin[i][0] + (bit >> 6), origin[i][1] + (bit >> 3 & 7), origin[i][2] + (bit & 7)};
                octree.attributes.colors.push_back(value(v));
                octree.attributes.normals.push_back({2 * value(v).x - 1, 2 * value(v).y - 1, 2 * value(v).z - 1});
                expected[v] = value(v);
            }
    ASSERT_EQ(expected.size(), voxels.size());

    svo::gl::OctreeView view(context(), octree);
    const AxisView axis(2, Vec3d{12, 12, 12}, 0.25, 104, 104); // 4 pixels per voxel, looking down -z
    for (const svo::gl::VoxelColor mode : {svo::gl::VoxelColor::Color, svo::gl::VoxelColor::Normal}) {
        ViewLayers l;
        l.outlines = false;
        l.voxelColor = mode;
        const Image image = view.render(axis.camera, axis.width, axis.height, l);
        for (const auto& [v, c] : expected) {
            const auto q = axis.project(Vec3d{double(v[0]), double(v[1]), double(v[2])});
            const uint8_t* p = image.pixel(int(q[0]), int(q[1]));
            for (int i = 0; i < 3; ++i)
                EXPECT_NEAR(p[i], 255.0 * c[i], 1.01) << "voxel " << v[0] << "," << v[1] << "," << v[2];
        }
    }
    ViewLayers triangles;
    triangles.voxelColor = svo::gl::VoxelColor::Triangle;
    EXPECT_THROW(view.render(axis.camera, 16, 16, triangles), svo::Error); // no triangle channel

    // The bricks layer: brick boxes in their own colour, with or without the outlines.
    ViewLayers bricks;
    bricks.voxels = bricks.outlines = false;
    bricks.bricks = true;
    const Image b = view.render(axis.camera, axis.width, axis.height, bricks);
    // Here the bricks fill the grid, so their boxes project to the lines
    // x, y = 8k - 1/2 (world) for k = 0..3: 4 + 4 lines 96 pixels long.
    std::vector<double> lines;
    for (int k = 0; k <= 3; ++k) lines.push_back(8.0 * k - 0.5);
    size_t yellow = 0, offLine = 0;
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
            const uint8_t* p = b.pixel(x, y);
            if (!(p[0] > 200 && p[1] > 170 && p[2] < 60)) continue;
            ++yellow;
            bool near = false;
            for (double w : lines) {
                const auto q = axis.project(Vec3d{w, w, 0});
                near |= std::abs(x + 0.5 - q[0]) < 1.5 || std::abs(y + 0.5 - q[1]) < 1.5;
            }
            offLine += !near;
        }
    EXPECT_EQ(octree.bricks.size(), 27u);
    EXPECT_GT(yellow, 700u);
    EXPECT_EQ(offLine, 0u);
}

/// Green-channel AO at a pixel of an axis view, where the face light is 1.
double aoAt(const Image& image, int x, int y) { return image.pixel(x, y)[1] / (255.0 * svo::gl::ViewColors::voxel[1]); }

/// Ambient occlusion from cones through the opacity volume and through the
/// octree. The analytic answers: an open plane is unoccluded (AO 1) and the
/// floor of a closed box fully occluded (AO 0). Cone samples never reach
/// the surface's own texels or cells, so the plane is exactly 1 with every
/// source. On the box's floor the cones leak where a sample holds only part
/// of a wall: with the octree's cells at a corner, where the step carries the
/// cone past it (stated bias 0.05 with the Max filter, 0.2 with the Average
/// one; measured 0.03 and 0.15); with the volume, where a coarse texel holds
/// the wall and the empty space beyond the room, and trilinear samples of a
/// wall one voxel thick composite to less than 1 (stated bias 0.35; measured
/// 0.23 to 0.29). bench/results has the error against a path-traced
/// reference, where the volume is the closer of the two.
TEST(View, AmbientOcclusionOfAnOpenPlaneAndInsideAClosedBox)
{
    using Filter = svo::gl::AmbientOcclusion::Filter;
    using Source = svo::gl::AmbientOcclusion::Source;
    const GridSpec g = unitGrid(64);
    std::vector<Voxel> plane;
    for (uint32_t x = 8; x < 56; ++x)
        for (uint32_t y = 8; y < 56; ++y) plane.push_back({x, y, 20});
    svo::gl::OctreeView planeView(context(), octreeOf(g, plane));
    const AxisView above(2, Vec3d{32.1, 32.1, 20}, 0.5, 64, 64); // looking down -z at the plane's top

    // A closed box of 1-voxel walls, [10, 50]^3; the camera inside, under the
    // ceiling, looking down at the floor.
    std::vector<Voxel> box;
    for (uint32_t a = 10; a <= 50; ++a)
        for (uint32_t b = 10; b <= 50; ++b)
            for (uint32_t wall : {10u, 50u}) {
                box.push_back({wall, a, b});
                box.push_back({a, wall, b});
                box.push_back({a, b, wall});
            }
    std::sort(box.begin(), box.end());
    box.erase(std::unique(box.begin(), box.end()), box.end());
    svo::gl::OctreeView boxView(context(), octreeOf(g, box));
    ViewCamera inside; // perspective: the near plane is just in front of the eye
    inside.target = {30.1, 30.1, 11};
    inside.eye = {30.1, 30.1, 46};
    inside.fovYDegrees = 50;

    ViewLayers l;
    l.outlines = false;
    l.ao.distance = 64;
    l.ao.offset = 2;
    const std::pair<Source, Filter> opacities[] = {
        {Source::Volume, Filter::Max}, {Source::Octree, Filter::Average}, {Source::Octree, Filter::Max}};
    for (const auto& [source, filter] : opacities)
        for (const int cones : {1, 3, 7, 16}) {
            l.ao.cones = cones;
            l.ao.source = source;
            l.ao.filter = filter;
            const std::string what = fmt::format("{} cones, {}", cones,
                                                 source == Source::Volume ? "volume"
                                                 : filter == Filter::Max  ? "octree, max"
                                                                          : "octree, average");
            const Image lit = planeView.render(above.camera, 64, 64, l);
            double lowest = 1;
            for (int y = 16; y < 48; ++y)
                for (int x = 16; x < 48; ++x) lowest = std::min(lowest, aoAt(lit, x, y));
            EXPECT_GT(lowest, 0.99) << "an open plane, " << what;
            const Image dark = boxView.render(inside, 60, 60, l);
            double highest = 0;
            for (int y = 5; y < 55; ++y)
                for (int x = 5; x < 55; ++x) highest = std::max(highest, aoAt(dark, x, y));
            EXPECT_LT(highest, source == Source::Volume ? 0.35 : filter == Filter::Average ? 0.2 : 0.05)
                << "the floor of a closed box, " << what;
        }
    // Finer steps keep both answers (the plane's exactly, the box's within
    // its bias).
    l.ao.step = 0.25;
    for (const Source source : {Source::Volume, Source::Octree}) {
        l.ao.source = source;
        l.ao.filter = Filter::Max;
        EXPECT_GT(aoAt(planeView.render(above.camera, 64, 64, l), 32, 32), 0.99);
        const Image dark = boxView.render(inside, 60, 60, l);
        EXPECT_LT(aoAt(dark, 30, 30), source == Source::Volume ? 0.35 : 0.05);
    }
    l.ao.step = 1.5;
    EXPECT_THROW(planeView.render(above.camera, 8, 8, l), svo::Error);
    l.ao.step = 0.5;
    // A grid wider than 8 texels a side per texel of the volume: the error
    // names both ways out; the octree's opacity needs no volume.
    GridSpec wide = unitGrid(8);
    wide.dims = {4096, 8, 8};
    svo::gl::OctreeView wideView(context(), octreeOf(wide, {{4000, 1, 1}}));
    l.ao.source = Source::Volume;
    try {
        wideView.render(above.camera, 8, 8, l);
        ADD_FAILURE() << "a 4096-wide grid with a 256 volume drew AO";
    } catch (const svo::Error& e) {
        EXPECT_NE(std::string(e.what()).find("AmbientOcclusion::Source::Octree"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("AmbientOcclusion::volumeResolution"), std::string::npos) << e.what();
    }
    l.ao.volumeResolution = 512;
    EXPECT_NO_THROW(wideView.render(above.camera, 8, 8, l));
    l.ao.volumeResolution = 256;
    l.ao.source = Source::Octree;
    EXPECT_NO_THROW(wideView.render(above.camera, 8, 8, l));
    l.ao.source = Source::Octree;
    // AO alone: grey, the value that scales the lit voxel colour (at the
    // pixel where the Average filter leaks most, so that it is not 0).
    l.ao.cones = 7;
    l.ao.filter = Filter::Average;
    const Image lit = boxView.render(inside, 60, 60, l);
    int px = 0, py = 0;
    for (int y = 5; y < 55; ++y)
        for (int x = 5; x < 55; ++x)
            if (aoAt(lit, x, y) > aoAt(lit, px, py)) px = x, py = y;
    ASSERT_GT(aoAt(lit, px, py), 0.05);
    l.ao.only = true;
    const Image grey = boxView.render(inside, 60, 60, l);
    EXPECT_EQ(grey.pixel(px, py)[0], grey.pixel(px, py)[1]);
    EXPECT_EQ(grey.pixel(px, py)[2], grey.pixel(px, py)[1]);
    EXPECT_NEAR(grey.pixel(px, py)[1] / 255.0, aoAt(lit, px, py), 0.01);
    l.ao.cones = 0;
    EXPECT_THROW(boxView.render(inside, 8, 8, l), svo::Error); // AO alone needs cones
    l.ao.only = false;
    EXPECT_NEAR(aoAt(planeView.render(above.camera, 64, 64, l), 32, 32), 1.0, 0.01); // no cones, no AO
    l.ao.cones = 17;
    EXPECT_THROW(boxView.render(inside, 8, 8, l), svo::Error);
}

/// Interleaved cones (AmbientOcclusion::interleave) average a pixel's AO
/// over the 4x4 window around it, on its own surface only. A plate one voxel
/// thick, 10 voxels over a floor, seen from above: the plate's top is an
/// open plane (AO exactly 1 at every pixel, the analytic answer), although
/// the windows of its border pixels hold floor pixels that the plate
/// occludes; a blur across the depth step would darken them. Without
/// interleaving the plate is 1 as well, and the floor beside it is dark in
/// both.
TEST(View, InterleavedAoIsNotAveragedAcrossADepthStep)
{
    const GridSpec g = unitGrid(64);
    std::vector<Voxel> voxels;
    for (uint32_t x = 4; x < 60; ++x)
        for (uint32_t y = 4; y < 60; ++y) voxels.push_back({x, y, 10});
    for (uint32_t x = 20; x < 44; ++x)
        for (uint32_t y = 20; y < 44; ++y) voxels.push_back({x, y, 20});
    svo::gl::OctreeView view(context(), octreeOf(g, voxels));
    const AxisView above(2, Vec3d{32, 32, 20}, 0.5, 128, 128); // 2 pixels a voxel, looking down -z
    ViewLayers l;
    l.outlines = false;
    l.ao.cones = 7;
    l.ao.distance = 32;
    for (const bool interleave : {true, false}) {
        l.ao.interleave = interleave;
        const Image image = view.render(above.camera, 128, 128, l);
        // The plate covers [19.5, 43.5) in x and y (a voxel's box is its index
        // +- 1/2); at 2 pixels a voxel, the picture's centre at 32, pixel
        // centres from the left x + 1/2 and from the top y + 1/2: columns 39
        // to 86 and rows 41 to 88. Its border pixels, 4 deep, and the floor's
        // 4 pixels beside its left and right borders.
        double plateLowest = 1, floorHighest = 0;
        for (int a = 0; a < 4; ++a)
            for (int b = 50; b < 80; ++b)
                for (const auto& [x, y] : {std::pair{39 + a, b}, std::pair{86 - a, b}, std::pair{b, 41 + a},
                                           std::pair{b, 88 - a}})
                    plateLowest = std::min(plateLowest, aoAt(image, x, y));
        for (int a = 1; a <= 4; ++a)
            for (int y = 56; y < 72; ++y)
                floorHighest = std::max({floorHighest, aoAt(image, 39 - a, y), aoAt(image, 86 + a, y)});
        EXPECT_GT(plateLowest, 0.99) << (interleave ? "interleaved" : "fixed");
        EXPECT_LT(floorHighest, 0.85) << (interleave ? "interleaved" : "fixed");
    }
}

TEST(View, BadCamerasAndSizesThrow)
{
    const GridSpec g = unitGrid(16);
    svo::gl::OctreeView view(context(), octreeOf(g, {{1, 2, 3}}));
    ViewCamera c;
    c.eye = c.target = {1, 1, 1};
    EXPECT_THROW(view.render(c, 16, 16), svo::Error);
    c.eye = {1, 5, 1};
    EXPECT_THROW(view.render(c, 16, 16), svo::Error); // up along the view
    c.eye = {1, 1, 5};
    EXPECT_THROW(view.render(c, 0, 16), svo::Error);
    EXPECT_NO_THROW(view.render(c, 16, 16));
}

} // namespace

namespace {

using Coords = std::set<std::array<int64_t, 3>>;

/// The voxels of a loaded octree in the file's index coordinates.
Coords indexCoords(const svo::Octree& octree)
{
    Coords out;
    for (uint64_t k : svo::octreeKeys(octree)) {
        const auto v = svo::unpackVoxelKey(k);
        out.insert({octree.grid.anchor[0] + v[0], octree.grid.anchor[1] + v[1], octree.grid.anchor[2] + v[2]});
    }
    return out;
}

template <typename TreeT>
Coords activeCoords(const TreeT& tree)
{
    Coords out;
    for (auto it = tree.cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue()) {
            ADD_FAILURE() << "an active tile where voxels were expected";
            continue;
        }
        out.insert({it.getCoord().x(), it.getCoord().y(), it.getCoord().z()});
    }
    return out;
}

std::string writeGrid(const svo::test::TempDir& dir, const std::string& name, openvdb::GridBase::Ptr grid)
{
    openvdb::io::File file(dir.path(name));
    file.write({grid});
    file.close();
    return dir.path(name);
}

} // namespace

TEST(View, LevelSetIsDrawnAtItsZeroCrossing)
{
    openvdb::initialize();
    const svo::test::TempDir dir("view_zero");
    auto ls = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(6.3f, openvdb::Vec3f(0.3f, -0.2f, 0.45f), 0.5f, 3.0f);
    ls->setName("surface");
    const std::string path = writeGrid(dir, "sphere.vdb", ls);

    // OpenVDB's answer: the interior (values below zero) less its face
    // erosion, of the band's voxels.
    auto interior = openvdb::tools::sdfInteriorMask(*ls);
    auto eroded = interior->deepCopy();
    openvdb::tools::erodeActiveValues(eroded->tree(), 1, openvdb::tools::NN_FACE, openvdb::tools::EXPAND_TILES);
    interior->tree().topologyDifference(eroded->tree());
    interior->tree().topologyIntersection(ls->tree());
    interior->tree().voxelizeActiveTiles();
    const Coords expected = activeCoords(interior->tree());

    svo::Voxelizer voxelizer;
    const svo::LoadedOctree shown =
        svo::loadOctree(voxelizer, path, "", {}, {}, svo::FieldVoxels::ZeroCrossing);
    EXPECT_EQ(shown.fieldVoxels, ls->activeVoxelCount());
    const Coords got = indexCoords(shown.octree);
    EXPECT_GT(expected.size(), 1000u);
    EXPECT_LT(expected.size(), ls->activeVoxelCount() / 3); // a shell, not the band's six voxels across
    EXPECT_TRUE(got == expected) << got.size() << " voxels drawn, " << expected.size() << " at the zero crossing";

    // Every drawn voxel lies within a voxel's diagonal of the sphere.
    for (const auto& c : got) {
        const openvdb::Vec3d w = ls->indexToWorld(openvdb::Vec3d(double(c[0]), double(c[1]), double(c[2])));
        EXPECT_LT(std::abs((w - openvdb::Vec3d(0.3, -0.2, 0.45)).length() - 6.3), 0.5 * std::sqrt(3.0) + 1e-6);
    }
    // Beside a grid that sorts first by name (an .nvdb level set's
    // closest_triangle), the level set is still the one drawn.
    auto closest = openvdb::Int32Grid::create(-1);
    closest->setTransform(ls->transform().copy());
    closest->tree().topologyUnion(ls->tree());
    closest->setName("closest_triangle");
    const std::string both = dir.path("both.vdb");
    {
        openvdb::io::File file(both);
        file.write({ls, closest});
    }
    const svo::LoadedOctree beside = svo::loadOctree(voxelizer, both, "", {}, {}, svo::FieldVoxels::ZeroCrossing);
    EXPECT_TRUE(indexCoords(beside.octree) == expected) << indexCoords(beside.octree).size() << " voxels drawn";
    // Asked for the active voxels (svo info, convert), the whole band.
    const svo::LoadedOctree band = svo::loadOctree(voxelizer, path, "", {}, {});
    EXPECT_EQ(band.fieldVoxels, 0u);
    EXPECT_EQ(band.octree.voxelCount(), ls->activeVoxelCount());
}

TEST(View, UnsignedFieldIsDrawnWithinHalfAVoxel)
{
    openvdb::initialize();
    const svo::test::TempDir dir("view_udf");
    // The distance to the plane z = 0.2 * h over a 11 x 11 x 7 block, h = 0.25:
    // centres at index z = 0 are 0.2 h from it, all others 0.8 h or more.
    const double h = 0.25;
    auto udf = openvdb::FloatGrid::create(float(4 * h)); // beyond every value below
    udf->setTransform(openvdb::math::Transform::createLinearTransform(h));
    udf->setName("distance");
    auto fog = openvdb::FloatGrid::create(0.0f);
    fog->setTransform(udf->transform().copy());
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    fog->setName("density");
    Coords plane;
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            for (int z = -3; z <= 3; ++z) {
                const float d = float(h * std::abs(z - 0.2));
                udf->tree().setValue({x, y, z}, d);
                fog->tree().setValue({x, y, z}, d);
                if (z == 0) plane.insert({x, y, z});
            }
    EXPECT_EQ(svo::vdb::distanceKind(*udf), svo::vdb::DistanceKind::Unsigned);
    EXPECT_EQ(svo::vdb::distanceKind(*fog), svo::vdb::DistanceKind::None);
    svo::Voxelizer voxelizer;
    const svo::LoadedOctree u = svo::loadOctree(voxelizer, writeGrid(dir, "udf.vdb", udf), "", {}, {},
                                                svo::FieldVoxels::ZeroCrossing);
    EXPECT_TRUE(indexCoords(u.octree) == plane) << indexCoords(u.octree).size() << " voxels drawn";
    EXPECT_EQ(u.fieldVoxels, 11u * 11u * 7u);
    // A density grid is no distance field: all its active voxels.
    const svo::LoadedOctree f = svo::loadOctree(voxelizer, writeGrid(dir, "fog.vdb", fog), "", {}, {},
                                                svo::FieldVoxels::ZeroCrossing);
    EXPECT_EQ(f.fieldVoxels, 0u);
    EXPECT_EQ(f.octree.voxelCount(), 11u * 11u * 7u);
}

TEST(View, CornellBoxOpensThroughItsOpenFront)
{
    const svo::TriangleMesh room = svo::cornellBox();
    svo::VoxelizeOptions vo;
    vo.attributes = svo::kColors;
    const svo::Octree octree = svo::Voxelizer().voxelize(room, svo::makeGrid(room, svo::GridRequest{64, 0}), vo);
    const int width = 160, height = 120;
    const auto box = svo::gl::gridWorldBox(octree.grid);
    const ViewCamera camera = svo::gl::roomView(box, double(width) / height);
    // In front of the open side (+z), in its middle, looking along -z.
    EXPECT_GT(camera.eye.z, box[1].z);
    EXPECT_NEAR(camera.eye.x, 0.5 * (box[0].x + box[1].x), 1e-12);
    EXPECT_NEAR(camera.eye.y, 0.5 * (box[0].y + box[1].y), 1e-12);
    EXPECT_EQ(camera.target.x, camera.eye.x);
    EXPECT_EQ(camera.target.y, camera.eye.y);

    svo::gl::OctreeView view(context(), octree, &room);
    ViewLayers layers;
    layers.outlines = false;
    layers.voxelColor = svo::gl::VoxelColor::Color;
    const Image image = view.render(camera, width, height, layers);
    // The red wall (x = -1) fills a band of the left third, the green one
    // (x = +1) of the right third, and neither colour strays to the other
    // side. A wall's pixel is its colour shaded by the face light: a channel
    // at least twice each other one (the walls' reflectances differ 3 to 12
    // times, white and the bluish grey background less than 2).
    const auto dominant = [](const uint8_t* p, int c) {
        return p[c] > 40 && p[c] > 2 * p[(c + 1) % 3] && p[c] > 2 * p[(c + 2) % 3];
    };
    size_t red[3] = {}, green[3] = {};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const int third = 3 * x / width;
            red[third] += dominant(image.pixel(x, y), 0);
            green[third] += dominant(image.pixel(x, y), 1);
        }
    const size_t thirdPixels = size_t(width / 3) * size_t(height);
    EXPECT_GT(red[0], thirdPixels / 8) << "red in the left third";
    EXPECT_GT(green[2], thirdPixels / 8) << "green in the right third";
    EXPECT_EQ(red[1] + red[2], 0u);
    EXPECT_EQ(green[0] + green[1], 0u);
    // The back wall, white, in the middle of the picture.
    const uint8_t* middle = image.pixel(width / 2, height / 3);
    EXPECT_GT(std::min({middle[0], middle[1], middle[2]}), 120) << int(middle[0]) << "," << int(middle[1]) << "," << int(middle[2]);

    EXPECT_THROW(svo::gl::roomView(box, 1.0, 180.0), svo::InvalidInput);
    EXPECT_THROW(svo::gl::roomView(box, 0.0), svo::InvalidInput);
}

// The window's key table (apps/view_keys.h), which the window presses
// through and `svo view --help` prints: one row an action, no character in
// two rows, letters found in either case, and every row in the help text.

TEST(View, WindowKeysAreOneTable)
{
    using svo::app::kViewKeys;
    std::set<char> seen;
    std::set<int> actions;
    const std::string help = svo::app::viewKeysHelp();
    for (const svo::app::ViewKey& k : kViewKeys) {
        EXPECT_TRUE(actions.insert(int(k.action)).second) << "two rows for one action: " << k.chars;
        for (char c : k.chars) {
            EXPECT_TRUE(seen.insert(c).second) << "'" << c << "' presses two rows";
            EXPECT_EQ(svo::app::viewKeyOf(c), &k);
            if (c >= 'a' && c <= 'z') {
                EXPECT_EQ(svo::app::viewKeyOf(char(c - 'a' + 'A')), &k);
            }
        }
        EXPECT_EQ(&svo::app::viewKeyFor(k.action), &k);
        EXPECT_NE(help.find(svo::app::viewKeyNames(k)), std::string::npos) << help;
        EXPECT_NE(help.find(std::string(k.does)), std::string::npos) << help;
    }
    EXPECT_EQ(actions.size(), size_t(svo::app::ViewAction::Quit) + 1); // every action has a key
    EXPECT_EQ(svo::app::viewKeyOf('!'), nullptr);
    EXPECT_EQ(svo::app::viewKeyLabel("voxels", svo::app::ViewAction::Voxels), "voxels (V)");
}
