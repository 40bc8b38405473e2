#include "svo/reference/scene.h"

#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <limits>
#include <string>

#include "scene_data.h"
#include "svo/core/error.h"
#include "vec_math.h"

namespace svo::reference {

namespace {

// Embree reports errors through a callback; the first one of a call is kept
// here and turned into an svo::Error by the caller.
void recordError(void* user, RTCError code, const char* message)
{
    auto* first = static_cast<std::string*>(user);
    if (first->empty()) *first = fmt::format("Embree error {}: {}", int(code), message ? message : "");
}

bool inUnit(const Vec3d& a) { return finite(a) && nonNegative(a) && a.x <= 1 && a.y <= 1 && a.z <= 1; }

} // namespace

SceneData::~SceneData()
{
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
}

bool SceneData::intersect(const Vec3d& origin, const Vec3d& dir, Surface& hit) const
{
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = float(origin.x), rh.ray.org_y = float(origin.y), rh.ray.org_z = float(origin.z);
    rh.ray.dir_x = float(dir.x), rh.ray.dir_y = float(dir.y), rh.ray.dir_z = float(dir.z);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    // The point again in double, from the corners and the barycentrics: its
    // error is float's relative to the triangle, not to the ray's length.
    const auto& f = triangles[rh.hit.primID];
    const double u = rh.hit.u, v = rh.hit.v, w = 1.0 - u - v;
    const Vec3d &a = positions[f[0]], &b = positions[f[1]], &c = positions[f[2]];
    hit.point = a + u * (b - a) + v * (c - a);
    const Vec3d n = cross(b - a, c - a);
    const double len = length(n);
    // A degenerate triangle Embree still reports (float rounding): face the ray.
    hit.normal = len > 0 ? (1.0 / len) * n : -1.0 * dir;
    if (dot(hit.normal, dir) > 0) hit.normal = -1.0 * hit.normal;
    hit.albedo = colors.empty() ? albedo : w * colors[f[0]] + u * colors[f[1]] + v * colors[f[2]];
    hit.emission = emission.empty() ? Vec3d{} : emission[rh.hit.primID];
    return true;
}

bool SceneData::occluded(const Vec3d& origin, const Vec3d& dir, double tFar) const
{
    if (!(tFar > 0)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = float(origin.x), ray.org_y = float(origin.y), ray.org_z = float(origin.z);
    ray.dir_x = float(dir.x), ray.dir_y = float(dir.y), ray.dir_z = float(dir.z);
    ray.tnear = 0.0f;
    // Rounded down, so a shadow ray never reaches the light's own position.
    float far = float(tFar);
    if (double(far) > tFar) far = std::nextafter(far, 0.0f);
    ray.tfar = far;
    ray.mask = 0xffffffffu;
    rtcOccluded1(scene, &context, &ray);
    return ray.tfar < 0; // Embree sets tfar to -inf on a hit
}

Scene::Scene(const TriangleMesh& mesh, const Material& material, double rayEpsilon)
    : data_(std::make_unique<SceneData>())
{
    validateMesh(mesh);
    const size_t nt = mesh.triangles.size(), nv = mesh.positions.size();
    if (!inUnit(material.albedo))
        throw InvalidInput(fmt::format("reference scene: albedo ({}, {}, {}) is not in [0, 1]", material.albedo.x,
                                       material.albedo.y, material.albedo.z));
    if (!material.emission.empty() && material.emission.size() != nt)
        throw InvalidInput(fmt::format("reference scene: {} emissions for {} triangles (expected none or one per triangle)",
                                       material.emission.size(), nt));
    for (size_t t = 0; t < material.emission.size(); ++t)
        if (!finite(material.emission[t]) || !nonNegative(material.emission[t]))
            throw InvalidInput(fmt::format("reference scene: the emission of triangle {} is negative or not finite", t));
    if (!(rayEpsilon >= 0) || !std::isfinite(rayEpsilon))
        throw InvalidInput(fmt::format("reference scene: ray epsilon {} is not a finite number >= 0", rayEpsilon));
    if (material.vertexColors && !mesh.colors.empty())
        for (size_t v = 0; v < nv; ++v) {
            const Vec3f& c = mesh.colors[v];
            if (!inUnit({c.x, c.y, c.z}))
                throw InvalidInput(fmt::format("reference scene: the colour ({}, {}, {}) of vertex {} is not in [0, 1]", c.x,
                                               c.y, c.z, v));
        }
    if (nt > (size_t(1) << 31)) throw InvalidInput(fmt::format("reference scene: {} triangles; at most 2^31", nt));

    SceneData& s = *data_;
    s.bounds = mesh.bounds();
    s.centre = 0.5 * (s.bounds.min + s.bounds.max);
    const double diagonal = length(s.bounds.extent());
    // A mesh of one point (all triangles degenerate) still gets a positive epsilon.
    s.epsilon = rayEpsilon > 0 ? rayEpsilon : std::fmax(1e-5 * diagonal, 1e-300);
    s.positions.resize(nv);
    for (size_t v = 0; v < nv; ++v) s.positions[v] = mesh.positions[v] - s.centre;
    s.triangles = mesh.triangles;
    if (material.vertexColors && !mesh.colors.empty()) {
        s.colors.resize(nv);
        for (size_t v = 0; v < nv; ++v) s.colors[v] = {mesh.colors[v].x, mesh.colors[v].y, mesh.colors[v].z};
    }
    s.albedo = material.albedo;
    s.emission = material.emission;
    for (const Vec3d& e : s.emission) s.emits = s.emits || maxChannel(e) > 0;
    if (!s.emits) s.emission.clear();

    std::string error;
    s.device = rtcNewDevice(nullptr);
    if (!s.device) throw DeviceError(fmt::format("reference scene: Embree has no device (error {})", int(rtcGetDeviceError(nullptr))));
    rtcSetDeviceErrorFunction(s.device, recordError, &error);
    auto check = [&](const char* what) {
        if (!error.empty()) {
            rtcSetDeviceErrorFunction(s.device, nullptr, nullptr);
            throw DeviceError(fmt::format("reference scene: {} failed: {}", what, error));
        }
    };
    s.scene = rtcNewScene(s.device);
    rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // rtcSetNewGeometryBuffer pads the vertex buffer as Embree's 16-byte loads need.
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geometry);
        check("allocating the mesh's buffers");
        throw OutOfMemory("reference scene: Embree could not allocate the mesh's buffers");
    }
    for (size_t v = 0; v < nv; ++v) {
        vertices[3 * v + 0] = float(s.positions[v].x);
        vertices[3 * v + 1] = float(s.positions[v].y);
        vertices[3 * v + 2] = float(s.positions[v].z);
    }
    std::memcpy(indices, s.triangles.data(), nt * 3 * sizeof(uint32_t));
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(s.scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(s.scene);
    check("building the BVH");
    rtcSetDeviceErrorFunction(s.device, nullptr, nullptr);
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

Bounds Scene::bounds() const { return data_->bounds; }
double Scene::rayEpsilon() const { return data_->epsilon; }
size_t Scene::triangleCount() const { return data_->triangles.size(); }
bool Scene::emits() const { return data_->emits; }

const SceneData& sceneData(const Scene& scene) { return *scene.data_; }

} // namespace svo::reference
