#pragma once
/// @file view_layers.h
/// @brief What the octree view draws: its layers, voxel colour, outline levels,
/// AO and lighting (ViewLayers).
#include <cstdint>
#include <limits>

#include "svo/core/option_info.h"
#include "svo/gl/ambient_occlusion.h"
#include "svo/gl/illumination.h"
#include "svo/gl/surface.h"
#include "svo/gl/voxel_color.h"

namespace svo::gl {

/// @brief What to draw.
struct ViewLayers {
    bool voxels = true; ///< the voxel layer: the `surface`, shaded
    Surface surface = Surface::Voxels; ///< what the voxel layer shades
    bool outlines = true; ///< the node outlines of levels firstLevel to lastLevel
    bool bricks = false; ///< the brick-level nodes' boxes, in their own colour, whatever the level range
    bool mesh = false; ///< the mesh, flat grey, when the voxel layer does not shade it (needs a mesh; ignored without one)
    VoxelColor voxelColor = VoxelColor::Flat; ///< a channel the octree lacks is an error
    AmbientOcclusion ao;                      ///< on the voxels; off by default
    Illumination light;                       ///< lit voxels instead of colours and AO; off by default
    uint32_t firstLevel = 0;                                    ///< outline levels, 0 = root
    uint32_t lastLevel = std::numeric_limits<uint32_t>::max(); ///< clamped to the brick level
};

/// @brief The layer options the front ends take, declared once
/// (svo/core/option_info.h): the voxel colour, then AmbientOcclusion's and
/// Illumination's. The layers and the outline levels are each front end's own
/// (`--layers voxels,mesh` and `--levels 2:5`; lists and pairs in Python).
template <typename Visit>
void forEachOption(ViewLayers& l, Visit&& visit)
{
    visit(OptionInfo{"ViewLayers::voxelColor", "color",
                     "Voxel colours: flat, or the attribute channel normal, color or triangle"},
          l.voxelColor);
    forEachOption(l.ao, visit);
    forEachOption(l.light, visit);
}

} // namespace svo::gl
