#pragma once
/// @file winding_tree.h
/// The generalized winding number of a triangle mesh (Jacobson et al. 2013)
/// and the tree that evaluates it fast (Barill et al. 2018): the host half of
/// svo's winding-number signs (the GPU evaluates it, svo/gl/winding_number.h).
///
/// The winding number of a point q is the sum of the signed solid angles the
/// triangles subtend at q, over 4 pi: 1 inside a closed, outward-oriented
/// surface, 0 outside, and in between where the surface has holes, so that
/// thresholding it at 1/2 gives a sensible inside for open meshes, soups and
/// overlapping parts. Triangles with inconsistent orientation subtract
/// instead of adding; no method based on the triangles alone can tell.
///
/// The tree is built over pieces of the triangles (winding_pieces.h: those
/// with an edge much longer than most triangles' are cut, so that no leaf
/// is large because one of its triangles is). It is a bounding-volume
/// hierarchy split at the median along the longest axis of the pieces'
/// centroids, with at most kWindingLeafSize pieces a leaf. Every node keeps its triangles' far field expanded to
/// second order about c, their area-weighted centroid (Barill et al. 2018):
/// the sum N of their area vectors (half the cross product, pointing out),
/// the first moments C_ij = sum of a_i o_j and the second moments
/// M_ijk = sum of a_i o_j o_k of each triangle's area vector a over its
/// points, o = point - c, and the radius r of the ball about c that holds
/// all their corners. A node whose ball is far from q (|q - c| > beta r)
/// adds the three terms of the Taylor series of the solid angle at d = c - q
/// instead of its triangles:
///   N . d / |d|^3 + tr(C) / |d|^3 - 3 d^T C d / |d|^5
///   + [15 sum M_ijk d_i d_j d_k / |d|^7 - 3 (2 sum M_iik d_k + sum M_ijj d_i) / |d|^5] / 2,
/// over 4 pi. The error is of the third order in r / |d| (with c the
/// area-weighted centroid C vanishes on flat patches, so the dipole alone
/// is of the second): doubling beta divides the error by about 8 or more,
/// and beta = 1.5 is twice as accurate as the dipole alone at beta = 2.
/// Nearer nodes are opened, and leaf triangles add their exact solid angle.
/// With beta = infinity every triangle is exact.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/vec3.h"

namespace svo {

/// Triangles in one leaf of the winding tree, at most.
inline constexpr uint32_t kWindingLeafSize = 8;
/// The longest edge of a piece of the tree, at least, in the positions'
/// units (svo builds the tree in local voxels): shorter pieces make more
/// nodes to visit, longer ones more exact solid angles.
inline constexpr double kWindingPieceEdge = 8.0;
/// ... and at least this many times the median of the triangles' longest
/// edges: large triangles among small ones are cut (their leaves would be
/// opened from afar, the small triangles in them evaluated exactly), a mesh
/// of triangles of one size is left whole (a single triangle spanning the
/// grid is cheapest whole: one exact solid angle a point).
inline constexpr double kWindingPieceMedians = 4.0;
/// The most pieces a tree is built over, per triangle (at least 2^20 in
/// all): past it the pieces are cut twice as long, and so on.
inline constexpr size_t kWindingPiecesPerTriangle = 4;
/// Floats per node of WindingTree::nodes.
inline constexpr uint32_t kWindingNodeFloats = 36;

struct WindingTree {
    /// kWindingNodeFloats per node: centre c (x, y, z), radius r, area vector
    /// N (x, y, z), the first moments C_00, C_01, C_02, C_10, ..., C_22, the
    /// second moments M_i00, M_i01, M_i02, M_i11, M_i12, M_i22 for i = 0, 1,
    /// 2, then 2 zeros (9 vec4s). Node 0 is the root.
    std::vector<float> nodes;
    /// 2 uints per node. Inner node: the two children. Leaf: the first entry
    /// of `order`, and the count with the top bit set.
    std::vector<uint32_t> links;
    /// Indices into `triangles` in leaf order.
    std::vector<uint32_t> order;
    /// The pieces the tree holds (cutLongTriangles): the input positions,
    /// then the corners the cuts added, and three indices into them each.
    std::vector<Vec3d> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
    double pieceEdge = 0; ///< the longest edge the pieces were cut to
    uint32_t depth = 0; ///< levels below the root
};

/// Builds the tree for triangles over `positions` (any frame; svo uses
/// local voxel coordinates), cut into pieces of edges at most the larger of
/// @a pieceEdge and kWindingPieceMedians times the median longest edge
/// (within the budget of kWindingPiecesPerTriangle). Degenerate triangles
/// are kept (their area vector is zero, their solid angle zero).
/// @param pieceEdge the longest edge of a piece; infinity keeps the triangles whole
/// @throw svo::InvalidInput when there are no triangles, svo::Unsupported for more than 2^31 pieces.
WindingTree buildWindingTree(const std::vector<Vec3d>& positions,
                             const std::vector<std::array<uint32_t, 3>>& triangles,
                             double pieceEdge = kWindingPieceEdge);

/// The signed solid angle of triangle abc seen from q, over 4 pi (van
/// Oosterom and Strackee's formula, in double): in (-1/2, 1/2], 0 when q lies
/// in the triangle's plane.
double triangleWinding(const Vec3d& q, const Vec3d& a, const Vec3d& b, const Vec3d& c);

/// The exact winding number at q: every triangle's solid angle summed, no
/// tree. O(triangles); the reference that tests hold the GPU tree to.
double windingNumber(const std::vector<Vec3d>& positions, const std::vector<std::array<uint32_t, 3>>& triangles,
                     const Vec3d& q);

} // namespace svo
