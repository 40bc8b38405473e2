#pragma once
/// @file ambient_occlusion.h
/// @brief Ambient occlusion at given surface points (voxel centres, test
/// points), not only at what a camera sees.
///
/// @details AO(x, n) = (1/pi) ∫ cos(theta) [no hit within R] dω over the
/// hemisphere around n. Estimated with cosine-weighted directions (Malley's
/// method: uniform points on the unit disk lifted to the hemisphere), whose
/// density cos(theta)/pi cancels the integrand's weight, so AO is the fraction
/// of `samples` occlusion rays that hit nothing within R: a binomial
/// proportion, with standard error sqrt(AO (1 - AO) / samples). It is exact
/// (every ray agrees) where the hemisphere is entirely open or entirely closed.
/// Rays start at x moved by the scene's ray epsilon along n, and R is measured
/// from there. Sample s of point i draws from the PCG generator of (seed, i, s),
/// as path_trace.h's pixels do, so results do not depend on thread scheduling.
#include <cstdint>
#include <limits>
#include <vector>

#include "svo/reference/path_trace.h"
#include "svo/reference/scene.h"

namespace svo::reference {

/// @brief How AO is estimated at each point.
struct AmbientOcclusionOptions {
    double distance = std::numeric_limits<double>::infinity(); ///< R, world units, > 0
    int samples = 256;  ///< rays per point, >= 1
    uint64_t seed = 0;  ///< the same seed gives the same values, bit for bit
    int threads = 0;    ///< TBB threads for many points; 0 for TBB's default
};

/// @brief AO at one point.
/// @param point   world units, on (or just above) a surface
/// @param normal  the side to look at; need not be unit length, must not be zero
/// @param stats   when given, receives the ray counts and wall time
/// @return AO in [0, 1]; 1 = open
/// @throw svo::InvalidInput  point or normal not finite, normal zero, distance not > 0,
///                    samples < 1, threads < 0.
double ambientOcclusionAt(const Scene& scene, const Vec3d& point, const Vec3d& normal,
                          const AmbientOcclusionOptions& options, RenderStats* stats = nullptr);

/// @brief AO at many points in parallel; point i is sampled as index i (so the
/// first point here equals the single-point call's result with the same seed).
/// @param normals one per point
/// @return one AO value per point
/// @throw svo::InvalidInput  as above, naming the first bad point, or when the lists'
///                    sizes differ.
std::vector<double> ambientOcclusionAt(const Scene& scene, const std::vector<Vec3d>& points,
                                       const std::vector<Vec3d>& normals, const AmbientOcclusionOptions& options,
                                       RenderStats* stats = nullptr);

} // namespace svo::reference
