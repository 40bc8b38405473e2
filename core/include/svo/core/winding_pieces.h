#pragma once
/// @file winding_pieces.h
/// @brief The triangles a winding tree is built over: the mesh's, with every
/// triangle that has an edge longer than a limit cut into pieces.
///
/// A leaf of the winding tree (winding_tree.h) is opened by every point
/// within beta radii of its ball, and its ball holds its largest triangle:
/// a few large triangles make large leaves that every point near them
/// evaluates exactly, triangle by triangle, the small triangles beside them
/// too. Pieces no longer than the limit keep the leaves small, so that the
/// far field takes over a few pieces away. The solid angle of a triangle is
/// the sum of its pieces' (the pieces tile it), so the winding number is
/// the same function; only its far-field approximation and rounding change.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/vec3.h"

namespace svo {

struct WindingPieces {
    /// The input positions, then the corners the cuts add.
    std::vector<Vec3d> positions;
    /// Three indices into positions each: the uncut triangles and the
    /// pieces, in input order (a triangle's pieces where it was).
    std::vector<std::array<uint32_t, 3>> triangles;
    /// The longest edge a piece was allowed: the requested limit, doubled
    /// until the pieces fit the budget.
    double edge = 0;
};

/// @brief Cuts each triangle with an edge longer than @a maxEdge in two at
/// the middle of its longest edge, and its halves the same way, until no
/// edge is longer (longest-edge bisection: a sliver becomes a row of
/// pieces, not a grid of slivers). Degenerate triangles are kept whole.
/// @param maxEdge the longest edge a piece may have (in the positions'
///        units); infinity keeps every triangle
/// @param budget  the most triangles the result may have: while the pieces
///        would be more, the limit is doubled (never fewer than the input)
/// @return the pieces and the limit they were cut with
WindingPieces cutLongTriangles(const std::vector<Vec3d>& positions,
                               const std::vector<std::array<uint32_t, 3>>& triangles, double maxEdge, size_t budget);

} // namespace svo
