#pragma once
// The estimators behind every mode, on one surface point at a time, in the
// scene's local frame.
#include <climits>
#include <cstdint>

#include "sampling.h"
#include "scene_data.h"
#include "svo/reference/lights.h"

namespace svo::reference {

struct RayCounts {
    uint64_t camera = 0, occlusion = 0, bounce = 0;
};

// Throws svo::Error for a light or environment render() refuses.
void checkLighting(const Lighting& lights);

// A light with its direction made unit and its position in the local frame.
struct LocalLights {
    struct Directional { Vec3d toLight, irradiance; };
    struct Point { Vec3d position, intensity; };
    std::vector<Directional> directional;
    std::vector<Point> point;
    Vec3d environment;
    LocalLights(const SceneData& scene, const Lighting& lights);
};

// Reflected radiance toward the viewer at `x` from the lights, by one
// reflection, with shadow rays: sum of albedo/pi * E cos, albedo/pi * I cos / r².
// Deterministic.
Vec3d directLight(const SceneData& scene, const LocalLights& lights, const Surface& x, RayCounts& counts);

// One path's radiance estimate toward the viewer from `first`, the surface
// the camera ray hit, counting paths of at most `maxScatter` reflections
// (INT_MAX: all, with Russian roulette). With no emitters and a black
// environment, the last continuation could only bring 0 and is not traced.
Vec3d pathRadiance(const SceneData& scene, const LocalLights& lights, const Surface& first, int maxScatter,
                   Rng& rng, RayCounts& counts);

// One ambient-occlusion sample at `origin` (already offset) around unit `n`:
// 1 when a cosine-weighted ray meets nothing within `distance`, else 0.
inline double aoSample(const SceneData& scene, const Vec3d& origin, const Vec3d& n, double distance, Rng& rng,
                       RayCounts& counts)
{
    const double u1 = rng.next(), u2 = rng.next();
    ++counts.occlusion;
    return scene.occluded(origin, cosineDirection(n, u1, u2), distance) ? 0.0 : 1.0;
}

} // namespace svo::reference
