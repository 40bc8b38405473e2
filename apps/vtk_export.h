#pragma once
/// @file vtk_export.h
/// Octrees as VTK data, without VTK in the interface.
///
/// The functions live in a module of their own (libsvo_vtk.so, built from
/// vtk_export.cpp) that `svo vtk` loads when it runs: linked into svo, VTK's
/// 60-odd shared libraries cost every other command about 20 ms of start-up
/// on the 2-core machine (a fifth of a small `svo voxelize`). The module uses
/// the executable's svo symbols (exported by module_exports.list), so it shares
/// its error types, temporary files and interrupt clean-up.
///
/// Levels: 0 is the root, `brickLevel` the 8^3 bricks, and brickLevel + 1, + 2,
/// + 3 split a brick into 4^3, 2^3 and single voxels, so every file can reach
/// down to voxels with branch factor 2 throughout.
#include <cstdint>
#include <string>

#include "svo/core/mesh.h"
#include "svo/core/octree.h"

namespace svo::app {

struct LevelRange {
    uint32_t first = 0;
    uint32_t last = UINT32_MAX; ///< clamped to brickLevel + 3
};

/// .htg: a vtkHyperTreeGrid of one tree, branch factor 2, child c = x + 2y + 4z
/// (the octree's order). Cell arrays: `level`, `occupancy` (0/1),
/// `voxel_count`, and the octree's attribute channels (`normal`,
/// `triangle_id`, `color`) on voxel cells. Occupied cells are refined down to
/// level range.last. Empty cells are masked (the grid's mask, 1 = masked), so
/// ParaView draws only the occupied leaves (the voxels) with no filter. Written in binary mode: VTK 9.1's appended mode corrupts
/// hyper tree grids with more than one cell array.
void writeHyperTreeGrid(const std::string& path, const Octree& octree, const LevelRange& levels);

/// .vtu: every occupied voxel as a VTK_VOXEL cell in world coordinates, with
/// its OpenVDB index as the cell array `index`, and the attribute channels.
void writeVoxelCells(const std::string& path, const Octree& octree);

/// .vtp: the outline (12 edges) of every occupied node at levels
/// [first, min(last, brickLevel)], with the cell array `level`.
void writeNodeOutlines(const std::string& path, const Octree& octree, const LevelRange& levels);

struct PictureOptions {
    int width = 1600, height = 1200;
    const TriangleMesh* mesh = nullptr; ///< drawn translucent when given
    LevelRange outlineLevels{0, UINT32_MAX};
};

/// A PNG of the voxels (green), the node outlines (red) and the mesh (grey),
/// rendered offscreen through VTK. VTK 9.1 from Debian renders through X: with
/// no DISPLAY, svo starts Xvfb for the duration (xvfb.h).
void renderPicture(const std::string& path, const Octree& octree, const PictureOptions& options);

/// The functions above, as the module hands them over.
struct VtkExport {
    void (*writeHyperTreeGrid)(const std::string&, const Octree&, const LevelRange&);
    void (*writeVoxelCells)(const std::string&, const Octree&);
    void (*writeNodeOutlines)(const std::string&, const Octree&, const LevelRange&);
    void (*renderPicture)(const std::string&, const Octree&, const PictureOptions&);
};

/// The module's entry point, extern "C"; its name carries the layout's version.
#define SVO_VTK_MODULE_ENTRY svo_vtk_export_v1

/// Loads the module once, from SVO_VTK_MODULE_FROM_BIN next to the running
/// executable (vtk_module.cpp). Throws svo::Error naming the module's path and
/// the loader's reason when it cannot be loaded.
const VtkExport& vtkExport();

} // namespace svo::app
