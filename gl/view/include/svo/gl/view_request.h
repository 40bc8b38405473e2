#pragma once
/// @file view_request.h
/// @brief The view policy: what a picture of an octree gets by default, and which
/// combinations are refused, written once for `svo view` (its flags), its
/// window (its keys and panel) and Python's Octree.render (its keywords).
///
/// A front end fills a ViewRequest with what the user asked for and calls
/// viewLayers, which gives the ViewLayers OctreeView draws:
///   - the render mode: Layers draws the layers as asked; AmbientOcclusion
///     draws the surface as its AO alone, grey, and Direct and Global light
///     it (Illumination::Mode); AO alone and lit pictures draw the voxel
///     layer without outlines and brick boxes;
///   - AO alone with no cones asked takes AmbientOcclusion::kDefaultCones;
///   - lit pictures without lights take defaultLights over the octree's
///     grid (a room's when `room`);
///   - the surface: Auto shades the mesh (when one is given) for AO alone and
///     lit pictures, else the voxels;
///   - refused (svo::InvalidInput naming the option): the Mesh surface
///     without a mesh, a voxel colour whose channel the octree lacks, lit
///     pictures of an octree without the normal channel, and AO or lighting
///     options out of range (checkAmbientOcclusion, checkIllumination).
#include <cstdint>
#include <optional>

#include "svo/core/lights.h"
#include "svo/core/octree.h"
#include "svo/core/option_info.h"
#include "svo/gl/render_mode.h"
#include "svo/gl/surface_choice.h"
#include "svo/gl/view_layers.h"

namespace svo::gl {

/// @brief What a caller asks of one picture. Errors name its fields as
/// "ViewRequest::render", "ViewRequest::surface" and "ViewLayers::voxelColor".
struct ViewRequest {
    RenderMode render = RenderMode::Layers;      ///< what the picture shows
    SurfaceChoice surface = SurfaceChoice::Auto; ///< what the voxel layer shades
    /// The layers, outline levels, voxel colour, and AO and lighting as asked
    /// (cones, their shape, source, albedo, specular, ...). viewLayers sets
    /// `surface`, `light.mode` and, for RenderMode::AmbientOcclusion,
    /// `ao.only`; `ao.only` asked with RenderMode::Layers is AO alone with
    /// the layers kept (the window's checkbox, Python's ao_only).
    ViewLayers layers;
    /// The lights of lit pictures; none: `layers.light.lights`, or where that
    /// is empty, defaultLights(gridWorldBox(octree.grid), room).
    std::optional<Lights> lights;
    bool room = false; ///< the default lights are a room's seen from inside (the Cornell box)
};

/// @brief The request's options the front ends take, declared once
/// (svo/core/option_info.h), then its layers' (view_layers.h). Python takes
/// `surface` and the layers' options; its `lighting` (off, direct, gi) and
/// `ao_only` are its own words for the render mode.
template <typename Visit>
void forEachOption(ViewRequest& r, Visit&& visit)
{
    visit(OptionInfo{"ViewRequest::render", "render",
                     "debug: the layers; ao: the surface as its ambient occlusion, grey (5 cones unless --ao says); "
                     "direct: lit by --light with shadows; gi: direct and one diffuse bounce cone-traced through the "
                     "lighting volume"},
          r.render);
    visit(OptionInfo{"ViewRequest::surface", "surface",
                     "What the voxel layer shades: voxels (those the camera's rays hit: the octree as it is), mesh (the "
                     "input mesh's triangles, lit, occluded and coloured through the octree: no blocks; needs a mesh "
                     "input) or auto (mesh for --render ao, direct and gi of a mesh, else voxels)"},
          r.surface);
    forEachOption(r.layers, visit);
}

/// @brief The layers to draw @a octree with: the defaults applied and the
/// request checked.
/// @param haveMesh whether the picture has the octree's mesh to draw
/// @return what OctreeView::render and draw take
/// @throw svo::InvalidInput naming the option at fault (see the file comment)
ViewLayers viewLayers(const ViewRequest& request, const Octree& octree, bool haveMesh);

/// @brief What viewLayers checks before any octree exists (AO and lighting
/// options out of range; a lit request without lights is checked as if it
/// had one): a command line checks it before it voxelizes.
/// @throw svo::InvalidInput naming the option at fault
void checkViewRequest(const ViewRequest& request);

/// @brief The attribute channels the request's picture reads: lit pictures
/// the normals and colours (the albedo, where a mesh has vertex colours), AO
/// from the volume the normals (its cones leave along them). Throws nothing.
/// @return svo::AttributeChannel bits
uint32_t channelsFor(const ViewRequest& request);

} // namespace svo::gl
