#pragma once
/// @file field_join.h
/// @brief Unsigned distance fields of regions joined into the field of their
/// union, on the bricks: how a NanoVDB grid past a GPU memory budget or past
/// one shader buffer is laid out without an OpenVDB tree.
#include "svo/core/field_bricks.h"

namespace svo {

/// @brief Adds the bricks of @a more, the field of another region of the same
/// grid, to @a into. Regions share no brick (their bounds and the grid's
/// anchor are multiples of 8), and each region's bricks are exactly the whole
/// grid's there, so joining every region's field gives the whole grid's.
/// @param into an unsigned field; keeps its bricks sorted and unique
/// @param more an unsigned field of the same grid; left empty
/// @throw svo::InvalidInput for a signed field, fields of different grids or
///        of different requests (closest triangles), or a brick in both
/// @throw svo::Unsupported when the joined field holds more than 2^32 values
void joinUnsignedFields(DistanceBricks& into, DistanceBricks&& more);

} // namespace svo
