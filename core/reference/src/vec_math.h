#pragma once
// Small double-vector helpers the reference shares (svo/core/vec3.h has only
// the GLSL basics).
#include <cmath>

#include "svo/core/vec3.h"

namespace svo::reference {

inline double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }
inline Vec3d normalize(const Vec3d& a) { return (1.0 / length(a)) * a; }
inline Vec3d mul(const Vec3d& a, const Vec3d& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline bool finite(const Vec3d& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
inline bool nonNegative(const Vec3d& a) { return a.x >= 0 && a.y >= 0 && a.z >= 0; }
inline double maxChannel(const Vec3d& a) { return std::fmax(a.x, std::fmax(a.y, a.z)); }

} // namespace svo::reference
