#pragma once
/// @file field_clip.h
/// @brief A region's field or solid cut to its box of bricks: what the
/// region's passes computed beyond it (a parity column's bricks above and
/// below the region, which its crossings needed) left out, as OpenVDB's
/// Grid::clip cuts a grid to a box of whole leaves.
#include "svo/core/field_bricks.h"
#include "svo/core/voxel_box.h"

namespace svo {

/// @brief Leaves out of @a field what lies outside @a box: band bricks with
/// their masks, distances, closest triangles and inside voxels; parity
/// runs cut to the box; winding's inside and partly inside bricks.
/// @param box brick coordinates of the field's grid, [lo, hi) per axis
void clipField(DistanceBricks& field, const BrickBox& box);

/// @brief clipField for a solid: its band bricks with their inside voxels,
/// and its signs beyond the band.
void clipSolid(SolidBricks& solid, const BrickBox& box);

} // namespace svo
