#pragma once
/// @file path_trace.h
/// @brief Images of a Scene under a Camera by CPU path tracing (Embree 3): the
/// independent reference that svo's voxel cone tracing (ambient occlusion,
/// direct light with a shadow map, one diffuse bounce) is measured against.
///
/// @details Each mode is one quantity (docs/lighting_reference.md has the
/// formulas). In the light-transport terms used there, a path's scattering
/// count is the number of surface reflections between the light and the eye:
/// - AmbientOcclusion: AO(x) = (1/pi) ∫ cos(theta) [no hit within R] dω over
///   the hemisphere of the surface normal facing the camera; 1 = open.
///   One channel. Pixels that see no surface are 1.
/// - Direct: paths of at most one scattering: the emission of the surface
///   seen, plus albedo/pi · (E cos(theta) or I cos(theta)/r²) from each light
///   it sees (shadow ray), plus emitters and environment seen from it by one
///   reflection. Without emitters and environment this is deterministic and
///   one sample per pixel is traced, whatever `samples` says.
/// - OneBounce: paths of at most two scatterings: Direct plus, per sample, a
///   cosine-weighted direction from the surface seen and the direct light
///   (as above) at the point it hits: what a one-bounce cone tracer approximates.
/// - Full: all paths, unbiased: next-event estimation of the lights at every
///   vertex, cosine-weighted continuation, Russian roulette with survival
///   probability min(0.99, largest albedo channel) from the first vertex on.
/// Rays that leave the scene bring the Lighting's environment radiance.
///
/// Sampling: the camera ray is always the pixel's centre (cameraRay), so an
/// image is comparable pixel for pixel with the GL view's. Random numbers are
/// counter-based: sample s of pixel p draws from a PCG generator seeded with
/// a hash of (seed, p, s), so an image does not depend on thread scheduling,
/// thread count or the order of pixels. Rows run in parallel (TBB).
#include <cstdint>
#include <limits>
#include <vector>

#include "svo/core/mesh.h"
#include "svo/reference/camera.h"
#include "svo/reference/lights.h"
#include "svo/reference/scene.h"

namespace svo::reference {

/// @brief The quantity an image holds (see the file comment).
enum class Mode { AmbientOcclusion, Direct, OneBounce, Full };

/// @brief What to render and how many samples.
struct RenderOptions {
    Mode mode = Mode::Direct; ///< the quantity
    int samples = 16;   ///< per pixel, >= 1; each sample is one path (or one AO ray)
    uint64_t seed = 0;  ///< the same seed gives the same image, bit for bit
    /// AmbientOcclusion: R, the distance within which a hit occludes (world
    /// units, > 0; infinity for any distance).
    double aoDistance = std::numeric_limits<double>::infinity();
    int threads = 0;    ///< TBB threads; 0 for TBB's default. The image does not depend on it.
};

/// @brief A float image, rows from the top: `channels` floats per pixel (1 for
/// AmbientOcclusion, RGB radiance for the others).
struct FloatImage {
    int width = 0, height = 0, channels = 0; ///< pixels; floats per pixel
    std::vector<float> pixels;   ///< width * height * channels
    std::vector<uint8_t> covered; ///< per pixel: 1 where the camera ray hits a triangle
    /// @brief Channel @a c of pixel (@a x, @a y), row @a y from the top; unchecked.
    float at(int x, int y, int c = 0) const
    {
        return pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)];
    }
};

/// @brief What a render cost; kept apart from its result.
struct RenderStats {
    uint64_t cameraRays = 0;    ///< one per pixel
    uint64_t occlusionRays = 0; ///< shadow and AO rays (any-hit)
    uint64_t bounceRays = 0;    ///< closest-hit rays after the camera's
    double wallMs = 0;          ///< wall milliseconds
    /// @brief All rays traced.
    uint64_t rays() const { return cameraRays + occlusionRays + bounceRays; }
};

/// @brief Renders one mode of @a scene as seen by @a camera in a @a width x
/// @a height image.
/// @param lights  ignored by AmbientOcclusion
/// @param stats   when given, receives the ray counts and wall time
/// @return the image; the same inputs give the same bytes, whatever the thread count.
/// @throw svo::InvalidInput  the camera fails checkCamera; samples < 1; threads < 0;
///        aoDistance not > 0 (NaN included); a light direction zero or not
///        finite; a light position, irradiance, intensity or the environment
///        not finite or negative.
FloatImage render(const Scene& scene, const Camera& camera, int width, int height, const Lighting& lights,
                  const RenderOptions& options, RenderStats* stats = nullptr);

/// @brief The same, building a Scene from @a mesh and @a material first.
/// @throw as above, and what Scene's constructor throws
FloatImage render(const TriangleMesh& mesh, const Material& material, const Camera& camera, int width, int height,
                  const Lighting& lights, const RenderOptions& options, RenderStats* stats = nullptr);

} // namespace svo::reference
