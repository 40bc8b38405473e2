#pragma once
/// @file nanovdb_grids.h
/// @brief svo's sparse results (octree bricks, distance and solid bricks) as
/// NanoVDB grids, laid out directly (svo/vdb_io/nanovdb_layout.h) with no
/// OpenVDB tree. Each grid equals, voxel for voxel and value for value, what
/// nanovdb::openToNanoVDB makes of the OpenVDB grid the same data gives
/// (grid_builder.h, field_grids.h): the same names, classes, backgrounds,
/// active voxels and values, inactive values included.
#include <string>
#include <vector>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/HostBuffer.h>

#include "svo/core/field_bricks.h"
#include "svo/core/octree.h"
#include "svo/vdb_io/grid_options.h"
#include "svo/vdb_io/nanovdb_layout.h"

namespace svo::vdb {

using NanoHandle = nanovdb::GridHandle<nanovdb::HostBuffer>;

/// @brief An octree's voxels as NanoVDB grids, in octreeToGrids' order: the
/// topology (ValueMask, or bool true on voxels, named grids.name), "density"
/// (fog, 1 on voxels, background 0, class FogVolume) when asked, then the
/// channels "normal" (Vec3f), "triangle_id" (Int32, background -1) and
/// "color" (Vec3f) when asked and present. Transform: the octree's lattice.
/// @param checksum whether each grid gets a full CRC32
std::vector<NanoHandle> octreeToNanoGrids(const Octree& octree, const GridOptions& grids = {}, bool checksum = true);

/// @brief One channel of an octree as sparse voxels: its octree's leaves
/// (occupied bricks, in octreeToNanoGrids' order), 512 values each, the
/// channel's value on active voxels and the background elsewhere.
struct OctreeChannel {
    std::string name;                       ///< "normal", "triangle_id" or "color"
    bool vector = true;                     ///< Vec3f (background 0) or Int32 (background -1)
    SparseVoxels<nanovdb::Vec3f> vectors;   ///< when `vector`
    SparseVoxels<int32_t> ints;             ///< otherwise
};

/// @brief The channels octreeChannelNanoGrids lays out, in its order, as
/// sparse voxels (for a builder of the caller's: the GPU's).
/// @param grids whether channels are asked for (GridOptions::attributes)
/// @return one entry per channel the octree holds, none when not asked
std::vector<OctreeChannel> octreeChannelVoxels(const Octree& octree, const GridOptions& grids = {});

/// @brief The channel grids of octreeToNanoGrids alone ("normal",
/// "triangle_id", "color"), for callers that lay out the topology and fog
/// elsewhere (on the GPU: svo::Voxelizer::voxelizeNanoVdb).
/// @param checksum whether each grid gets a full CRC32
std::vector<NanoHandle> octreeChannelNanoGrids(const Octree& octree, const GridOptions& grids = {}, bool checksum = true);

/// @brief A distance field as NanoVDB grids, as levelSetGrids (field_grids.h):
/// "surface" (class LevelSet) or "distance" (class Unknown), float, background
/// the exterior band in world units, then "closest_triangle" (Int32,
/// background -1) when it was computed.
/// @param lattice the grid whose transform the grids take (the caller's, not the field's padded grid)
std::vector<NanoHandle> levelSetNanoGrids(const DistanceBricks& field, double exteriorBand, double interiorBand,
                                          const GridSpec& lattice, bool checksum = true);

/// @brief OpenVDB's signed flood fill (tools::signedFloodFill, which the
/// OpenVDB path runs on level sets signed by parity) on a NanoVDB level set
/// laid out from leaves whose values carry their signs (levelSetNanoGrids,
/// or the GPU builder's grid of the same leaves): in each node, bottom up,
/// the inactive values and tiles take the sign of the last active value or
/// child met along x, then y, then z, and the background's magnitude. The
/// grid's checksum is not updated (updateFullChecksum does).
/// @param grid a grid with leaves and internal nodes, no root tiles
void signedFloodFill(nanovdb::NanoGrid<float>& grid);

/// @brief The voxels of an unsigned field nearer than @a band as the grid
/// "band" (bandGrid's voxels, field_grids.h): a leaf per brick with such a
/// voxel, no values.
/// @param lattice  the grid whose voxel size and translation the grid takes
/// @param topology ValueMask, class Topology (Mask), or bool true on every active voxel (Bool)
NanoHandle bandNanoGrid(const DistanceBricks& field, double band, const GridSpec& lattice,
                        GridOptions::Topology topology = GridOptions::Topology::Mask, bool checksum = true);

/// @brief A solid's voxels as solidNanoGrid lays them out: a leaf per brick
/// with an inside voxel (its mask the inside voxels), whole bricks inside as
/// active 8³ tiles (level 1, value true); values left empty.
/// @param solid the solid's bricks and signs
/// @return the leaves and tiles, in no particular order
SparseVoxels<bool> solidVoxels(const SolidBricks& solid);

/// @brief A solid as the grid "solid", as solidGrid (field_grids.h) and
/// withTopology (reader_grids.h) give it: inside voxels active, whole bricks
/// inside as active 8³ tiles.
/// @param topology ValueMask (Mask), or bool with true on every active voxel and tile (Bool)
NanoHandle solidNanoGrid(const SolidBricks& solid, const GridSpec& lattice,
                         GridOptions::Topology topology = GridOptions::Topology::Mask, bool checksum = true);

} // namespace svo::vdb
