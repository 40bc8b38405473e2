#include "svo/reference/ambient_occlusion.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "integrator.h"
#include "parallel.h"
#include "svo/core/error.h"
#include "vec_math.h"

namespace svo::reference {

namespace {

void checkOptions(const AmbientOcclusionOptions& options)
{
    if (!(options.distance > 0))
        throw InvalidInput(fmt::format("reference ambient occlusion: distance {} is not positive", options.distance));
    if (options.samples < 1)
        throw InvalidInput(fmt::format("reference ambient occlusion: {} samples; at least 1", options.samples));
    if (options.threads < 0)
        throw InvalidInput(fmt::format("reference ambient occlusion: {} threads; 0 (TBB's default) or more", options.threads));
}

void checkPoint(size_t i, const Vec3d& point, const Vec3d& normal)
{
    if (!finite(point)) throw InvalidInput(fmt::format("reference ambient occlusion: point {} is not finite", i));
    if (!finite(normal) || !(length(normal) > 0))
        throw InvalidInput(fmt::format("reference ambient occlusion: the normal of point {} is zero or not finite", i));
}

double estimate(const SceneData& s, size_t index, const Vec3d& point, const Vec3d& normal,
                const AmbientOcclusionOptions& options, RayCounts& counts)
{
    const Vec3d n = normalize(normal);
    const Vec3d origin = s.toLocal(point) + s.epsilon * n;
    double open = 0;
    for (int k = 0; k < options.samples; ++k) {
        Rng rng(options.seed, index, uint64_t(k));
        open += aoSample(s, origin, n, options.distance, rng, counts);
    }
    return open / options.samples;
}

} // namespace

std::vector<double> ambientOcclusionAt(const Scene& scene, const std::vector<Vec3d>& points,
                                       const std::vector<Vec3d>& normals, const AmbientOcclusionOptions& options,
                                       RenderStats* stats)
{
    const auto start = std::chrono::steady_clock::now();
    checkOptions(options);
    if (points.size() != normals.size())
        throw InvalidInput(fmt::format("reference ambient occlusion: {} points but {} normals", points.size(), normals.size()));
    for (size_t i = 0; i < points.size(); ++i) checkPoint(i, points[i], normals[i]);
    const SceneData& s = sceneData(scene);
    std::vector<double> result(points.size());
    std::atomic<uint64_t> rays{0};
    inArena(options.threads, [&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
            RayCounts counts;
            for (size_t i = r.begin(); i != r.end(); ++i)
                result[i] = estimate(s, i, points[i], normals[i], options, counts);
            rays += counts.occlusion;
        });
    });
    if (stats) {
        *stats = RenderStats{};
        stats->occlusionRays = rays;
        stats->wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    return result;
}

double ambientOcclusionAt(const Scene& scene, const Vec3d& point, const Vec3d& normal,
                          const AmbientOcclusionOptions& options, RenderStats* stats)
{
    return ambientOcclusionAt(scene, std::vector<Vec3d>{point}, std::vector<Vec3d>{normal}, options, stats)[0];
}

} // namespace svo::reference
