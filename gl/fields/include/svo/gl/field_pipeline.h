#pragma once
/// @file field_pipeline.h
/// @brief Level sets, unsigned distance fields and solids of a mesh on svo's
/// own types: the band's bricks from the triangles (a solid's from its
/// surface voxels), distances there on the GPU (distance_field.h), and signs
/// by parity crossings or winding numbers (winding_number.h). What
/// svo::Voxelizer runs, usable without OpenVDB; the converter
/// (svo/vdb_io/field_grids.h) makes grids of the result.
#include <string>

#include "svo/core/field_bricks.h"
#include "svo/core/field_options.h"
#include "svo/core/grid.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/gl/device.h"
#include "svo/gl/voxelize_pipeline.h"

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
/// on the GPU (the settings' backend only refuses Backend::Cpu).
/// @details Every voxel centre within the band of a triangle gets its exact
/// distance in double precision, rounded once to float; signed fields get
/// each band voxel's side, and (winding) the bricks beyond the band inside.
/// The result's grid is @a grid padded by the band.
/// @param checkpoint polled between stages with the fraction done (to 0.85)
/// @param stats      receives stages, counts, the sign method and why, warnings
/// @throw svo::Error for options that fail checkLevelSetOptions or
///        checkFieldMode, the CPU backend, parity signs asked for a mesh with
///        holes, a band wider than one pass holds, no usable GPU or GPU
///        memory exhausted; svo::Interrupted.
DistanceBricks levelSetBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                              const LevelSetOptions& levelSet, const VoxelizeSettings& settings,
                              const Checkpoint& checkpoint, VoxelizeStats& stats);

/// @brief The solid a checked mesh bounds on a checked grid: every voxel whose
/// centre is inside, plus the surface voxels (conservative, as voxelizeMesh).
/// @param checkpoint polled between stages with the fraction done (to 0.8)
/// @throw svo::Error as levelSetBricks.
SolidBricks solidBricks(Device& device, const TriangleMesh& mesh, const GridSpec& grid,
                        const VoxelizeSettings& settings, const SignOptions& sign, const Checkpoint& checkpoint,
                        VoxelizeStats& stats);

} // namespace gl
} // namespace svo
