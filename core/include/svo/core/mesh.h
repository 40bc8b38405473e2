#pragma once
/// @file mesh.h
/// An indexed triangle mesh in double precision: the input every backend takes.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "svo/core/vec3.h"

namespace svo {

struct Bounds {
    Vec3d min{+INFINITY, +INFINITY, +INFINITY};
    Vec3d max{-INFINITY, -INFINITY, -INFINITY};
    bool empty() const { return !(min.x <= max.x); }
    Vec3d extent() const { return max - min; }
};

struct TriangleMesh {
    std::vector<Vec3d> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
    /// Per-vertex RGB in [0, 1], one per position; empty when the file has none.
    std::vector<Vec3f> colors;
    /// Where the mesh came from (a path, or the built-in scene's name).
    std::string source;
    /// Things the reader could not keep, for the user to see (never silent).
    std::vector<std::string> warnings;

    Bounds bounds() const;
    /// The three corners of triangle t.
    std::array<Vec3d, 3> corners(size_t t) const
    {
        const auto& f = triangles[t];
        return {positions[f[0]], positions[f[1]], positions[f[2]]};
    }
};

/// Throws svo::Error, naming mesh.source, when the mesh cannot be voxelized:
/// no triangles, an index out of range, a NaN/Inf coordinate in a vertex
/// that a triangle uses, or a colour list that does not match the vertices.
void validateMesh(const TriangleMesh& mesh);

} // namespace svo
