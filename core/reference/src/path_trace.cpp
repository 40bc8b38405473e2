#include "svo/reference/path_trace.h"

#include <atomic>
#include <chrono>
#include <climits>
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

void checkOptions(const RenderOptions& options)
{
    if (options.samples < 1) throw InvalidInput(fmt::format("reference render: {} samples per pixel; at least 1", options.samples));
    if (options.threads < 0) throw InvalidInput(fmt::format("reference render: {} threads; 0 (TBB's default) or more", options.threads));
    if (!(options.aoDistance > 0))
        throw InvalidInput(fmt::format("reference render: ambient occlusion distance {} is not positive", options.aoDistance));
}

int maxScatter(Mode mode)
{
    switch (mode) {
    case Mode::Direct: return 1;
    case Mode::OneBounce: return 2;
    default: return INT_MAX;
    }
}

} // namespace

FloatImage render(const Scene& scene, const Camera& camera, int width, int height, const Lighting& lights,
                  const RenderOptions& options, RenderStats* stats)
{
    const auto start = std::chrono::steady_clock::now();
    checkCamera(camera, width, height);
    checkOptions(options);
    checkLighting(lights);
    const SceneData& s = sceneData(scene);
    const LocalLights local(s, lights);
    const bool ao = options.mode == Mode::AmbientOcclusion;
    const int scatter = maxScatter(options.mode);
    // Direct light of delta lights alone involves no random choice: one sample says it all.
    const bool deterministic =
        options.mode == Mode::Direct && !s.emits && !(maxChannel(lights.environment) > 0);
    const int samples = deterministic ? 1 : options.samples;

    FloatImage image;
    image.width = width, image.height = height, image.channels = ao ? 1 : 3;
    image.pixels.assign(size_t(width) * size_t(height) * size_t(image.channels), 0.0f);
    image.covered.assign(size_t(width) * size_t(height), 0);
    std::atomic<uint64_t> cameraRays{0}, occlusionRays{0}, bounceRays{0};

    inArena(options.threads, [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, height, 1), [&](const tbb::blocked_range<int>& rows) {
            RayCounts counts;
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < width; ++x) {
                    const size_t pixel = size_t(y) * size_t(width) + size_t(x);
                    float* out = &image.pixels[pixel * size_t(image.channels)];
                    const Ray ray = cameraRay(camera, width, height, x, y);
                    // The camera ray is the pixel's centre for every sample: traced once.
                    Surface first;
                    ++counts.camera;
                    if (!s.intersect(s.toLocal(ray.origin), ray.direction, first)) {
                        if (ao) out[0] = 1.0f;
                        else out[0] = float(lights.environment.x), out[1] = float(lights.environment.y),
                        out[2] = float(lights.environment.z);
                        continue;
                    }
                    image.covered[pixel] = 1;
                    if (ao) {
                        const Vec3d origin = s.offset(first);
                        double open = 0;
                        for (int k = 0; k < samples; ++k) {
                            Rng rng(options.seed, pixel, uint64_t(k));
                            open += aoSample(s, origin, first.normal, options.aoDistance, rng, counts);
                        }
                        out[0] = float(open / samples);
                        continue;
                    }
                    Vec3d sum{};
                    for (int k = 0; k < samples; ++k) {
                        Rng rng(options.seed, pixel, uint64_t(k));
                        sum = sum + pathRadiance(s, local, first, scatter, rng, counts);
                    }
                    const Vec3d mean = (1.0 / samples) * sum;
                    out[0] = float(mean.x), out[1] = float(mean.y), out[2] = float(mean.z);
                }
            cameraRays += counts.camera;
            occlusionRays += counts.occlusion;
            bounceRays += counts.bounce;
        });
    });

    if (stats) {
        stats->cameraRays = cameraRays;
        stats->occlusionRays = occlusionRays;
        stats->bounceRays = bounceRays;
        stats->wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    return image;
}

FloatImage render(const TriangleMesh& mesh, const Material& material, const Camera& camera, int width, int height,
                  const Lighting& lights, const RenderOptions& options, RenderStats* stats)
{
    const auto start = std::chrono::steady_clock::now();
    // Cheap checks first, so that bad input does not wait for a BVH.
    checkCamera(camera, width, height);
    checkOptions(options);
    checkLighting(lights);
    const Scene scene(mesh, material);
    FloatImage image = render(scene, camera, width, height, lights, options, stats);
    if (stats) stats->wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return image;
}

} // namespace svo::reference
