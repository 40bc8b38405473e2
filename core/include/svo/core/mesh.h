#pragma once
/// @file mesh.h
/// @brief An indexed triangle mesh in double precision: the input every backend takes.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "svo/core/vec3.h"

namespace svo {

/// @brief An axis-aligned box; empty (min above max) until a point is added.
struct Bounds {
    Vec3d min{+INFINITY, +INFINITY, +INFINITY}; ///< lowest corner
    Vec3d max{-INFINITY, -INFINITY, -INFINITY}; ///< highest corner
    /// @brief Whether the box holds no point.
    bool empty() const { return !(min.x <= max.x); }
    /// @brief The box's size along each axis.
    Vec3d extent() const { return max - min; }
};

/// @brief An indexed triangle mesh in double precision, with optional vertex colours.
struct TriangleMesh {
    std::vector<Vec3d> positions;                   ///< vertices
    std::vector<std::array<uint32_t, 3>> triangles; ///< three indices into positions each
    /// Per-vertex RGB in [0, 1], one per position; empty when the file has none.
    std::vector<Vec3f> colors;
    /// Where the mesh came from (a path, or the built-in scene's name).
    std::string source;
    /// Things the reader could not keep, for the user to see (never silent).
    std::vector<std::string> warnings;

    /// @brief The box of the vertices that triangles use.
    Bounds bounds() const;
    /// @brief The three corners of triangle @a t; unchecked.
    std::array<Vec3d, 3> corners(size_t t) const
    {
        const auto& f = triangles[t];
        return {positions[f[0]], positions[f[1]], positions[f[2]]};
    }
};

/// @brief Checks that a mesh can be voxelized.
/// @throw svo::InvalidInput, naming mesh.source, for no triangles, an index
///        out of range, a NaN/Inf coordinate in a vertex that a triangle uses,
///        or a colour list that does not match the vertices
void validateMesh(const TriangleMesh& mesh);

} // namespace svo
