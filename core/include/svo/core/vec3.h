#pragma once
/// @file vec3.h
/// @brief svo::Vec3: the 3-vector of meshes, grids and the overlap test.
#include <cmath>

namespace svo {

/// @brief A minimal 3-vector with the GLSL spelling (x, y, z, dot, cross, abs, min,
/// max) so that overlap.glsl compiles unchanged as C++.
template <typename T>
struct Vec3 {
    T x{}, y{}, z{};
    constexpr Vec3() = default;
    constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    friend constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
    friend constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    friend constexpr Vec3 operator*(T s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
    friend constexpr bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
};

using Vec3d = Vec3<double>;
using Vec3f = Vec3<float>;

/// @brief GLSL's dot, cross and abs (componentwise), for overlap.glsl.
template <typename T> constexpr T dot(Vec3<T> a, Vec3<T> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <typename T> constexpr Vec3<T> cross(Vec3<T> a, Vec3<T> b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T> inline Vec3<T> abs(Vec3<T> a) { return {std::abs(a.x), std::abs(a.y), std::abs(a.z)}; }

} // namespace svo
