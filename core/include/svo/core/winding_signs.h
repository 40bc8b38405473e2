#pragma once
/// @file winding_signs.h
/// @brief Winding-number signs on the CPU: the evaluations of the GPU's
/// winding pass (svo/gl/winding_number.h) with the same tree, the same
/// far-field rule and the same arithmetic in the same order, and the rule
/// (shared with the GPU path) for the bricks beyond a band.
///
/// A voxel centre q is inside when its winding number, summed by the walk of
/// winding_tree.h, is at least 1/2: a node whose ball is farther from q than
/// beta radii (|c - q|^2 > beta^2 r^2, in float) adds its far field in
/// float; a nearer leaf adds its triangles' exact solid angles (double, the
/// angle's arctangent in float); children are visited as the GPU's stack
/// visits them, so each centre's sum adds the same terms in the same order.
/// A brick's 512 centres share one walk: each node is visited once for all
/// the centres whose own walk reaches it (a mask), so the tree's upper
/// levels are read once a brick, not once a voxel.
///
/// The float arctangent of each exact triangle is Mesa's polynomial (what
/// llvmpipe runs for GLSL's atan, absolute error about 1e-5): on llvmpipe
/// the sums are the GPU's bit for bit; a hardware GPU's own atan differs by
/// about 1e-6 in a winding number, which moves only a centre whose number is
/// that near 1/2 (on a face of the mesh, where either side is the answer).
///
/// Most centres need no walk: windingInsideAlongColumns walks a run of
/// bricks' lowest centres (or enters the run from the brick below, whose
/// centre's number the brick-centre pass has) and climbs each column from
/// them (winding_columns.h), walking only where the climb cannot decide. It gives
/// the walk's side wherever the walk is within windingWalkError of the exact
/// number; a centre on the surface, where the walk's number is 1/2 up to
/// rounding, takes the side of the crossings' ties.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/field_bricks.h"
#include "svo/core/grid.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/core/vec3.h"
#include "svo/core/winding_columns.h"
#include "svo/core/winding_tree.h"

namespace svo {

/// A brick beyond the band whose centre's winding number is nearer 1/2 than
/// this may hold both sides (the 1/2 level crosses free space only where the
/// mesh has holes); its voxels are evaluated one by one.
inline constexpr float kWindingMargin = 0.25f;

/// @brief The winding number at the centre of every brick of @a grid's box
/// (brick b's centre is 8 b + 3.5 in local coordinates), or of the box of
/// bricks that @a columns covers, on the CPU.
/// With @a columns, each column of bricks climbs from its lowest centre
/// (walked) and a centre is walked only where the climbed number, give or
/// take its doubt and twice windingWalkError, could fall on either side of
/// 1/2 -+ kWindingMargin: there the number is a climbed one, on the side of
/// those thresholds the walk's is on (wherever the walk is within
/// windingWalkError of the exact number).
/// @param tree  built from the mesh's positions in @a grid's local frame
///              (localPositions) and its triangles (buildWindingTree)
/// @param beta  the far-field threshold (SignOptions::windingAccuracy)
/// @param checkpoint polled on the calling thread between batches
/// @param columns brickCentreColumns of @a grid (of its whole box or a part),
///                or null: every centre of the whole box walked
/// @param walked  if not null, gets the number of centres walked
/// @param doubts  if not null, gets per centre how far its number may be
///                from a walk's, less windingWalkError (0 where walked)
/// @return x-fastest over the box (the whole box: ceil(dims / 8) bricks)
/// @throw svo::Unsupported for a box of more than 2^31 bricks; svo::InvalidInput
///        when @a columns is of another box; svo::Interrupted.
std::vector<float> windingAtBrickCentres(const WindingTree& tree, const GridSpec& grid, double beta,
                                         const Checkpoint& checkpoint, const BrickCentreColumns* columns = nullptr,
                                         uint64_t* walked = nullptr, std::vector<float>* doubts = nullptr);

/// @brief Per brick of a list, the voxels whose centre's winding number is
/// at least 1/2, on the CPU.
/// @param bricks brick coordinates (local voxel coordinate / 8)
/// @return per brick, in list order, the inside voxels (bit order of Brick)
/// @throw svo::Interrupted from the checkpoint.
std::vector<Brick> windingInside(const WindingTree& tree, const std::vector<BrickCoord>& bricks, double beta,
                                 const Checkpoint& checkpoint);

/// @brief How far a walk's winding number may be from the exact sum of
/// every triangle's solid angle, as windingInsideAlongColumns allows for:
/// 0.1 at beta = 1.5 (the far field's error, of the third order in 1/beta;
/// the largest measured is about half of it), at least 1e-3 (the float
/// arctangent and sums), at most 1/2 (no climb decides: every centre walked).
float windingWalkError(double beta);

/// @brief Where a run of bricks may start its climb without walking its
/// lowest layer: from the brick below it, whose box holds no triangle when
/// it is not in the list and was searched. The winding number is smooth
/// there, so at the top centre of each of its columns it is the number at
/// its centre, give or take that number's doubt and 3.5 sqrt 3 voxels of
/// BrickCentreColumns::gradientAt.
struct ClimbAnchors {
    const BrickCentreColumns* columns = nullptr; ///< the grid's box and the gradient's bounds
    const std::vector<float>* centres = nullptr; ///< windingAtBrickCentres over its box
    const std::vector<float>* doubts = nullptr;  ///< ... and its doubts
    /// The bricks b, lo <= b < hi per axis, that the list's band (of at least
    /// one voxel about every triangle) was searched in whole: one not listed
    /// holds no triangle in the box of its centres.
    std::array<uint32_t, 3> lo{}, hi{};
};

/// @brief windingInside's result with fewer walks: per run of bricks stacked
/// in z, the lowest layer's centres are walked (or entered from the brick
/// below, with @a anchors) and each column climbs from there by @a columns
/// (winding_columns.h); a centre is walked too where the climbed number is
/// within its bound plus twice windingWalkError(beta) of 1/2, and the
/// column climbs on from it. A centre not walked is then on the side a walk
/// would give it, wherever the walk is within windingWalkError of the exact
/// number.
/// @param columns windingColumns of @a bricks
/// @param walked  if not null, gets the number of centres walked
/// @param anchors if not null, the brick centres' numbers to enter runs from
/// @return per brick, in list order, the inside voxels (bit order of Brick)
/// @throw svo::InvalidInput when @a columns is not of @a bricks, or
///        @a anchors not of one box; svo::Interrupted.
std::vector<Brick> windingInsideAlongColumns(const WindingTree& tree, const std::vector<BrickCoord>& bricks,
                                             const WindingColumns& columns, double beta, const Checkpoint& checkpoint,
                                             uint64_t* walked = nullptr, const ClimbAnchors* anchors = nullptr);

/// What the bricks beyond a band take from their centres' winding numbers.
struct BricksBeyondBand {
    std::vector<BrickCoord> voxelwise; ///< within kWindingMargin of 1/2: to classify voxel by voxel
    std::vector<BrickCoord> inside;    ///< the others at or above 1/2: wholly inside
};

/// @brief The rule for the bricks of a box of the grid's bricks that are not in the band.
/// @param centres   windingAtBrickCentres (or the GPU's per-brick numbers), x-fastest over the box
/// @param brickDims the box in bricks
/// @param band      the band's bricks, sorted (x-major) and unique; those outside the box are passed over
/// @param origin    the box's first brick
/// @return both lists in x-major order
BricksBeyondBand bricksBeyondBand(const std::vector<float>& centres, const std::array<uint32_t, 3>& brickDims,
                                  const std::vector<BrickCoord>& band, const std::array<uint32_t, 3>& origin = {0, 0, 0});

} // namespace svo
