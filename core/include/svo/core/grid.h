#pragma once
/// @file grid.h
/// @brief The voxel grid: OpenVDB's index convention plus the local frame the GPU works in.
///
/// Voxel (i,j,k) has its centre at index point (i,j,k) and covers the closed
/// cube [i-1/2, i+1/2] x ... . World = voxelSize * index + translation, where
/// the translation is a whole number of voxels (`shift`), zero unless the mesh
/// lies so far from the origin that its indices would not fit OpenVDB's int32
/// coordinates. Such a shift keeps the lattice, so a mesh moved by a multiple
/// of the voxel size voxelizes identically.
///
/// Vertices go to index space in double precision, then to *local* coordinates
/// relative to an integer `anchor` (a multiple of 8, so bricks align with
/// OpenVDB leaves). Local coordinates lie in [0, dims) and are what the GPU gets
/// in float. The guard band epsilon() bounds float rounding at that magnitude.
#include <array>
#include <cstdint>
#include <string>

#include "svo/core/option_info.h"

#include "svo/core/mesh.h"

namespace svo {

/// @brief A grid: its lattice (voxel size and whole-voxel shift) and the
/// local range the GPU works in (anchor and dims).
struct GridSpec {
    double voxelSize = 1.0;          ///< world units per voxel
    std::array<int64_t, 3> shift{};  ///< translation = voxelSize * shift
    std::array<int64_t, 3> anchor{}; ///< index of local (0,0,0); multiple of 8
    std::array<uint32_t, 3> dims{};  ///< local voxel range [0, dims) per axis

    /// @brief World position -> OpenVDB index space (double): (world - translation) / voxelSize.
    Vec3d toIndex(const Vec3d& world) const;
    /// @brief World position -> local index coordinates (double).
    Vec3d toLocal(const Vec3d& world) const;
    /// @brief Local integer coordinate -> OpenVDB index coordinate.
    std::array<int64_t, 3> toGlobal(const std::array<uint32_t, 3>& local) const
    {
        return {anchor[0] + local[0], anchor[1] + local[1], anchor[2] + local[2]};
    }
    /// @brief The world position of index (0, 0, 0): voxelSize * shift.
    std::array<double, 3> translation() const
    {
        return {voxelSize * double(shift[0]), voxelSize * double(shift[1]), voxelSize * double(shift[2])};
    }
    /// @brief The largest of dims.
    uint32_t maxDim() const;
    /// @brief The guard band, in voxels: 32 float ulps (2^-24 each) of the largest local
    /// dimension, so 16 to 32 ulps of the largest local coordinate.
    /// The GPU grows each cube by epsilon()/2; see docs/precision.md.
    double epsilon() const;
};

/// @brief How the user asked for the grid: exactly one of the two is positive.
struct GridRequest {
    int64_t resolution = 0; ///< voxels along the longest bounding-box side (vdb_tool's dim)
    double voxelSize = 0.0; ///< world units per voxel
};

/// @brief The resolution a request that gives neither number gets (as vdb_tool's default dim).
inline constexpr int64_t kDefaultResolution = 256;

/// @brief Largest local extent per axis: voxel keys pack 21 bits per axis.
constexpr uint32_t kMaxGridDim = 1u << 21;

// The rules of a grid request's numbers, for every front door: makeGrid
// checks with them, and `svo --resolution/--voxel-size` and Python's
// resolution=/voxel_size= check what they are given with them under their
// own names; NaN never passes.

/// @brief The rule of GridRequest::resolution: a whole number from 1 to kMaxGridDim - 16.
/// @param name the value's name for the caller (a flag, a keyword, a field)
/// @throw svo::InvalidInput "<name> must be ..., got <value>" (argument() @a name)
void checkResolution(double resolution, const std::string& name);
/// @brief The rule of GridRequest::voxelSize: a positive finite number of world units.
/// @param name the value's name for the caller
/// @throw svo::InvalidInput "<name> must be ..., got <value>" (argument() @a name)
void checkVoxelSize(double voxelSize, const std::string& name);

/// @brief Each option of GridRequest, declared once for every front end
/// (svo/core/option_info.h). Neither given: kDefaultResolution.
template <typename Visit>
void forEachOption(GridRequest& r, Visit&& visit)
{
    visit(OptionInfo{"GridRequest::resolution", "resolution",
                     "Voxels along the longest bounding-box side, a whole number: voxel size = longest side / N; the "
                     "result spans N+1 voxels along that side (N+2 when the box ends exactly on voxel faces); neither "
                     "this nor a voxel size: 256",
                     "-r,--resolution"},
          OptionalNumber<int64_t>{r.resolution, checkResolution});
    visit(OptionInfo{"GridRequest::voxelSize", "voxel_size", "World units per voxel, instead of a resolution"},
          OptionalNumber<double>{r.voxelSize, checkVoxelSize});
}

/// @brief The largest multiple of 8 at or below @a i: brick and OpenVDB leaf origins.
constexpr int64_t floorTo8(int64_t i) { return i >= 0 ? i / 8 * 8 : -((-i + 7) / 8) * 8; }

/// @brief Checks that a grid is usable: a positive finite voxel size, dims
/// within kMaxGridDim, an anchor that is a multiple of 8, and every global
/// index (anchor + [0, dims)) inside OpenVDB's int32 coordinates, also after
/// the whole-voxel shift.
/// @param what prefixes the message (whose grid it is)
/// @throw svo::InvalidInput for the first rule broken
void checkGrid(const GridSpec& grid, const std::string& what);

/// @brief Anchor and dims for a mesh on a lattice whose voxel size and
/// whole-voxel shift are given (a caller's transform).
/// @throw svo::InvalidInput (naming mesh.source) for an empty mesh, a
///        non-finite mapping, or indices beyond kMaxGridDim or OpenVDB's
///        int32 coordinates
GridSpec makeGridOnLattice(const TriangleMesh& mesh, double voxelSize, const std::array<int64_t, 3>& shift);

/// @brief Chooses voxel size, shift, anchor and dims for a mesh.
/// @throw svo::InvalidInput for a bad request (both or neither given,
///        non-positive, non-finite), a mesh with no triangles, or with zero
///        extent under a resolution, or a grid beyond kMaxGridDim or
///        OpenVDB's int32 coordinates
GridSpec makeGrid(const TriangleMesh& mesh, const GridRequest& request);

/// @brief The mesh's vertices in local coordinates, in float, as uploaded to the GPU.
std::vector<Vec3f> localPositionsFloat(const TriangleMesh& mesh, const GridSpec& grid);

} // namespace svo
