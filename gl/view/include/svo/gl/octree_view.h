#pragma once
/// @file octree_view.h
/// @brief Pictures of an octree drawn by the GPU from the octree itself: the
/// renderer behind `svo view`.
///
/// What is drawn, and from where:
///   - voxels (green, lit by their face normal): a compute pass casts one
///     ray per pixel and marches the octree's node and brick buffers
///     (view_voxels.comp), and a full-screen triangle writes its pixels and
///     depths into the framebuffer: at each step it descends from the
///     root to the deepest node holding the current voxel, skips empty nodes
///     whole, tests brick bits at the bottom and skips empty 4³ and 2³
///     blocks of a brick whole. No voxel is expanded into
///     geometry and none is read back;
///   - node outlines (red): the 12 edges of each occupied node's box, one
///     instanced draw per level of the chosen range; a compute pass gives
///     every node its origin first, since the octree stores none;
///   - the mesh (grey, flat shaded), when one is given.
/// The octree's nodes and bricks are uploaded once, as they are laid out in
/// memory (docs/octree.md; docs/design.md gives the bytes per voxel).
///
/// Space: the camera is in world units (the octree's GridSpec gives the
/// map). Depth is shared by the three layers, so outlines and mesh are hidden
/// by voxels in front of them and the other way round.
///
/// Image convention: right = normalize(forward x up), image up = the part of
/// `up` orthogonal to forward; an orthographic view spans `height` world
/// units vertically and height * width / pixel height horizontally, centred
/// on the target.
#include <cstdint>
#include <memory>
#include <vector>

#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/gl/ambient_occlusion.h"
#include "svo/gl/context.h"
#include "svo/gl/illumination.h"
#include "svo/gl/image.h"
#include "svo/gl/light_volume.h"
#include "svo/gl/surface.h"
#include "svo/gl/view_camera.h"
#include "svo/gl/view_colors.h"
#include "svo/gl/view_layers.h"
#include "svo/gl/voxel_color.h"

namespace svo::gl {

/// @brief Draws one octree (and optionally its mesh) with a Context. Not copyable.
/// Every GL call happens inside a Context::Scope, so the caller's current
/// context is left as it was.
class OctreeView {
public:
    /// @brief Uploads the octree's nodes and bricks and computes the node
    /// origins on the GPU.
    /// @param context the context to draw with; must outlive the view
    /// @param mesh    when given, uploaded in the octree's frame: it must be
    ///        the mesh the octree was made from, in world units
    /// @throw svo::InvalidInput when the octree fails checkOctree's level ranges
    /// @throw svo::Unsupported for attribute channels over 2^32 voxels
    /// @throw svo::OutOfMemory when the GPU runs out of memory
    /// @throw svo::DeviceError on a shader or GL error
    OctreeView(const Context& context, const Octree& octree, const TriangleMesh* mesh = nullptr);
    ~OctreeView();
    OctreeView(const OctreeView&) = delete;
    OctreeView& operator=(const OctreeView&) = delete;

    /// @brief Replaces the octree (and mesh), e.g. after re-voxelizing; on a
    /// throw the previous one stays.
    /// @throw as the constructor
    void setOctree(const Octree& octree, const TriangleMesh* mesh = nullptr);

    /// @brief Renders one frame offscreen (a colour and a depth renderbuffer)
    /// and reads it back. The same inputs give the same bytes.
    /// @param width, height the picture's size, pixels
    /// @return the picture
    /// @throw svo::InvalidInput for a size outside [1, the driver's largest
    ///        renderbuffer], a degenerate camera (eye at target, up along the
    ///        view, height or fov not positive), a voxel colour whose channel
    ///        the octree lacks, the Mesh surface without a mesh, AO or
    ///        lighting options outside their ranges, lighting on an octree
    ///        without a normal channel
    /// @throw svo::DeviceError for a GL error, or rays or light injection that
    ///        a CPU rasterizer's loop limit cut short (ContextInfo::loopLimit;
    ///        see cutPixels())
    /// @throw svo::Unsupported for a grid too wide for the AO or lighting
    ///        volume (naming AmbientOcclusion::volumeResolution)
    /// @throw svo::OutOfMemory when the GPU cannot hold the pictures or volumes
    Image render(const ViewCamera& camera, int width, int height, const ViewLayers& layers = {}) const;

    /// @brief Draws one frame into the framebuffer bound now (a window's, when
    /// the Context adopted the window's context), over the viewport (0, 0,
    /// width, height), clearing it first. Leaves depth testing off and no
    /// program or vertex array bound.
    /// @throw as render(), except that rays cut short are drawn as they are
    ///        and counted in cutPixels()
    void draw(const ViewCamera& camera, int width, int height, const ViewLayers& layers = {}) const;

    /// @brief The time of one frame (timeFrames).
    struct FrameTime {
        double gpuMs = 0, wallMs = 0; ///< GL timestamp queries; issue to glFinish
    };
    /// @brief Times frames drawn offscreen one after another, after one
    /// untimed frame (programs made, caches warm), nothing read back. Each
    /// frame gets its GPU time from GL timestamp queries and its wall time
    /// from issue to glFinish (software rasterizers such as llvmpipe draw at
    /// the flush, so only the wall time is meaningful there).
    /// @param frames          the timed frames, at least 1
    /// @param injectEachFrame lit layers: inject the light and mip-map the
    ///        volume again inside each timed frame, as after a light moves
    /// @return one FrameTime per timed frame
    /// @throw as render(), and svo::InvalidInput for @a frames < 1
    std::vector<FrameTime> timeFrames(const ViewCamera& camera, int width, int height, const ViewLayers& layers,
                                      int frames, bool injectEachFrame = false) const;

    /// @brief The lighting volume @a light gives (built or taken from the cache
    /// as drawing does), every level read back: for tests and tools.
    /// @throw as render() for lighting options out of range, a missing normal
    ///        channel, a grid too wide for the volume, a cut injection, and
    ///        svo::OutOfMemory when the GPU cannot hold the volume
    LightVolume readLightVolume(const Illumination& light) const;

    /// @brief The pixels of the last frame whose rays (march, cones) a CPU
    /// rasterizer's loop limit cut short (ContextInfo::loopLimit: llvmpipe
    /// ends all loops of an invocation after 65,535 iterations in all,
    /// silently). render() and timeFrames() refuse such a frame; a window
    /// drawn with draw() should say so.
    /// @return the count; always 0 on GPUs
    uint32_t cutPixels() const;

    /// @brief The grid of the octree shown.
    const GridSpec& grid() const;
    /// @brief The octree's brick level (Octree::brickLevel).
    uint32_t brickLevel() const;

private:
    struct Impl; ///< opaque: GPU buffers and what drawing them needs

    const Context& context_;
    std::unique_ptr<Impl> impl_;
};

} // namespace svo::gl
