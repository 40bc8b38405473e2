#pragma once
/// @file field_pipeline.h
/// @brief Level sets, unsigned distance fields and solids of a mesh on svo's
/// own types: the band's bricks from the triangles (a solid's from its
/// surface voxels), distances there on the GPU (distance_field.h) or the CPU, and signs
/// by parity crossings or winding numbers (winding_number.h). What
/// svo::Voxelizer runs, usable without OpenVDB; the converter
/// (svo/vdb_io/field_grids.h) makes grids of the result.
#include <optional>
#include <string>
#include <vector>

#include "svo/core/field_bricks.h"
#include "svo/core/field_options.h"
#include "svo/core/grid.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/gl/device.h"
#include "svo/gl/field_result.h"
#include "svo/gl/voxelize_settings.h"
#include "svo/gl/voxelize_stats.h"

namespace svo {

/// @name The rules of the options' numbers (more in svo/core/field_options.h)
/// @{
/// The voxel mode of a level set or solid call: only VoxelMode::Conservative
/// (the default); a mode is a rule for surface voxels, and the distances, the
/// band and the inside do not depend on it.
void checkFieldMode(const VoxelizeSettings& settings);
/// @}

namespace gl {

/// @brief A narrow-band distance field of a checked mesh on a checked grid,
/// on the GPU's compute passes, or on the CPU (TBB, no GL context) when the
/// settings ask for Backend::Cpu; both give the same field.
/// @details Every voxel centre within the band of a triangle gets its exact
/// distance in double precision, rounded once to float; signed fields get
/// each band voxel's side, and (winding) the bricks beyond the band inside.
/// The result's grid is @a grid padded by the band. The CPU path's parts:
/// svo/core/band_bricks.h, band_distances.h, parity_crossings.h, winding_signs.h.
/// @param checkpoint polled between stages with the fraction done (to 0.85)
/// @param stats      receives stages, counts, the sign method and why, warnings
/// @throw svo::Error for options that fail checkLevelSetOptions or
///        checkFieldMode, parity signs asked for a mesh with holes, a band
///        wider than one pass holds, no usable GPU or GPU memory exhausted
///        (GPU backends); svo::Interrupted.
DistanceBricks levelSetBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                              const LevelSetOptions& levelSet, const VoxelizeSettings& settings,
                              const Checkpoint& checkpoint, VoxelizeStats& stats);

/// @brief Whether unsignedFieldLeaves takes a call: an unsigned field
/// (LevelSetOptions::unsignedDistance) without a region, on a GL backend
/// (the compute or raster backends, or Auto on a hardware GPU; not
/// Backend::Cpu, nor Auto on a software renderer).
/// @param device may make its GL context, to see the renderer
bool unsignedFieldOnDevice(Device& device, const LevelSetOptions& levelSet, const VoxelizeSettings& settings);

/// @brief A field's band left on the device as NanoVDB leaves.
struct DeviceField {
    GridSpec grid;            ///< the field's grid: the mesh's padded by the band, as levelSetBricks gives it
    FieldLeaves leaves;       ///< the device's leaves (field_result.h: the buffers' lifetime)
    bool signedField = false; ///< values inside negated
    /// Signed by winding numbers: the leaves also hold the bricks beyond the
    /// band with inside voxels (after FieldLeaves::activeCount), and
    /// `insideBricks` are the whole bricks inside beyond it (inactive tiles
    /// of the negated background). By parity (not winding): the values
    /// beyond the band are still unsigned (a signed flood fill's).
    bool winding = false;
    std::vector<BrickCoord> insideBricks;
};

/// @brief levelSetBricks for an unsigned field on the GPU, its band left on
/// the device as the leaves of the grid svo::vdb::levelSetNanoGrids lays out
/// from levelSetBricks' result: the bricks with a voxel nearer than the
/// exterior band, the distances in world units (voxel size @a grid's), the
/// exterior band in world units beyond (band_leaves.comp). Only the leaf
/// count is read back. Feed them to svo::gl::buildNanoGridGpu.
/// @param checkpoint polled between stages with the fraction done (to 0.85)
/// @param stats      receives the stages ("band leaves" in place of "band
///        packing"), counts, warnings
/// @throw as levelSetBricks; svo::InvalidInput where unsignedFieldOnDevice is false
DeviceField unsignedFieldLeaves(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                                const LevelSetOptions& levelSet, const VoxelizeSettings& settings,
                                const Checkpoint& checkpoint, VoxelizeStats& stats);

/// @brief The unsigned field whose active voxels are a band of @a band
/// voxels (both bands @a band): what bandTopologyBricks and
/// bandTopologyLeaves compute. Throws nothing (setUpField checks the band).
LevelSetOptions bandFieldOptions(double band);

/// @brief levelSetBricks for the unsigned field of @a band voxels, computed
/// as only its voxels nearer than the band ask (a band's topology): a voxel
/// found nearer takes no more triangles, on the GPU and the CPU alike, so
/// DistanceBricks::near is the field's exactly and the distances are not
/// the least.
/// @param band the band half width in voxels (checkBand)
/// @throw as levelSetBricks
DistanceBricks bandTopologyBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid, double band,
                                  const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats);

/// @brief The voxels nearer than @a band to a triangle (a band's topology)
/// left on the device as leaves without values: unsignedFieldLeaves'
/// leaves and masks for an unsigned field of that band, computed as only
/// the set asks (FieldRequest::bandOnly: a voxel already nearer than the
/// band takes no more distances). Feed them to svo::gl::buildNanoGridGpu
/// as a mask or bool grid.
/// @param band the band half width in voxels (checkBand)
/// @throw as unsignedFieldLeaves
DeviceField bandTopologyLeaves(Device& device, const TriangleMesh& mesh, const GridSpec& grid, double band,
                               const VoxelizeSettings& settings, const Checkpoint& checkpoint, VoxelizeStats& stats);

/// @brief A level set's band, where it can stay on the device, or read back.
struct LevelSetBand {
    std::optional<DeviceField> device; ///< a GL backend and no region
    DistanceBricks host;               ///< otherwise: levelSetBricks' result
};

/// @brief levelSetBricks, or its band left on the device as the leaves
/// levelSetNanoGrids lays out (as unsignedFieldLeaves) where it can be: on a
/// GL backend, without a region.
/// Parity signs: the crossings come back and are scanned on the host; the
/// inside voxels go back up and are negated in the leaves, background
/// included; the values beyond the band (signed flood fill) are the
/// caller's, as levelSetNanoGrids does them on its grid. Winding numbers:
/// computed first (their inside voxels come back), then uploaded and
/// negated in the leaves as parity's are; bricks with inside voxels and
/// none active take leaves too, the bricks beyond the band classified voxel
/// by voxel are added as leaves, and the whole bricks inside are left to
/// the caller as tiles (DeviceField::insideBricks).
/// @param checkpoint polled between stages with the fraction done (to 0.85)
/// @param stats      receives stages, counts, the sign method and why, warnings
/// @throw as levelSetBricks
LevelSetBand levelSetBand(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                          const LevelSetOptions& levelSet, const VoxelizeSettings& settings,
                          const Checkpoint& checkpoint, VoxelizeStats& stats);

/// @brief The solid a checked mesh bounds on a checked grid: every voxel whose
/// centre is inside, plus the surface voxels (conservative, as voxelizeMesh);
/// on the CPU when the settings ask for Backend::Cpu, with the same result.
/// @param checkpoint polled between stages with the fraction done (to 0.8)
/// @throw svo::Error as levelSetBricks.
SolidBricks solidBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                        const VoxelizeSettings& settings, const SignOptions& sign, const Checkpoint& checkpoint,
                        VoxelizeStats& stats);

} // namespace gl
} // namespace svo
