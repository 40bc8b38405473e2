#pragma once
/// @file join_region.h
/// @brief Joins the grids of disjoint regions (svo/core/region.h) into one:
/// what a run in tiles (svo.distributed) does with its tiles' grids.
#include <openvdb/Grid.h>

namespace svo::vdb {

/// @brief Moves the grid of one region into the grid of other regions it does
/// not meet (regions are whole leaves, so no leaf is shared): its leaves, its
/// active tiles and its inactive tiles that are not background (a level
/// set's interior beyond the band, a solid's inside). OpenVDB's merge
/// policies drop an inactive tile wherever the target already has a node, so
/// the tiles are set first, at their own level, then the nodes move.
/// @param into the grid of the regions so far
/// @param part a region's grid, of the same type and background; left empty
/// @throw svo::InvalidInput for grids of different types or backgrounds, or
///        a type other than bool, mask, float, int32 and vec3s
void joinRegion(openvdb::GridBase& into, openvdb::GridBase& part);

} // namespace svo::vdb
