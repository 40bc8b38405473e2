// The view policy (svo/gl/view_request.h): one request, the defaults applied
// and the combinations checked, for svo view, its window and Python.
#include "svo/gl/view_request.h"

#include <string>
#include <vector>

#include "svo/core/error.h"
#include "svo/gl/view_camera.h"

namespace svo::gl {
namespace {

bool noLights(const Lights& l) { return l.directional.empty() && l.point.empty(); }

/// What the render mode turns on and off, before any octree is known.
ViewLayers requested(const ViewRequest& r)
{
    ViewLayers l = r.layers;
    if (r.render == RenderMode::AmbientOcclusion) {
        l.ao.only = true;
        l.outlines = l.bricks = false;
    }
    if (l.ao.only && l.ao.cones == 0) l.ao.cones = AmbientOcclusion::kDefaultCones;
    if (isLit(r.render)) {
        l.light.mode = r.render == RenderMode::Global ? Illumination::Mode::Global : Illumination::Mode::Direct;
        l.outlines = l.bricks = false; // lit pictures: the voxel layer alone
        if (r.lights) l.light.lights = *r.lights;
    } else {
        l.light.mode = Illumination::Mode::Off;
    }
    return l;
}

/// The attribute channel a voxel colour reads, and its identifier in errors.
struct ColorChannel {
    bool present;
    const char* identifier;
    const char* words;
};
ColorChannel channelOf(VoxelColor c, const VoxelAttributes& a)
{
    switch (c) {
    case VoxelColor::Normal: return {!a.normals.empty(), "svo::kNormals", "the normal channel"};
    case VoxelColor::Color: return {!a.colors.empty(), "svo::kColors", "the colour channel"};
    case VoxelColor::Triangle: return {!a.triangles.empty(), "svo::kTriangles", "the triangle channel"};
    case VoxelColor::Flat: break;
    }
    return {true, "", ""};
}

} // namespace

void checkViewRequest(const ViewRequest& request)
{
    const ViewLayers l = requested(request);
    checkAmbientOcclusion(l.ao);
    if (l.light.mode != Illumination::Mode::Off) {
        Illumination probe = l.light;
        if (!request.lights && noLights(probe.lights)) // the default lights come with the octree's box: a stand-in
            probe.lights.directional.push_back({{0, -1, 0}, {1, 1, 1}});
        checkIllumination(probe);
    }
}

uint32_t channelsFor(const ViewRequest& request)
{
    const ViewLayers l = requested(request);
    if (l.light.mode != Illumination::Mode::Off) return kNormals | kColors;
    if (l.ao.cones > 0 && l.ao.source == AmbientOcclusion::Source::Volume) return kNormals;
    return 0;
}

ViewLayers viewLayers(const ViewRequest& request, const Octree& octree, bool haveMesh)
{
    ViewLayers l = requested(request);
    const bool lit = l.light.mode != Illumination::Mode::Off;
    // Lit and AO pictures of a mesh shade its triangles (the octree lights
    // them: no blocks, and the path tracer's surface); other pictures, and
    // inputs without a mesh, the voxels.
    if (request.surface == SurfaceChoice::Mesh && !haveMesh)
        throw InvalidInput(std::vector<Error::Part>{
            Error::option("ViewRequest::surface", "surface"), " mesh shades the input mesh, and this input holds voxels "
                                                              "only (give the mesh, or ",
            Error::option("ViewRequest::surface", "surface"), " voxels)"});
    l.surface = request.surface == SurfaceChoice::Mesh ||
                        (request.surface == SurfaceChoice::Auto && haveMesh && (l.ao.only || lit))
                    ? Surface::Mesh
                    : Surface::Voxels;

    const ColorChannel channel = channelOf(l.voxelColor, octree.attributes);
    if (!channel.present) {
        const std::string name(nameOf(l.voxelColor));
        throw InvalidInput(std::vector<Error::Part>{
            Error::option("ViewLayers::voxelColor", "voxel colour"),
            " " + name + ": the octree has no '" + name + "' channel (voxelize the mesh with ",
            Error::option(channel.identifier, channel.words),
            l.voxelColor == VoxelColor::Color ? "; colours need vertex colours)" : ")"});
    }
    if (lit && octree.attributes.normals.empty())
        throw InvalidInput(std::vector<Error::Part>{
            Error::option("ViewRequest::render", "render"),
            " " + std::string(nameOf(request.render)) +
                " needs the octree's normal channel, which it lacks (voxelize the mesh with ",
            Error::option("svo::kNormals", "the normal channel"), ", or view the mesh itself)"});
    if (lit && !request.lights && noLights(l.light.lights))
        l.light.lights = defaultLights(gridWorldBox(octree.grid), request.room);
    checkAmbientOcclusion(l.ao);
    if (lit) checkIllumination(l.light);
    return l;
}

} // namespace svo::gl
