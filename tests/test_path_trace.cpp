// The path-traced lighting reference (svo/reference) against analytic
// answers: exact where the estimator is exact, else within 5 standard errors
// derived from the sample count (docs/lighting_reference.md says why each).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <limits>

#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/reference/ambient_occlusion.h"
#include "svo/reference/path_trace.h"

using namespace svo;
using namespace svo::reference;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

double len(const Vec3d& a) { return std::sqrt(dot(a, a)); }
Vec3d unit(const Vec3d& a) { return (1.0 / len(a)) * a; }

// Appends the quad a b c d (two triangles, a-b-c and a-c-d).
void addQuad(TriangleMesh& m, Vec3d a, Vec3d b, Vec3d c, Vec3d d)
{
    const auto i = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c, d});
    m.triangles.push_back({i, i + 1, i + 2});
    m.triangles.push_back({i, i + 2, i + 3});
}

// A horizontal square at height z, half side s, centred on (cx, cy).
TriangleMesh plane(double s, double z = 0, double cx = 0, double cy = 0)
{
    TriangleMesh m;
    m.source = "plane";
    addQuad(m, {cx - s, cy - s, z}, {cx + s, cy - s, z}, {cx + s, cy + s, z}, {cx - s, cy + s, z});
    return m;
}

// The closed box [lo, hi]: six quads sharing its 8 corners (so edges are shared).
TriangleMesh box(Vec3d lo, Vec3d hi)
{
    TriangleMesh m;
    m.source = "box";
    for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    const uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : q) {
        m.triangles.push_back({f[0], f[1], f[2]});
        m.triangles.push_back({f[0], f[2], f[3]});
    }
    return m;
}

Camera topDown(double height, Vec3d centre = {0, 0, 0})
{
    Camera c;
    c.eye = centre + Vec3d{0, 0, 10};
    c.target = centre;
    c.up = {0, 1, 0};
    c.orthographic = true;
    c.height = height;
    return c;
}

// The cosine-weighted solid angle fraction (1/pi) ∫ cos dω that a polygon
// above the horizon of (origin, unit n) covers: Lambert's formula,
// (1/2pi) Σ angle(v_i, v_i+1) n · unit(v_i × v_i+1), its sign by winding.
double polygonFormFactor(const std::vector<Vec3d>& corners, Vec3d origin, Vec3d n)
{
    double sum = 0;
    for (size_t i = 0; i < corners.size(); ++i) {
        const Vec3d a = corners[i] - origin, b = corners[(i + 1) % corners.size()] - origin;
        const Vec3d c = cross(a, b);
        const double angle = std::atan2(len(c), dot(a, b));
        sum += angle * dot(n, unit(c));
    }
    return std::abs(sum) / (2 * kPi);
}

bool sameBytes(const FloatImage& a, const FloatImage& b)
{
    return a.width == b.width && a.height == b.height && a.channels == b.channels && a.covered == b.covered &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

} // namespace

// --- the camera ------------------------------------------------------------

TEST(PathTraceCamera, PixelCentresFollowTheGlView)
{
    Camera c;
    c.eye = {0, 0, 5};
    c.target = {0, 0, 0};
    c.fovYDegrees = 90; // tan(45°) = 1
    // 3 x 3: pixel (1, 1) is the centre, along forward.
    const Ray centre = cameraRay(c, 3, 3, 1, 1);
    EXPECT_NEAR(centre.direction.z, -1.0, 1e-15);
    // Top left: ndc (-2/3, +2/3); right = +x, image up = +y, rows from the top.
    const Ray tl = cameraRay(c, 3, 3, 0, 0);
    const Vec3d expected = unit({-2.0 / 3.0, 2.0 / 3.0, -1.0});
    EXPECT_NEAR(tl.direction.x, expected.x, 1e-15);
    EXPECT_NEAR(tl.direction.y, expected.y, 1e-15);
    EXPECT_NEAR(tl.direction.z, expected.z, 1e-15);
    // Aspect widens x: 6 x 3, pixel (0, 1) at ndc.x = -5/6, times aspect 2.
    const Ray wide = cameraRay(c, 6, 3, 0, 1);
    EXPECT_NEAR(wide.direction.x / -wide.direction.z, -5.0 / 6.0 * 2.0, 1e-14);

    // Orthographic: 4 x 2 pixels over height 2 (width 4); pixel (0, 0) at (-1.5, 0.5).
    c.orthographic = true;
    c.height = 2;
    const Ray o = cameraRay(c, 4, 2, 0, 0);
    EXPECT_NEAR(o.origin.x, -1.5, 1e-15);
    EXPECT_NEAR(o.origin.y, 0.5, 1e-15);
    EXPECT_EQ(o.origin.z, 5.0);
    EXPECT_EQ(o.direction.z, -1.0);
}

// The GL view's own matrices (gl/view/src/octree_view.cpp's cellCamera: view,
// then a perspective or orthographic projection, column-major) project every
// point of the reference's ray for pixel (x, y) to the NDC of the fragment
// at gl_FragCoord = (x + 1/2, height - 1 - y + 1/2): the same ray.
TEST(PathTraceCamera, RaysProjectToTheGlFragmentCentre)
{
    for (bool orthographic : {false, true}) {
        Camera c;
        c.eye = {1.5, -2, 4};
        c.target = {0.2, 0.1, -0.3};
        c.up = {0.1, 1, 0.2};
        c.orthographic = orthographic;
        c.fovYDegrees = 55;
        c.height = 3.5;
        const int w = 7, h = 5;
        const Vec3d f = unit(c.target - c.eye), r = unit(cross(f, c.up)), u = cross(r, f);
        const double view[16] = {r.x, u.x, -f.x, 0, r.y, u.y, -f.y, 0, r.z, u.z, -f.z, 0,
                                 -dot(r, c.eye), -dot(u, c.eye), dot(f, c.eye), 1};
        const double aspect = double(w) / h, n = 0.5, fa = 50;
        double proj[16] = {};
        if (orthographic) {
            const double hh = c.height, ww = hh * aspect;
            const double o[16] = {2 / ww, 0, 0, 0, 0, 2 / hh, 0, 0, 0, 0, -2 / (fa - n), 0, 0, 0, -(fa + n) / (fa - n), 1};
            std::copy(o, o + 16, proj);
        } else {
            const double t = 1.0 / std::tan(c.fovYDegrees * kPi / 360.0);
            const double p[16] = {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0};
            std::copy(p, p + 16, proj);
        }
        auto apply = [](const double* m, const double v[4], double out[4]) {
            for (int row = 0; row < 4; ++row) {
                out[row] = 0;
                for (int k = 0; k < 4; ++k) out[row] += m[k * 4 + row] * v[k];
            }
        };
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const Ray ray = cameraRay(c, w, h, x, y);
                const double fragX = x + 0.5, fragY = (h - 1 - y) + 0.5;
                for (double s : {1.0, 4.0, 20.0}) {
                    const Vec3d q = ray.origin + s * ray.direction;
                    const double world[4] = {q.x, q.y, q.z, 1};
                    double eye[4], clip[4];
                    apply(view, world, eye);
                    apply(proj, eye, clip);
                    EXPECT_NEAR((clip[0] / clip[3] + 1) / 2 * w, fragX, 1e-9) << x << ", " << y;
                    EXPECT_NEAR((clip[1] / clip[3] + 1) / 2 * h, fragY, 1e-9) << x << ", " << y;
                }
            }
    }
}

// --- white furnace -----------------------------------------------------------

// Inside a closed sphere whose every triangle emits Le and reflects albedo a,
// radiance is Le (1 + a + a² + ...) = Le / (1 - a) everywhere. With Russian
// roulette continuing with probability q = a and weight a / q = 1, a path's
// estimate is Le times its vertex count N, 1 + a geometric count: the mean is
// Le / (1 - a) and the standard deviation of one sample Le sqrt(a) / (1 - a).
TEST(PathTraceFurnace, ClosedSphereFromInside)
{
    const Vec3d centre{100, -50, 20}; // off the origin: the local frame at work
    const TriangleMesh sphere = icosphere(centre, 1.0, 3);
    const double le = 0.25;
    for (double a : {0.0, 0.5, 0.8}) {
        Material material;
        material.albedo = {a, a, a};
        material.emission.assign(sphere.triangles.size(), {le, le, le});
        const Scene scene(sphere, material);
        Camera camera;
        camera.eye = centre;
        camera.target = centre + Vec3d{0.3, -0.2, -1};
        camera.fovYDegrees = 100;
        RenderOptions options;
        options.mode = Mode::Full;
        options.samples = 256;
        options.seed = 11;
        const int w = 16, h = 16;
        const FloatImage image = render(scene, camera, w, h, {}, options);
        const double expected = le / (1 - a);
        const double sigma = le * std::sqrt(a) / (1 - a);
        const double pixelTol = 5 * sigma / std::sqrt(options.samples) + 1e-6 * expected;
        const double meanTol = 5 * sigma / std::sqrt(double(options.samples) * w * h) + 1e-6 * expected;
        double sum = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                ASSERT_TRUE(image.covered[size_t(y) * w + x]);
                const float v = image.at(x, y, 0);
                EXPECT_EQ(v, image.at(x, y, 1)); // grey in, grey out, bit for bit
                EXPECT_EQ(v, image.at(x, y, 2));
                EXPECT_NEAR(v, expected, pixelTol) << "a = " << a << " pixel " << x << ", " << y;
                sum += v;
            }
        std::printf("furnace a = %.1f: mean %.6f, expected %.6f, tolerance %.6f\n", a, sum / (w * h), expected, meanTol);
        EXPECT_NEAR(sum / (w * h), expected, meanTol) << "a = " << a;
    }
}

// The furnace's other form: a convex object under a constant sky Lenv.
// Every reflected ray leaves a convex surface for the sky, so a surface's
// radiance is a Lenv: exactly so in Direct and OneBounce (each sample is
// a Lenv), and in Full a Bernoulli(a) times Lenv per sample (roulette with
// q = a), standard deviation Lenv sqrt(a (1 - a)). Pixels that miss see Lenv.
TEST(PathTraceFurnace, ConvexObjectUnderConstantSky)
{
    const Vec3d centre{-3e3, 2e3, 5e2};
    const TriangleMesh sphere = icosphere(centre, 2.0, 3);
    const double a = 0.6, sky = 2.0;
    Material material;
    material.albedo = {a, a, a};
    const Scene scene(sphere, material);
    Lighting lights;
    lights.environment = {sky, sky, sky};
    Camera camera;
    camera.eye = centre + Vec3d{1, 2, 9};
    camera.target = centre;
    camera.fovYDegrees = 35;
    const int w = 24, h = 24;
    RenderOptions options;
    options.samples = 64;
    for (Mode mode : {Mode::Direct, Mode::OneBounce}) {
        options.mode = mode;
        const FloatImage image = render(scene, camera, w, h, lights, options);
        int covered = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const bool hit = image.covered[size_t(y) * w + x];
                covered += hit;
                EXPECT_NEAR(image.at(x, y), hit ? a * sky : sky, 1e-6) << x << ", " << y;
            }
        EXPECT_GT(covered, w * h / 4);
        EXPECT_LT(covered, w * h);
    }
    options.mode = Mode::Full;
    options.samples = 400;
    const FloatImage image = render(scene, camera, w, h, lights, options);
    const double sigma = sky * std::sqrt(a * (1 - a));
    double sum = 0;
    int covered = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!image.covered[size_t(y) * w + x]) {
                EXPECT_EQ(image.at(x, y), float(sky));
                continue;
            }
            ++covered;
            sum += image.at(x, y);
            EXPECT_NEAR(image.at(x, y), a * sky, 5 * sigma / std::sqrt(options.samples)) << x << ", " << y;
        }
    std::printf("sky furnace: mean %.6f over %d pixels, expected %.6f\n", sum / covered, covered, a * sky);
    EXPECT_NEAR(sum / covered, a * sky, 5 * sigma / std::sqrt(double(options.samples) * covered));
}

// --- ambient occlusion --------------------------------------------------------

TEST(PathTraceAo, OpenPlaneIsOne)
{
    const Scene scene(plane(10, 0, 1e4, -1e4));
    AmbientOcclusionOptions options;
    options.samples = 4096;
    EXPECT_EQ(ambientOcclusionAt(scene, {1e4, -1e4, 0}, {0, 0, 1}, options), 1.0);
    EXPECT_EQ(ambientOcclusionAt(scene, {1e4 + 3, -1e4 - 2, 0}, {0, 0, -1}, options), 1.0);

    // The image: every pixel sees the plane, from above and from below (the
    // hemisphere is the one facing the camera).
    RenderOptions ro;
    ro.mode = Mode::AmbientOcclusion;
    ro.samples = 64;
    for (double side : {1.0, -1.0}) {
        Camera camera = topDown(8, {1e4, -1e4, 0});
        camera.eye = Vec3d{1e4, -1e4, 10 * side};
        const FloatImage image = render(scene, camera, 16, 16, {}, ro);
        ASSERT_EQ(image.channels, 1);
        for (size_t i = 0; i < image.pixels.size(); ++i) {
            EXPECT_TRUE(image.covered[i]);
            EXPECT_EQ(image.pixels[i], 1.0f);
        }
    }
}

TEST(PathTraceAo, ClosedBoxFloorIsZero)
{
    const Vec3d c{1e4, 1e4, 1e4}; // far from the origin
    const Scene scene(box(c - Vec3d{1, 1, 1}, c + Vec3d{1, 1, 1}));
    AmbientOcclusionOptions options;
    options.samples = 20000;
    const Vec3d floor = c - Vec3d{0, 1, 0};
    EXPECT_EQ(ambientOcclusionAt(scene, floor, {0, 1, 0}, options), 0.0);
    // Near a corner, where rays graze three faces and two shared edges: still closed.
    EXPECT_EQ(ambientOcclusionAt(scene, c + Vec3d{0.999, -1, 0.999}, {0, 1, 0}, options), 0.0);
    // Within R = 0.9 of the floor's centre there is no wall (the nearest is 1 away).
    options.distance = 0.9;
    EXPECT_EQ(ambientOcclusionAt(scene, floor, {0, 1, 0}, options), 1.0);
}

// A point on the floor facing a wall at distance d, of height h, along y over
// [-L, L]: AO = 1 - F, F the wall's cosine-weighted fraction of the
// hemisphere (Lambert's polygon formula, exact). As L grows F tends to
// (1 - d / sqrt(d² + h²)) / 2: the 2-D form factor of an infinite strip,
// (sin φ2 - sin φ1) / 2 with φ measured from the normal (φ1 = atan(d/h) at
// the top edge, φ2 = 90° at the foot). The estimate is a binomial proportion:
// tolerance 5 sqrt(AO (1 - AO) / n).
TEST(PathTraceAo, PointFacingAWall)
{
    const double d = 1.0, h = 1.5, L = 40;
    TriangleMesh m;
    m.source = "floor and wall";
    addQuad(m, {-50, -L, 0}, {d, -L, 0}, {d, L, 0}, {-50, L, 0});
    const std::vector<Vec3d> wall = {{d, -L, 0}, {d, L, 0}, {d, L, h}, {d, -L, h}};
    addQuad(m, wall[0], wall[1], wall[2], wall[3]);
    const Scene scene(m);
    const double exact = 1 - polygonFormFactor(wall, {0, 0, 0}, {0, 0, 1});
    const double infinite = (1 + d / std::sqrt(d * d + h * h)) / 2;
    EXPECT_NEAR(exact, infinite, 2e-3); // the wall's finite length
    AmbientOcclusionOptions options;
    options.samples = 200000;
    options.seed = 3;
    const double ao = ambientOcclusionAt(scene, {0, 0, 0}, {0, 0, 1}, options);
    std::printf("AO facing a wall: %.6f, exact %.6f, infinite wall %.6f\n", ao, exact, infinite);
    EXPECT_NEAR(ao, exact, 5 * std::sqrt(exact * (1 - exact) / options.samples));

    // Many points at once: point 0 is the single call's, others against their own exact value.
    std::vector<Vec3d> points, normals;
    for (double x : {0.0, -0.5, -2.0, 0.5}) points.push_back({x, 3.0, 0}), normals.push_back({0, 0, 2});
    options.samples = 50000;
    const std::vector<double> many = ambientOcclusionAt(scene, points, normals, options);
    EXPECT_EQ(many[0], ambientOcclusionAt(scene, points[0], normals[0], options));
    for (size_t i = 0; i < points.size(); ++i) {
        const double e = 1 - polygonFormFactor(wall, points[i], {0, 0, 1});
        EXPECT_NEAR(many[i], e, 5 * std::sqrt(e * (1 - e) / options.samples)) << "point " << i;
    }
}

// --- direct light ---------------------------------------------------------------

// A directional light at angle θ on a plane of albedo ρ: ρ/π E cos θ, with no
// randomness at all. A square occluder at height 1 casts its shadow shifted
// by tan θ along the light's travel: 0 there, exactly.
TEST(PathTraceDirect, DirectionalLightAndShadow)
{
    const double theta = 40 * kPi / 180, rho = 0.7;
    TriangleMesh m = plane(5);
    addQuad(m, {-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1});
    Material material;
    material.albedo = {rho, rho, rho};
    const Scene scene(m, material);
    Lighting lights;
    lights.directional.push_back({{std::sin(theta), 0, -std::cos(theta)}, {1, 2, 3}});
    const Camera camera = topDown(6);
    const int n = 48;
    RenderOptions options;
    options.mode = Mode::Direct;
    options.samples = 1;
    RenderStats stats;
    const FloatImage image = render(scene, camera, n, n, lights, options, &stats);
    options.samples = 32; // deterministic: the same image
    EXPECT_TRUE(sameBytes(image, render(scene, camera, n, n, lights, options)));
    EXPECT_EQ(stats.cameraRays, uint64_t(n * n));
    EXPECT_EQ(stats.occlusionRays, uint64_t(n * n));
    EXPECT_EQ(stats.bounceRays, 0u);

    const double shift = std::tan(theta), pixel = 6.0 / n;
    int lit = 0, shadowed = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const Vec3d p = cameraRay(camera, n, n, x, y).origin;
            const bool onOccluder = std::abs(p.x) < 0.5 - pixel && std::abs(p.y) < 0.5 - pixel;
            const bool inShadow = std::abs(p.x - shift) < 0.5 - pixel && std::abs(p.y) < 0.5 - pixel;
            const bool clear = (std::abs(p.x) > 0.5 + pixel || std::abs(p.y) > 0.5 + pixel) &&
                               (std::abs(p.x - shift) > 0.5 + pixel || std::abs(p.y) > 0.5 + pixel);
            for (int c = 0; c < 3; ++c) {
                const double e = rho / kPi * (c + 1) * std::cos(theta);
                if (onOccluder || clear) {
                    EXPECT_NEAR(image.at(x, y, c), e, 1e-6 * e) << x << ", " << y;
                } else if (inShadow) {
                    EXPECT_EQ(image.at(x, y, c), 0.0f) << x << ", " << y;
                }
            }
            lit += onOccluder || clear;
            shadowed += inShadow && !onOccluder;
        }
    EXPECT_GT(shadowed, 20);
    EXPECT_GT(lit, n * n / 2);
}

// A point light I at distance r whose direction makes angle θ with the
// normal: ρ/π I cos θ / r², per pixel, here through a perspective camera.
TEST(PathTraceDirect, PointLightFalloff)
{
    const double rho = 0.5, intensity = 5;
    const Vec3d light{0.3, -0.2, 1.5};
    Material material;
    material.albedo = {rho, rho, rho};
    const Vec3d offset{250, 120, -40};
    const Scene scene(plane(4, offset.z, offset.x, offset.y), material);
    Lighting lights;
    lights.point.push_back({offset + light, {intensity, intensity, intensity}});
    Camera camera;
    camera.eye = offset + Vec3d{-1, -2, 3};
    camera.target = offset;
    camera.up = {0, 0, 1};
    camera.fovYDegrees = 60;
    const int w = 40, h = 30;
    RenderOptions options;
    options.mode = Mode::Direct;
    const FloatImage image = render(scene, camera, w, h, lights, options);
    int checked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Ray ray = cameraRay(camera, w, h, x, y);
            const double t = (offset.z - ray.origin.z) / ray.direction.z;
            const Vec3d p = ray.origin + t * ray.direction - offset;
            if (std::abs(p.x) > 3.9 || std::abs(p.y) > 3.9) continue;
            const Vec3d toLight = light - p;
            const double r2 = dot(toLight, toLight), cosine = toLight.z / std::sqrt(r2);
            const double e = rho / kPi * intensity * cosine / r2;
            EXPECT_NEAR(image.at(x, y, 0), e, 1e-5 * e) << x << ", " << y;
            ++checked;
        }
    EXPECT_GT(checked, w * h / 2);
}

TEST(PathTraceDirect, VertexColoursAreAlbedo)
{
    TriangleMesh m = plane(2);
    m.colors.assign(m.positions.size(), Vec3f{0.2f, 0.4f, 0.6f});
    const Scene scene(m);
    Lighting lights;
    lights.directional.push_back({{0, 0, -3}, {1, 1, 1}});
    const FloatImage image = render(scene, topDown(3), 8, 8, lights, {});
    for (int c = 0; c < 3; ++c) {
        const double e = double(m.colors[0][c]) / kPi;
        EXPECT_NEAR(image.at(4, 4, c), e, 1e-6 * e);
    }
    // Without vertex colours: the constant albedo.
    Material material;
    material.vertexColors = false;
    const FloatImage grey = render(m, material, topDown(3), 8, 8, lights, {});
    EXPECT_NEAR(grey.at(4, 4, 1), 0.5 / kPi, 1e-6);
}

// --- one bounce ---------------------------------------------------------------

// Inside a sphere of radius R with a point light I at its centre: on a
// sphere, direct radiance is L1 = ρ/π I / R² and one bounce adds ρ L1. The
// icosphere's faces lie between p (the least face-plane distance) and R from
// the centre, so the direct radiance of any point lies in
// [ρ/π I p / R³, ρ/π I / p²], and a one-bounce sample, L1(x0) + ρ L1(x1),
// lies in (1 + ρ) times that range: bounds with no Monte Carlo error.
TEST(PathTraceOneBounce, PointLightInsideSphere)
{
    const Vec3d centre{7, 8, 9};
    const double radius = 2, rho = 0.6, intensity = 3;
    const TriangleMesh sphere = icosphere(centre, radius, 4);
    double p = radius;
    for (size_t t = 0; t < sphere.triangles.size(); ++t) {
        const auto c = sphere.corners(t);
        const Vec3d n = unit(cross(c[1] - c[0], c[2] - c[0]));
        p = std::min(p, std::abs(dot(n, c[0] - centre)));
    }
    const double lo = rho / kPi * intensity * p / (radius * radius * radius);
    const double hi = rho / kPi * intensity / (p * p);
    ASSERT_LT(hi / lo, 1.02);
    Material material;
    material.albedo = {rho, rho, rho};
    const Scene scene(sphere, material);
    Lighting lights;
    lights.point.push_back({centre, {intensity, intensity, intensity}});
    Camera camera;
    camera.eye = centre + Vec3d{0.5, 0.5, 0.5};
    camera.target = centre + Vec3d{0.5, 0.3, -1};
    camera.fovYDegrees = 120;
    RenderOptions options;
    options.samples = 16;
    options.mode = Mode::Direct;
    const FloatImage direct = render(scene, camera, 12, 12, lights, options);
    options.mode = Mode::OneBounce;
    const FloatImage bounce = render(scene, camera, 12, 12, lights, options);
    for (size_t i = 0; i < direct.pixels.size(); ++i) {
        EXPECT_GE(direct.pixels[i], lo * (1 - 1e-6));
        EXPECT_LE(direct.pixels[i], hi * (1 + 1e-6));
        EXPECT_GE(bounce.pixels[i], (1 + rho) * lo * (1 - 1e-6));
        EXPECT_LE(bounce.pixels[i], (1 + rho) * hi * (1 + 1e-6));
    }
}

// --- determinism and threads ---------------------------------------------------------

TEST(PathTraceDeterminism, SameSeedSameBytesWhateverTheThreads)
{
    const Scene scene(cornellBox());
    const Bounds b = scene.bounds();
    Camera camera;
    camera.target = 0.5 * (b.min + b.max);
    camera.eye = camera.target + Vec3d{0.35, 0.3, 1.0 * 3.5};
    Lighting lights;
    lights.point.push_back({camera.target + Vec3d{0, 0.8, 0}, {2, 2, 2}});
    lights.directional.push_back({{-0.3, -1, -0.2}, {0.5, 0.5, 0.5}});
    for (Mode mode : {Mode::AmbientOcclusion, Mode::OneBounce, Mode::Full}) {
        RenderOptions options;
        options.mode = mode;
        options.samples = 4;
        options.seed = 7;
        options.aoDistance = 0.5;
        options.threads = 1;
        const FloatImage one = render(scene, camera, 24, 20, lights, options);
        options.threads = 2;
        const FloatImage three = render(scene, camera, 24, 20, lights, options);
        options.threads = 0;
        const FloatImage any = render(scene, camera, 24, 20, lights, options);
        EXPECT_TRUE(sameBytes(one, three)) << int(mode);
        EXPECT_TRUE(sameBytes(one, any)) << int(mode);
        options.seed = 8;
        EXPECT_FALSE(sameBytes(one, render(scene, camera, 24, 20, lights, options))) << int(mode);
    }
    // Points too.
    std::vector<Vec3d> points, normals;
    for (int i = 0; i < 100; ++i) points.push_back({b.min.x + 0.02 * i, b.min.y + 0.01, 0.0}), normals.push_back({0, 1, 0});
    AmbientOcclusionOptions ao;
    ao.samples = 64;
    ao.threads = 1;
    const auto one = ambientOcclusionAt(scene, points, normals, ao);
    ao.threads = 2;
    EXPECT_EQ(one, ambientOcclusionAt(scene, points, normals, ao));
}

// --- bad input ---------------------------------------------------------------

TEST(PathTraceErrors, BadInputIsAnError)
{
    const TriangleMesh m = plane(1);
    const Scene scene(m);
    const Camera good = topDown(2);
    const Lighting none;
    const RenderOptions ro;
    EXPECT_NO_THROW(render(scene, good, 4, 4, none, ro));
    EXPECT_THROW(render(scene, good, 0, 4, none, ro), Error);
    EXPECT_THROW(render(scene, good, 4, -1, none, ro), Error);
    EXPECT_THROW(render(scene, good, 40000, 4, none, ro), Error);
    auto camera = [&](auto change) {
        Camera c = good;
        change(c);
        return c;
    };
    EXPECT_THROW(render(scene, camera([](Camera& c) { c.eye.x = NAN; }), 4, 4, none, ro), Error);
    EXPECT_THROW(render(scene, camera([](Camera& c) { c.target.y = INFINITY; }), 4, 4, none, ro), Error);
    EXPECT_THROW(render(scene, camera([](Camera& c) { c.eye = c.target; }), 4, 4, none, ro), Error);
    EXPECT_THROW(render(scene, camera([](Camera& c) { c.up = {0, 0, 1}; }), 4, 4, none, ro), Error);
    EXPECT_THROW(render(scene, camera([](Camera& c) { c.up = {0, 0, 0}; }), 4, 4, none, ro), Error);
    EXPECT_THROW(render(scene, camera([](Camera& c) { c.height = 0; }), 4, 4, none, ro), Error);
    EXPECT_THROW(render(scene, camera([](Camera& c) { c.orthographic = false, c.fovYDegrees = 180; }), 4, 4, none, ro),
                 Error);
    EXPECT_THROW(cameraRay(good, 4, 4, 4, 0), Error);

    auto options = [&](auto change) {
        RenderOptions o;
        change(o);
        return o;
    };
    EXPECT_THROW(render(scene, good, 4, 4, none, options([](RenderOptions& o) { o.samples = 0; })), Error);
    EXPECT_THROW(render(scene, good, 4, 4, none, options([](RenderOptions& o) { o.threads = -1; })), Error);
    EXPECT_THROW(render(scene, good, 4, 4, none, options([](RenderOptions& o) { o.aoDistance = 0; })), Error);
    EXPECT_THROW(render(scene, good, 4, 4, none, options([](RenderOptions& o) { o.aoDistance = NAN; })), Error);

    auto lights = [&](auto change) {
        Lighting l;
        change(l);
        return l;
    };
    EXPECT_THROW(render(scene, good, 4, 4, lights([](Lighting& l) { l.directional.push_back({{0, 0, 0}, {1, 1, 1}}); }), ro),
                 Error);
    EXPECT_THROW(render(scene, good, 4, 4, lights([](Lighting& l) { l.directional.push_back({{0, 0, -1}, {-1, 1, 1}}); }),
                        ro),
                 Error);
    EXPECT_THROW(render(scene, good, 4, 4, lights([](Lighting& l) { l.point.push_back({{NAN, 0, 0}, {1, 1, 1}}); }), ro),
                 Error);
    EXPECT_THROW(render(scene, good, 4, 4, lights([](Lighting& l) { l.environment = {0, INFINITY, 0}; }), ro), Error);

    Material material;
    material.albedo = {1.5, 0.5, 0.5};
    EXPECT_THROW(Scene(m, material), Error);
    material.albedo = {0.5, NAN, 0.5};
    EXPECT_THROW(Scene(m, material), Error);
    material = {};
    material.emission.assign(1, {1, 1, 1}); // two triangles
    EXPECT_THROW(Scene(m, material), Error);
    material.emission.assign(2, {1, -1, 1});
    EXPECT_THROW(Scene(m, material), Error);
    EXPECT_THROW(Scene(m, {}, -1.0), Error);
    TriangleMesh coloured = m;
    coloured.colors.assign(m.positions.size(), Vec3f{0.5f, 2.0f, 0.5f});
    EXPECT_THROW(Scene(coloured, {}), Error);
    EXPECT_THROW(Scene(TriangleMesh{}, {}), Error);
    EXPECT_THROW(render(TriangleMesh{}, {}, good, 4, 4, none, ro), Error);

    AmbientOcclusionOptions ao;
    EXPECT_THROW(ambientOcclusionAt(scene, {0, 0, 0}, {0, 0, 0}, ao), Error);
    EXPECT_THROW(ambientOcclusionAt(scene, {NAN, 0, 0}, {0, 0, 1}, ao), Error);
    EXPECT_THROW(ambientOcclusionAt(scene, {{0, 0, 0}}, {}, ao), Error);
    ao.distance = -1;
    EXPECT_THROW(ambientOcclusionAt(scene, {0, 0, 0}, {0, 0, 1}, ao), Error);
    ao = {};
    ao.samples = 0;
    EXPECT_THROW(ambientOcclusionAt(scene, {0, 0, 0}, {0, 0, 1}, ao), Error);
}
