#pragma once
/// @file reader_grids.h
/// @brief Grids every OpenVDB reader opens. python3-openvdb (pyopenvdb as
/// Debian 12 builds it, OpenVDB 10) wraps BoolGrid, FloatGrid and Vec3SGrid
/// only, and refuses a whole file (readAll, readAllGridMetadata) when any one
/// grid in it has another type. svo's other grids are its triangle indices
/// (Int32Grid "triangle_id", "closest_triangle"), which therefore go to a
/// file of their own beside the output, and a solid's MaskGrid, which
/// becomes a BoolGrid of the same topology unless a MaskGrid is asked for.
#include <openvdb/Grid.h>
#include <openvdb/openvdb.h>
#include <string>
#include <utility>

#include "svo/vdb_io/grid_options.h"

namespace svo::vdb {

/// @brief The file beside a .vdb output that holds its triangle-index grids:
/// "out.vdb" -> "out.triangle.vdb" (same folder; the extension replaced).
/// @param path the .vdb output
/// @return the sidecar's path
std::string triangleSidecarPath(const std::string& path);

/// @brief Marks @a sidecarGrids as the triangle indices of @a output:
/// metadata "svo:sidecar_of", the output's file name (no folder), by which a
/// later run that writes @a output without them knows the sidecar as the
/// stale one of an earlier run (isTriangleSidecarOf).
/// @param sidecarGrids the grids written to triangleSidecarPath(@a output)
/// @param output the .vdb output they belong to
void markTriangleSidecar(const openvdb::GridPtrVec& sidecarGrids, const std::string& output);

/// @brief Whether the file at triangleSidecarPath(@a output) is a sidecar svo
/// wrote for @a output: a regular file (not a link) that OpenVDB opens, whose
/// grids, one or more, are all Int32Grids marked by markTriangleSidecar with
/// @a output's file name. Reads the grids' metadata only.
/// @param output a .vdb output
/// @return false for a missing, unreadable or foreign file; never throws
bool isTriangleSidecarOf(const std::string& output);

/// @brief Whether python3-openvdb reads a grid of this type (bool, float, Vec3s).
/// @param grid any grid
/// @return true for BoolGrid, FloatGrid and Vec3SGrid
bool pyopenvdbReads(const openvdb::GridBase& grid);

/// @brief Splits grids into those that stay in the output and the triangle
/// indices (Int32Grid) that go to triangleSidecarPath(), each keeping its order.
/// @param grids the grids of one output
/// @return (the output's grids, the sidecar's grids); the second is empty when
///         no grid holds triangle indices
std::pair<openvdb::GridPtrVec, openvdb::GridPtrVec> splitTriangleGrids(const openvdb::GridPtrVec& grids);

/// @brief A solid (or any mask) as the topology GridOptions asks for: the same
/// active voxels and active tiles, its name, transform, class and metadata.
/// @param mask  the MaskGrid (Voxelizer::solid)
/// @param topology Bool: a BoolGrid, true where active and false elsewhere;
///        Mask: @a mask itself
/// @return the grid to write
openvdb::GridBase::Ptr withTopology(openvdb::MaskGrid::Ptr mask, GridOptions::Topology topology);

} // namespace svo::vdb
