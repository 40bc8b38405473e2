#pragma once
/// @file field_join.h
/// @brief Fields and solids of regions joined into those of their union, on
/// the bricks: how a NanoVDB grid past a GPU memory budget or past one shader
/// buffer is laid out without an OpenVDB tree.
///
/// Regions cut from a grid's box along x and y, in whole bricks, share no
/// brick (their bounds and the grid's anchor are multiples of 8), and each
/// region's bricks are exactly the whole grid's there (a parity-signed
/// region holds whole columns). So joining every region's field gives the
/// whole grid's field, and its grids are the whole grid's, byte for byte.
#include "svo/core/field_bricks.h"

namespace svo {

/// @brief Adds the bricks of @a more, the field of another region of the same
/// grid, to @a into: the band's bricks with their near masks, distances,
/// closest triangles and (signed fields) inside voxels; beyond the band, the
/// signs' runs, inside bricks and partly inside bricks.
/// @param into a field; keeps its bricks, and its signs' lists, sorted and unique
/// @param more a field of the same grid and kind; left empty
/// @throw svo::InvalidInput for fields of different grids, kinds (signed,
///        winding) or requests (closest triangles), values or signs that do
///        not match the bricks, or a brick in both
/// @throw svo::Unsupported when the joined field holds more than 2^32 values
void joinFields(DistanceBricks& into, DistanceBricks&& more);

/// @brief Adds @a more, the solid of another region of the same grid, to
/// @a into: its band bricks with their inside voxels, and the signs beyond.
/// @param into a solid; keeps its bricks, and its signs' lists, sorted and unique
/// @param more a solid of the same grid; left empty
/// @throw svo::InvalidInput for solids of different grids, signs that do not
///        match the bricks, or a brick in both
void joinSolids(SolidBricks& into, SolidBricks&& more);

} // namespace svo
