#include "integrator.h"

#include <cmath>
#include <fmt/format.h>

#include "svo/core/error.h"
#include "vec_math.h"

namespace svo::reference {

void checkLighting(const Lighting& lights)
{
    auto bad = [](const Vec3d& v) { return !finite(v) || !nonNegative(v); };
    for (size_t i = 0; i < lights.directional.size(); ++i) {
        const auto& l = lights.directional[i];
        if (!finite(l.direction) || !(length(l.direction) > 0))
            throw InvalidInput(fmt::format("reference lights: directional light {} has a zero or non-finite direction", i));
        if (bad(l.irradiance))
            throw InvalidInput(fmt::format("reference lights: directional light {} has a negative or non-finite irradiance", i));
    }
    for (size_t i = 0; i < lights.point.size(); ++i) {
        const auto& l = lights.point[i];
        if (!finite(l.position))
            throw InvalidInput(fmt::format("reference lights: point light {} has a non-finite position", i));
        if (bad(l.intensity))
            throw InvalidInput(fmt::format("reference lights: point light {} has a negative or non-finite intensity", i));
    }
    if (bad(lights.environment))
        throw InvalidInput("reference lights: the environment radiance is negative or not finite");
}

LocalLights::LocalLights(const SceneData& scene, const Lighting& lights) : environment(lights.environment)
{
    for (const auto& l : lights.directional)
        if (maxChannel(l.irradiance) > 0) directional.push_back({-1.0 * normalize(l.direction), l.irradiance});
    for (const auto& l : lights.point)
        if (maxChannel(l.intensity) > 0) point.push_back({scene.toLocal(l.position), l.intensity});
}

Vec3d directLight(const SceneData& scene, const LocalLights& lights, const Surface& x, RayCounts& counts)
{
    Vec3d irradiance{};
    const Vec3d origin = scene.offset(x);
    for (const auto& l : lights.directional) {
        const double c = dot(x.normal, l.toLight);
        if (!(c > 0)) continue;
        ++counts.occlusion;
        if (!scene.occluded(origin, l.toLight, INFINITY)) irradiance = irradiance + c * l.irradiance;
    }
    for (const auto& l : lights.point) {
        // Cosine and falloff from the surface point itself; the shadow ray
        // from the offset origin stops short of the light by epsilon.
        const Vec3d d = l.position - x.point;
        const double r2 = dot(d, d);
        if (!(r2 > 0)) continue;
        const double r = std::sqrt(r2);
        const double c = dot(x.normal, d) / r;
        if (!(c > 0)) continue;
        const Vec3d shadow = l.position - origin;
        const double distance = length(shadow);
        ++counts.occlusion;
        if (!scene.occluded(origin, (1.0 / distance) * shadow, distance - scene.epsilon))
            irradiance = irradiance + (c / r2) * l.intensity;
    }
    return (1.0 / M_PI) * mul(x.albedo, irradiance);
}

Vec3d pathRadiance(const SceneData& scene, const LocalLights& lights, const Surface& first, int maxScatter,
                   Rng& rng, RayCounts& counts)
{
    const bool russianRoulette = maxScatter == INT_MAX;
    // Without emitters or environment, a continuation only matters for the
    // lights it reaches by next-event estimation at its end.
    const bool sources = scene.emits || maxChannel(lights.environment) > 0;
    Vec3d sum = first.emission, throughput{1, 1, 1};
    Surface x = first;
    // Vertex k carries k reflections before it: its emission (added on
    // arrival) is a path of k reflections, its next-event estimate and its
    // continuation add a reflection at x.
    for (int k = 0; k + 1 <= maxScatter; ++k) {
        sum = sum + mul(throughput, directLight(scene, lights, x, counts));
        if (k + 2 > maxScatter && !sources) break;
        Vec3d weight = x.albedo; // f cos / pdf = (albedo/pi) cos / (cos/pi)
        if (russianRoulette) {
            const double q = std::fmin(0.99, maxChannel(x.albedo));
            if (!(rng.next() < q)) break;
            weight = (1.0 / q) * weight;
        }
        if (!(maxChannel(weight) > 0)) break;
        throughput = mul(throughput, weight);
        const double u1 = rng.next(), u2 = rng.next();
        const Vec3d dir = cosineDirection(x.normal, u1, u2);
        ++counts.bounce;
        Surface next;
        if (!scene.intersect(scene.offset(x), dir, next)) {
            sum = sum + mul(throughput, lights.environment);
            break;
        }
        sum = sum + mul(throughput, next.emission);
        x = next;
    }
    return sum;
}

} // namespace svo::reference
