#pragma once
/// @file voxelize_pipeline.h
/// @brief Meshes and bricks to octrees on svo's own types, backend choice
/// included: what svo::Voxelizer runs, usable without OpenVDB.
///
/// The backends (raster_voxelizer.h, octree_builder.h and the CPU reference,
/// svo/core/cpu_voxelizer.h) each do one job; this file picks one for a call
/// and gathers what it measured. Callers check the mesh and grid first
/// (validateMesh, checkGrid).
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/region.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/core/option_info.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_mode.h"
#include "svo/core/voxelization.h"
#include "svo/gl/device.h"

namespace svo {

/// @brief Where voxelization runs.
enum class Backend {
    Auto,    ///< Compute on a GPU, Raster on a software renderer (llvmpipe): the faster of the two there (bench/results/*/compute.md)
    Raster,  ///< GPU: rasterization along each triangle's dominant axis
    Compute, ///< GPU: triangle-parallel compute shaders; the same voxels as Raster
    Cpu,     ///< the double-precision CPU reference (tests; no GL context needed)
};

/// @brief How the raster backend enlarges triangles so no touched column is missed.
enum class Dilation {
    Auto,         ///< Hardware where GL_NV_conservative_raster exists, else Shader
    Hardware,     ///< GL_NV_conservative_raster; an error where it is missing
    Shader,       ///< edge offsets in the geometry shader
    CentroidPush, ///< an early vertex-push method; misses voxels; benchmarks only
};

/// @brief The names of Backend and Dilation, as the command line and Python write them.
inline constexpr EnumName<Backend> kBackendNames[] = {
    {Backend::Auto, "auto"}, {Backend::Raster, "raster"}, {Backend::Compute, "compute"}, {Backend::Cpu, "cpu"}};
constexpr const auto& enumNames(Backend) { return kBackendNames; }
inline constexpr EnumName<Dilation> kDilationNames[] = {{Dilation::Auto, "auto"},
                                                        {Dilation::Hardware, "hardware"},
                                                        {Dilation::Shader, "shader"},
                                                        {Dilation::CentroidPush, "centroid"}};
constexpr const auto& enumNames(Dilation) { return kDilationNames; }

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
    /// and solids do not tile yet: they report running out of memory instead.
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
                     "Where voxelization runs: auto (compute on a GPU, raster on llvmpipe: the faster there), raster, "
                     "compute (GPU compute shaders, the same voxels), or cpu (double-precision reference)"},
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

/// @brief What one call measured. Kept apart from the result; filled only when asked.
struct VoxelizeStats {
    std::vector<StageTime> stages; ///< GPU (timer queries) and wall milliseconds per stage
    uint64_t voxels = 0, bricks = 0; ///< the result's voxels and bricks
    uint64_t listEntries = 0;      ///< voxel-list entries written, duplicates included
    int overflowRetries = 0;       ///< passes repeated because a GPU buffer was too small
    uint32_t tiles = 1;            ///< boxes the grid was voxelized in to stay within GPU memory (1: all at once)
    uint64_t gpuBytes = 0;         ///< GPU buffer bytes the call used (reused scratch counts at its full size)
    double epsilon = 0;            ///< guard band in voxels
    std::string backend;           ///< "raster", "compute" or "cpu"
    std::string mode;              ///< "conservative" or "thin"; empty for grids and bricks, which are not voxelized
    std::string dilation;          ///< "hardware", "shader", "centroid-push (baseline)"; empty for cpu
    std::string device;            ///< "vendor | renderer | version (EGL device)", or "cpu"
    std::string renderer;          ///< GL renderer string, or "cpu"
    GridSpec grid;                 ///< the local grid the call used
    /// What was asked for but could not be given (colours without vertex
    /// colours), one sentence each. Warnings name no option by its identifier
    /// (LevelSetOptions::exteriorBand, ...), so front ends show them as they
    /// are; a warning about an option would need its identifier kept apart,
    /// as svo::Error keeps it.
    std::vector<std::string> warnings;
    std::string sign;              ///< level sets and solids: the sign method used and why ("parity: closed and ...")
    uint64_t openColumns = 0;      ///< level sets and solids: voxel columns crossed an odd number of times (open mesh)
    uint64_t bandBricks = 0;       ///< level sets and solids: bricks whose distances or signs were computed
    uint64_t windingBricks = 0;    ///< winding signs: bricks beyond the band classified voxel by voxel
    /// Start-up paid since the previous call returned: the context if this
    /// call created it, and the programs this call made. Kept apart from
    /// `stages`, whose wall times exclude it.
    StartupStats startup;
    double gpuMs() const;          ///< the sum of the stages' GPU times
};

/// @brief Statistics of repeated runs: each stage's median GPU and wall time;
/// the other fields are the last run's.
/// @throw svo::InvalidInput for an empty list
VoxelizeStats medianStats(const std::vector<VoxelizeStats>& runs);

namespace gl {

/// @brief The backend a call with @a settings runs on: Backend::Auto resolved
/// (a dilation mode's raster backend when one is asked for; else the CPU
/// where there is no GL (Device::withoutGl) or the GL device is a software
/// rasterizer such as llvmpipe, unless the device was named (Device::named)
/// or a GPU memory budget given: then raster on a software device and
/// compute on a hardware GPU).
/// @param create with false and no context yet, none is created (Device::software,
///        Device::withoutGl)
/// @return never Backend::Auto
/// @throw svo::InvalidInput for a dilation mode with Backend::Compute
/// @throw svo::DeviceError when @a create makes a context for a named device
///        that cannot have one
Backend resolveBackend(Device& device, const VoxelizeSettings& settings, bool create = true);

/// @brief Whether a call with @a settings runs on the CPU: Backend::Cpu, or
/// Backend::Auto (with no dilation mode) where resolveBackend would pick the
/// CPU. For the passes whose GPU path has no raster/compute choice (level
/// sets, solids). Throws nothing.
/// @param create as for resolveBackend
bool runsOnCpu(Device& device, const VoxelizeSettings& settings, bool create = true);

/// @brief Where a call runs, in its statistics: backend, device and renderer
/// names (the GPU's, or "cpu").
/// @param stats receives VoxelizeStats::backend, device and renderer
/// @throw svo::DeviceError when @a backend is a GPU one and no context can
///        be made
void describeBackend(Device& device, Backend backend, VoxelizeStats& stats);

/// @brief The voxels of a checked mesh on a checked grid, as an octree.
/// @param checkpoint polled between stages and tiles with the fraction done
/// @param stats      receives the stages, counts, backend and warnings
/// @param voxelList  when set, also the backend's voxel set (sorted, unique keys)
/// @return the octree, in canonical order, with the channels asked for
/// @throw svo::InvalidInput for a dilation mode with the compute backend
/// @throw svo::DeviceError, svo::OutOfMemory, svo::Unsupported as the
///        backends (voxelizeToOctree, voxelizeCpu): no usable GPU, out of
///        GPU or host memory, a grid beyond one octree
/// @throw svo::Interrupted from the checkpoint
Octree voxelizeMesh(Device& device, const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeSettings& settings,
                    const Checkpoint& checkpoint, VoxelizeStats& stats, std::vector<uint64_t>* voxelList = nullptr);

/// @brief Whole bricks (brick-origin key, mask) on a checked grid, built into
/// an octree on the GPU, or on the CPU with Backend::Cpu.
/// @param backend Backend::Cpu, or any other for the GPU (already resolved)
/// @param stats   receives the stages, counts and backend
/// @return the octree, in canonical order
/// @throw as buildOctreeGpu (the GPU) or buildOctreeFromBricks (the CPU)
Octree bricksToOctree(Device& device, const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> bricks,
                      Backend backend, const Checkpoint& checkpoint, VoxelizeStats& stats);

} // namespace gl
} // namespace svo
