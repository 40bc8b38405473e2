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
#include "svo/core/grid.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh.h"
#include "svo/gl/device.h"
#include "svo/gl/voxelize_pipeline.h"

namespace svo {

/// How level sets and solids tell inside from outside.
enum class SignMethod {
    /// Parity when the mesh is closed and consistently oriented (after welding
    /// vertices at equal positions), the winding number otherwise; the
    /// statistics say which and why.
    Auto,
    /// Crossings counted along voxel columns, with exact tie rules: a voxel
    /// centre on a face, edge or vertex never flips the result. Correct for
    /// closed meshes, including nested shells; used as asked on others.
    Parity,
    /// The generalized winding number (svo/core/winding_tree.h) thresholded at
    /// 1/2: sensible insides for holes, soups and overlapping parts. At every
    /// voxel of the band, and of any brick beyond it whose centre's winding
    /// number is within 1/4 of 1/2; other bricks beyond the band take the
    /// side of their centre.
    Winding,
};

/// The sign method and its accuracy.
struct SignOptions {
    SignMethod method = SignMethod::Auto;
    /// Winding numbers: tree nodes farther than this many times their radius
    /// add their far field, expanded to second order, instead of their
    /// triangles (Barill et al. 2018's beta; larger is slower and more exact;
    /// positive and finite, checkWindingAccuracy: 1e300 evaluates every triangle).
    double windingAccuracy = 1.5;
    SignOptions(SignMethod m = SignMethod::Auto, double accuracy = 1.5) : method(m), windingAccuracy(accuracy) {}
};

/// What a level set (or unsigned distance field) holds.
struct LevelSetOptions {
    double exteriorBand = 3.0;     ///< active band outside the surface, in voxels (>= 1)
    double interiorBand = 3.0;     ///< active band inside, in voxels (>= 1); unused when unsigned
    bool unsignedDistance = false; ///< distances without sign: no inside/outside needed
    bool closestTriangle = false;  ///< also an Int32Grid "closest_triangle" on the band
    SignOptions sign;
};

/// @name The rules of the options' numbers
/// One rule per number, for every front door: the library checks its options
/// with them (naming the field, e.g. LevelSetOptions::exteriorBand), and the
/// command line and the Python module check what they are given with the same
/// functions, naming their own flag or keyword (`name`). Each throws
/// svo::InvalidInput with one line, "<name> <value>: <the rule>", whose
/// argument() is `name` and detail() "<value>: <the rule>". NaN never passes.
/// @{
/// A band half width: a number of voxels from 1 to 1000.
void checkBand(double voxels, const std::string& name);
/// SignOptions::windingAccuracy: a positive finite number (1e300 evaluates every triangle).
void checkWindingAccuracy(double accuracy, const std::string& name);
/// Both bands (the interior one only for signed fields) and the winding accuracy.
void checkLevelSetOptions(const LevelSetOptions& options);
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
