#pragma once
/// @file voxelize_settings.h
/// @brief svo::VoxelizeSettings: what a voxelization computes and where
/// (voxelize_pipeline.h runs it), each option declared once for every front end.
#include <cstdint>
#include <optional>

#include "svo/core/option_info.h"
#include "svo/core/region.h"
#include "svo/core/voxel_mode.h"
#include "svo/gl/backend.h"
#include "svo/gl/dilation.h"

namespace svo {

/// @brief What a voxelization computes and where. Plain values; the defaults suit most uses.
struct VoxelizeSettings {
    Backend backend = Backend::Auto; ///< where it runs
    /// Which voxels a triangle covers: Conservative (every voxel whose closed
    /// cube it meets; 26-separating) or Thin (every voxel one of whose three
    /// axis-aligned centre segments it meets; 6-separating, fewer voxels).
    /// Every backend and dilation computes both; the grid and guard band are
    /// the same.
    VoxelMode mode = VoxelMode::Conservative;
    /// Raster backend only: any mode but Auto makes Backend::Auto pick Raster,
    /// and is an error with Backend::Compute.
    Dilation dilation = Dilation::Auto;
    /// Per-voxel channels to compute: AttributeChannel bits (kNormals,
    /// kTriangles, kColors). Colours need vertex colours and are left out otherwise.
    uint32_t attributes = 0;
    /// GPU bytes a voxelization may allocate. A grid whose voxel list or
    /// octree needs more is cut into tiles of whole bricks, voxelized one
    /// after another and merged on the host: the same voxels and channels
    /// (VoxelizeStats::tiles says how many). 0: what the device reports free,
    /// less a margin (unbounded where the driver does not tell). Level sets
    /// and solids past a budget given here are computed in regions of the
    /// grid and joined (the front door; docs/design.md §7e); without one,
    /// they report running out of memory. Backend::Cpu refuses a budget
    /// (InvalidInput): it allocates no GPU memory.
    uint64_t gpuMemory = 0;
    /// Only the voxels of this box of whole leaves (svo/core/region.h), in
    /// the grid's index space: exactly what the whole-grid call gives there,
    /// with the work cut to the box (docs/design.md, "Regions"). None: the whole grid.
    std::optional<IndexBox> region;
};

/// @brief Each option of VoxelizeSettings, declared once for every front end
/// (svo/core/option_info.h).
template <typename Visit>
void forEachOption(VoxelizeSettings& s, Visit&& visit)
{
    visit(OptionInfo{"VoxelizeOptions::backend", "backend",
                     "Where voxelization runs: auto (compute on a GPU, cpu on llvmpipe or without GL: the faster "
                     "there), raster, compute (GPU compute shaders, the same voxels), or cpu (double-precision reference)"},
          s.backend);
    visit(OptionInfo{"VoxelizeOptions::mode", "mode",
                     "Which voxels a triangle covers: conservative (every voxel whose cube meets a triangle; "
                     "26-separating) or thin (every voxel one of whose three axis-aligned centre segments meets a "
                     "triangle; 6-separating)"},
          s.mode);
    visit(OptionInfo{"VoxelizeOptions::dilation", "conservative",
                     "Raster dilation: auto, hardware (GL_NV_conservative_raster), shader, or centroid (the seed "
                     "report's vertex push; a benchmark baseline that misses voxels)"},
          s.dilation);
    visit(OptionInfo{"VoxelizeOptions::attributes", "attributes",
                     "Per-voxel channels: normal, triangle (smallest triangle id), color (needs vertex colours)"},
          ChannelSet{s.attributes});
    visit(OptionInfo{"VoxelizeOptions::gpuMemory", "gpu_memory",
                     "GPU memory a voxelization may use (e.g. 8G, 512M); a grid that needs more is voxelized in tiles "
                     "and merged, with the same voxels (default: what the device reports free)"},
          ByteCount{s.gpuMemory});
    visit(OptionInfo{"VoxelizeOptions::region", "region",
                     "Only the voxels of this box of the grid's index space, [lo, hi) with every bound a multiple of "
                     "8: exactly the whole grid's result there (default: the whole grid)"},
          RegionOption{s.region});
}

} // namespace svo
