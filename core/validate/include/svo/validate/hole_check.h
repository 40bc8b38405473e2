#pragma once
/// @file hole_check.h
/// @brief Hole-freeness of a voxelization of a closed mesh.
///
/// Method: the empty voxels of the grid, padded by one layer, are flood-filled
/// from a corner (26-connected for conservative voxelizations, 6-connected
/// for thin ones). A correct voxelization of a closed mesh walls the inside
/// off, so the fill must reach no voxel whose centre lies inside the mesh
/// (CGAL's Side_of_triangle_mesh). Inside is tested on the filled voxels that
/// touch an occupied one (the fill's frontier): a fill that passes the surface
/// enters the interior, whose voxels next to the wall are frontier voxels.
/// A leak is reported with the path the fill took, from outside to the first
/// inside voxel found.
///
/// Applies only to closed meshes: after coincident vertices are welded and
/// degenerate faces dropped (CGAL's repair_polygon_soup), a mesh that CGAL
/// cannot orient into a 2-manifold, or one with border edges, has no inside;
/// the result says why.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"

namespace svo::validate {

/// @brief What the hole check found.
struct HoleCheck {
    bool applies = false;                          ///< the mesh is closed, so the check ran
    std::string reason;                            ///< why it does not apply
    int connectivity = 26;                         ///< the fill's: 26 or 6
    bool leak = false;                             ///< the fill reached an inside voxel
    std::vector<std::array<int64_t, 3>> leakPath;  ///< OpenVDB indices, outside -> inside
    uint64_t filled = 0, frontier = 0;             ///< voxels reached; of those, tested for inside
};

/// @brief Flood-fills the empty voxels around a voxelization of a closed mesh
/// and reports whether the fill leaks inside (see the file comment).
/// @param voxels       the voxelization: sorted, unique local keys on @a grid
/// @param connectivity 26 for conservative voxelizations, 6 for thin ones
///                     (separatingConnectivity)
/// @param progress     called now and then as (voxels done, total)
/// @throw svo::InvalidInput for a voxel outside the grid
/// @throw svo::OutOfMemory when the grid is too large for the fill's host memory
HoleCheck checkHoles(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<uint64_t>& voxels,
                     int connectivity = 26, const std::function<void(uint64_t, uint64_t)>& progress = {});

} // namespace svo::validate
