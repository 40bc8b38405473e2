#pragma once
/// @file mesh_topology.h
/// @brief Whether a mesh bounds a solid: the test that picks the sign method.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "svo/core/mesh.h"

namespace svo {

/// @brief Edge counts of a mesh after welding vertices at equal positions (so a
/// triangle soup such as an STL file counts as connected where it is).
/// Triangles with a repeated corner are left out: they bound nothing.
struct EdgeReport {
    uint64_t edges = 0;        ///< distinct undirected edges
    uint64_t boundary = 0;     ///< edges of one triangle only
    uint64_t nonManifold = 0;  ///< edges of three or more triangles
    uint64_t misoriented = 0;  ///< edges of two triangles that run the same way along it
    /// @brief Whether every edge has exactly two triangles running opposite
    /// ways: parity along any line then gives inside and outside correctly.
    bool closedAndOriented() const { return edges > 0 && !boundary && !nonManifold && !misoriented; }
    /// @brief "closed and consistently oriented", or what is wrong, with counts.
    std::string describe() const;
};

/// @brief An undirected edge of a mesh after welding its vertices.
struct WeldedEdge {
    uint32_t lo, hi; ///< its ends, lo < hi: each the first vertex at its position
    uint32_t uses;   ///< triangles that have it
    int64_t net;     ///< the triangles running lo -> hi along it, less those running hi -> lo
};

/// @brief Visits the edges of @a mesh after welding its vertices at equal
/// positions, in (lo, hi) order; triangles with a repeated corner left out.
/// Holds a few words per edge use, not the edges.
/// @param visit called once per edge
/// @throw std::bad_alloc only; indices must be valid (validateMesh)
void forEachWeldedEdge(const TriangleMesh& mesh, const std::function<void(const WeldedEdge&)>& visit);

/// @brief The edges forEachWeldedEdge visits, as a list.
/// @throw std::bad_alloc only; indices must be valid (validateMesh)
std::vector<WeldedEdge> weldedEdges(const TriangleMesh& mesh);

/// @brief Counts the edges of @a mesh after welding its vertices (weldedEdges).
/// Throws nothing but std::bad_alloc; indices must be valid (validateMesh).
EdgeReport checkEdges(const TriangleMesh& mesh);

} // namespace svo
