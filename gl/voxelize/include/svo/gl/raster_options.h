#pragma once
/// @file raster_options.h
/// @brief svo::gl::RasterOptions: what voxelizeRaster and voxelizeToOctree
/// (raster_voxelizer.h) compute, and within what GPU memory.
#include <cstdint>
#include <optional>
#include <vector>

#include "svo/core/interrupt.h"
#include "svo/core/voxel_box.h"
#include "svo/core/voxel_mode.h"
#include "svo/gl/conservative_mode.h"
#include "svo/gl/pipeline.h"

namespace svo::gl {

/// @brief Options of voxelizeRaster and voxelizeToOctree.
struct RasterOptions {
    /// Raster draws or compute dispatches; the octree build is the same.
    Pipeline pipeline = Pipeline::Raster;
    /// Auto: GL_NV_conservative_raster when present, else shader dilation.
    ConservativeMode conservative = ConservativeMode::Auto;
    /// Which voxels a triangle covers: its voxels' cubes (conservative) or
    /// their centre segments (thin). Both backends, every dilation.
    VoxelMode mode = VoxelMode::Conservative;
    /// Voxel-list entries to allocate first; 0 estimates from triangle areas.
    uint64_t initialCapacity = 0;
    /// Octree bricks to allocate first (voxelizeToOctree); 0 estimates from the list size.
    uint64_t initialBrickCapacity = 0;
    /// Per-voxel channels to compute (AttributeChannel bits; voxelizeToOctree
    /// only). Colours are skipped when the mesh has none.
    uint32_t attributes = 0;
    /// Guard band in voxels; negative means grid.epsilon(). Other values are
    /// for experiments only (docs/stability.md shows what 0 and too much do).
    double guardBand = -1.0;
    /// GPU bytes the call may allocate (voxelizeToOctree): the mesh, the work
    /// list, the voxel list, the octree build and the attribute pass. When a
    /// grid needs more, it is cut into tiles of whole bricks that are
    /// voxelized one after another and merged on the host: the same octree,
    /// in canonical order (canonicalOrder()). 0: what the device reports free
    /// (Context::availableMemory(), less a margin; unbounded when unknown).
    /// Grids whose list passes 2^32 entries or whose octree passes 2^28
    /// bricks are tiled the same way, whatever the budget.
    uint64_t gpuMemory = 0;
    /// Polled between stages and between viewport tiles; throws svo::Interrupted to stop.
    Checkpoint checkpoint;
    /// voxelizeToOctree only: when set, also receives the voxel list itself
    /// (sorted, unique keys), read back apart from the octree, so a check can
    /// compare the two without rasterizing again.
    std::vector<uint64_t>* voxelList = nullptr;
    /// voxelizeToOctree only: when set, only the voxels of this local box
    /// (its lo a multiple of 8), tiled within it past the budget. None: the whole grid.
    std::optional<VoxelBox> box;
};

} // namespace svo::gl
