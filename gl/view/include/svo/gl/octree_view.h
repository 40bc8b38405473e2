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
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "svo/core/camera.h"
#include "svo/core/enum_names.h"
#include "svo/core/lights.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/gl/context.h"

namespace svo::gl {

/// @brief A camera in world units (svo/core/camera.h), shared with the path-traced
/// reference so that both see each pixel along the same ray.
using ViewCamera = svo::Camera;

/// @brief How voxels are coloured: flat green, or by an attribute channel of the
/// octree (VoxelAttributes): the normal as 0.5 + 0.5 n, the colour, or a
/// colour hashed from the triangle id.
enum class VoxelColor { Flat, Normal, Color, Triangle };
inline constexpr EnumName<VoxelColor> kVoxelColorNames[] = {{VoxelColor::Flat, "flat"},
                                                             {VoxelColor::Normal, "normal"},
                                                             {VoxelColor::Color, "color"},
                                                             {VoxelColor::Triangle, "triangle"}};
constexpr const auto& enumNames(VoxelColor) { return kVoxelColorNames; }

/// @brief Ambient occlusion on the voxels (Crassin et al. 2011).
///
/// Cones over the
/// hemisphere, one along the normal and a ring tilted 60 degrees around it,
/// each weighted by its share of the cosine-weighted hemisphere, composited
/// front to back; AO is one minus the weighted occlusion. Distances in
/// voxels. Two sources of opacity:
///   - Volume (the default): the lighting volume's opacity alone (see
///     Illumination; no lights, no normals needed), a mip-mapped 3D texture
///     sampled trilinearly, opacity seen along x, y and z (Crassin's
///     anisotropic filter). Each cone keeps its occlusion per sector of its
///     cross-section, so that an occluder it sees at several depths (a
///     sphere's near and far sides) is counted once (docs/design.md, ambient
///     occlusion). The cones
///     leave the voxel's centre along the octree's normal channel when it
///     has one, else along the face the ray hit. Allocated while AO is on,
///     `volumeResolution` texels at most.
///   - Octree: the octree itself as the mip-map: a node's opacity is its
///     voxels over the voxels of one face of its box, at most 1 (a surface
///     crossing the box covers it); inside bricks, 4³ and 2³ blocks and
///     voxels give three finer levels; aligned cells, no filtering; the
///     face the ray hit is the normal. No extra memory; slower (each sample
///     descends from the root) and further from the reference.
/// A sample whose cell would reach behind the surface's tangent plane takes
/// a finer one (what lies behind cannot occlude). Volume cones start away
/// from a neighbouring surface (up to 2 texels down level 0's opacity
/// gradient across the normal), so that a concave edge's cones do not start
/// inside the other wall (docs/design.md, ambient occlusion).
///
/// The cone model is biased, and bench/results measures both sources against
/// a path-traced reference (svo/reference/path_trace.h). With the Octree
/// source, coarse cells that a surface crosses only in part (room corners)
/// let light leak through walls with the Average filter; the Max filter (a
/// node at least as opaque as its most opaque child) closes most of them
/// (docs/design.md gives a closed box's floor) and darkens thin features
/// instead.
struct AmbientOcclusion {
    enum class Source { Volume, Octree }; ///< where cones read opacity (see above)
    enum class Filter { Average, Max };   ///< Octree: a node's opacity from its children
    /// The cones the front ends turn AO on with (svo view --render ao, the
    /// window's G key, Python's ao_only); bench/results/ has the error of
    /// each count against more cones.
    static constexpr int kDefaultCones = 5;
    int cones = 0;                ///< 0: none; 1: the normal only; n: the normal and n - 1 around it (at most 16)
    double apertureDegrees = 60;  ///< full cone angle, (0, 180)
    /// First sample along the normal: Volume, in texels of the volume's level
    /// 0 (voxels while a texel is one voxel): a surface's own texels reach
    /// about two texels out of it; Octree, in voxels.
    double offset = 2.0;
    double distance = 32.0;       ///< cones stop here, voxels
    /// Each step, this share of the cone's width there, (0, 1]: smaller is
    /// slower and misses thinner walls less. Near the surface, where a
    /// sample is finer than the cone, at most twice the share of its width.
    double step = 0.5;
    Source source = Source::Volume; ///< where cones read opacity
    /// Volume: its largest side, texels: a power of two, 8 to 2048, and at
    /// least an eighth of the grid's largest side (a texel holds at most 8³
    /// voxels: 256 serves grids up to 2048 wide); wider grids are an error
    /// that names both ways out (a larger volume, or the Octree source).
    uint32_t volumeResolution = 256;
    /// Volume: interleaved cones. Each pixel of a 4x4 tile turns its ring of
    /// cones and shifts its steps its own way, and each pixel's AO is the
    /// mean over the 4x4 window around it of the pixels on its own surface
    /// (a normal within 25 degrees, a point within a voxel of its tangent
    /// plane: no blur across edges or depth steps). One cone set samples the
    /// coarse texels at fixed places and its error has their pattern; 16
    /// sets average most of it out, for one extra full-screen pass
    /// (docs/design.md, the viewer's AO). False: every pixel the same cone
    /// set, nothing averaged.
    bool interleave = true;
    Filter filter = Filter::Max;  ///< Octree: how node opacities are filtered up the octree
    bool only = false;            ///< draw the voxels as grey AO alone (no colour or face light), to measure it
};
inline constexpr EnumName<AmbientOcclusion::Source> kAoSourceNames[] = {{AmbientOcclusion::Source::Volume, "volume"},
                                                                         {AmbientOcclusion::Source::Octree, "octree"}};
constexpr const auto& enumNames(AmbientOcclusion::Source) { return kAoSourceNames; }
inline constexpr EnumName<AmbientOcclusion::Filter> kAoFilterNames[] = {{AmbientOcclusion::Filter::Average, "average"},
                                                                         {AmbientOcclusion::Filter::Max, "max"}};
constexpr const auto& enumNames(AmbientOcclusion::Filter) { return kAoFilterNames; }

/// @brief Light injected into the octree and gathered by cones (Crassin et al.
/// 2011; docs/design.md, light injection and one-bounce GI).
///
/// When on, the voxels are drawn lit instead of by ViewLayers::voxelColor and AO:
///   - injection: every voxel gets its outgoing radiance ρ/π Σ E cos θ V
///     (two-sided Lambertian, the normal from the octree's normal channel,
///     ρ from its colour channel or `albedo`), V from a ray marched through
///     the octree's voxels towards each light (hard shadows at voxel
///     resolution, no shadow-map bias to tune but `shadowOffset`);
///   - a lighting volume: a 3D texture whose texels are the octree's voxels
///     (or blocks of 2³ to 8³ voxels, so that its largest side is at most
///     `volumeResolution`), holding opacity seen along x, y, z and radiance
///     times coverage, mip-mapped on the GPU with the anisotropic filter
///     (and with `directional`, six-way radiance from level 1 up);
///     allocated only while lighting is on;
///   - the picture: at each voxel the ray hits, the direct light (same
///     shadow rays, from the side the camera sees) and, for Global, one
///     diffuse bounce: the albedo times the radiance `cones` cones gather
///     over the hemisphere, weighted as the cosine says; and with `specular`
///     a glossy reflection from one more cone.
/// The volume is built once and kept until the lights, albedo, offsets or
/// resolution change (a moved light re-injects). bench/results measures the
/// pictures against the path-traced reference (svo/reference/path_trace.h).
struct Illumination {
    enum class Mode { Off, Direct, Global }; ///< none; direct light with shadows; plus one diffuse bounce
    Mode mode = Mode::Off;                ///< off by default
    Lights lights;                        ///< world units; at least one light when on; no environment light
    Vec3d albedo{0.75, 0.75, 0.75};       ///< ρ where the octree has no colour channel, each in [0, 1]
    int cones = 5;                        ///< indirect light: 1 (the normal) to 16 cones
    double apertureDegrees = 60;          ///< full cone angle, (0, 180)
    double offset = 1.5;                  ///< cones start this far out along the normal, texels of level 0 (voxels while a texel is one voxel)
    double distance = 0;                  ///< cones stop here, voxels; 0: the grid's diagonal
    double step = 0.5;                    ///< cone steps, share of the cone's width, (0, 1] (AmbientOcclusion::step)
    bool interleave = true;               ///< the bounce's cones interleaved over 4x4 pixels (AmbientOcclusion::interleave)
    /// Six-way radiance (Crassin's anisotropic mip-map): from level 1 up, the
    /// radiance a ray along each of the six axis directions sees, composited
    /// front to back, so that a wall hides what lies behind it at every
    /// level; and at level 0 each texel's lit side, so that a one-voxel wall
    /// lit on one side sends no light out of the other (a texel's light
    /// leaves its lit side by the cosine); the opacity is kept as optical
    /// depth, so that samples between a wall's texels still see it opaque.
    /// Six textures at half resolution and one at level 0, and up to four
    /// fetches a sample instead of one; bench/results/ gives the memory,
    /// error and time of both, and docs/design.md (the light volume) the
    /// leaks through thin walls that remain.
    bool directional = false;
    /// Cones read a coarse level only where its texels hold no voxel: beside
    /// a surface a cone narrows to the level whose texels stay clear of it,
    /// down to level 0, so that no sample averages light across a wall. A
    /// coarse texel that straddles a one-voxel wall holds the light of both
    /// its sides; with six-way radiance this is what remains of the thin-wall
    /// leak (docs/design.md, the light volume; bench/results/ measures the
    /// leak, the error and the time with and without). Near surfaces a cone then samples like a ray: more,
    /// shorter steps and noisier light.
    bool clearance = false;
    /// Glossy reflection (Global only): one cone along the view direction
    /// mirrored about the normal, `specularApertureDegrees` wide, through the
    /// same volume; the radiance it gathers times `specular` (each in [0, 1])
    /// is added to the picture. It reflects the lit surfaces, not the lights
    /// themselves (a point or directional light has no area to see). 0: none.
    Vec3d specular{0, 0, 0};
    double specularApertureDegrees = 15;  ///< the glossy cone's full angle, (0, 180): narrower is shinier
    double shadowOffset = 2.0;            ///< shadow rays start this far out of the surface, voxels
    uint32_t volumeResolution = 256;      ///< the lighting volume's largest side, texels: a power of two, 8 to 2048
    double exposure = 1.0;                ///< the picture is (radiance x exposure)^(1 / gamma), clamped to 1
    double gamma = 2.2;                   ///< 1: linear, to compare with a reference
};
inline constexpr EnumName<Illumination::Mode> kLightingNames[] = {{Illumination::Mode::Off, "off"},
                                                                   {Illumination::Mode::Direct, "direct"},
                                                                   {Illumination::Mode::Global, "gi"}};
constexpr const auto& enumNames(Illumination::Mode) { return kLightingNames; }

/// @brief Checks lighting options before any work: what OctreeView::render
/// would refuse (a command line checks them before it voxelizes). What
/// depends on the octree (its normal channel, a volume resolution too small
/// for its grid) is checked when drawing.
/// @throw svo::InvalidInput, in one line naming the option, for an option out
///        of range, no light, or an environment light
void checkIllumination(const Illumination& light);
/// @brief Checks AO options before any work, as checkIllumination.
/// @throw svo::InvalidInput, in one line naming the option, for an option out of range
void checkAmbientOcclusion(const AmbientOcclusion& ao);

/// @brief One level of the lighting volume as read back
/// (OctreeView::readLightVolume), texels x fastest.
struct LightVolumeLevel {
    int size[3] = {0, 0, 0}; ///< texels along x, y, z
    std::vector<float> opacity;  ///< 4 per texel: seen along x, y, z, and coverage
    std::vector<float> radiance; ///< 4 per texel: radiance x coverage (rgb), coverage
    /// With Illumination::directional, from level 1 up, 4 per texel each:
    /// the premultiplied radiance (rgb) and opacity (a) a ray travelling
    /// along +x, -x, +y, -y, +z, -z sees. Empty otherwise.
    std::array<std::vector<float>, 6> along;
    /// With Illumination::directional, level 0 only, 4 per texel: its lit
    /// side (the normal turned to its lights, averaged by light; 0 unlit)
    /// times its light, the mean of its premultiplied radiance's rgb, so
    /// that a trilinear sample divided by the sampled light is the lit side
    /// of the light it holds.
    std::vector<float> litSide;
};
/// @brief The lighting volume as read back (OctreeView::readLightVolume).
struct LightVolume {
    uint32_t texelVoxels = 1; ///< voxels per texel edge at level 0
    std::vector<LightVolumeLevel> levels; ///< level 0 first
    /// With Illumination::clearance, per texel of level 0: the coarsest
    /// level a cone may sample anywhere in that texel and read no texel of
    /// level 0 that holds a voxel (at most 7: distances stop at 255 texels).
    /// Empty otherwise.
    std::vector<uint8_t> clearLevel;
};

/// @brief The surface the voxel layer shades (ViewLayers::surface):
///   - Voxels: the voxels camera rays hit in the octree, each shaded at its
///     centre along its normal channel (or the face the ray hit): what the
///     octree holds, blocky at its resolution;
///   - Mesh: the mesh's triangles (OctreeView needs the mesh), rasterized
///     into the triangle each pixel sees, met there by the pixel's ray, and
///     shaded at that point along the triangle's normal by the same light,
///     AO and cones through the octree's volume (deferred shading, as in
///     Crassin et al. 2011): silhouettes and edges are the triangles', and
///     the octree only lights them. `svo view` picks it for lit and AO
///     pictures of a mesh input (`--surface auto`). Direct light marches its
///     shadow ray from the pixel's point (the Voxels surface reads each
///     voxel's from the injection). Colours by attribute, and the albedo,
///     are the channel's value at the voxel holding the point.
enum class Surface { Voxels, Mesh };
inline constexpr EnumName<Surface> kSurfaceNames[] = {{Surface::Voxels, "voxels"}, {Surface::Mesh, "mesh"}};
constexpr const auto& enumNames(Surface) { return kSurfaceNames; }

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

/// @brief An RGBA8 picture, rows from the top.
struct Image {
    int width = 0, height = 0; ///< pixels
    std::vector<uint8_t> rgba; ///< 4 bytes per pixel
    /// @brief The 4 bytes of pixel (@a x, @a y), row @a y from the top; unchecked.
    const uint8_t* pixel(int x, int y) const { return &rgba[4 * (size_t(y) * size_t(width) + size_t(x))]; }
};

/// @brief The colours of the layers, 0..1 (tests classify pixels by them).
struct ViewColors {
    static constexpr float voxel[3] = {0.15f, 0.85f, 0.20f};
    static constexpr float outline[3] = {0.95f, 0.10f, 0.10f};
    static constexpr float brick[3] = {0.95f, 0.80f, 0.10f};
    static constexpr float mesh[3] = {0.70f, 0.70f, 0.72f};
    static constexpr float background[3] = {0.08f, 0.08f, 0.10f};
};

/// @brief The world box of the grid's voxels: local [-1/2, dims - 1/2] per axis.
/// @return the box's lowest and highest corners, world units
std::array<Vec3d, 2> gridWorldBox(const GridSpec& grid);

/// @brief A camera that sees the whole box. Orthographic views fit the box's
/// bounding sphere in the image height and width.
/// @param direction where the camera looks; need not be unit
/// @param aspect    the picture's width / height
/// @throw svo::InvalidInput for a zero @a direction
ViewCamera frameBox(const std::array<Vec3d, 2>& box, const Vec3d& direction, bool orthographic, double aspect);

/// @brief The named views of `svo view --view`, framing the box with frameBox.
/// @param name "front" (perspective, looking along (-0.35, -0.3, -1), the
///        Cornell box's open side) or an axis, "+x", "-x", "+y", "-y", "+z",
///        "-z" (orthographic, looking from that side)
/// @param aspect the picture's width / height
/// @throw svo::InvalidInput for another name ("view 'x': ...", its
///        argument() "svo::gl::namedView")
ViewCamera namedView(const std::array<Vec3d, 2>& box, const std::string& name, double aspect);

/// @brief Lights for a scene in the world box @a box when none are given.
///
/// For a room seen from inside (@a inside, e.g. the Cornell box), a point light a
/// tenth of the box's height below the top's centre, with intensity π d²
/// for d its distance to the box's centre; otherwise a directional light
/// from above, left and in front (travelling along (0.4, -1, -0.6)) with
/// irradiance π. Either way a white surface facing the light at the centre
/// reflects radiance 1.
Lights defaultLights(const std::array<Vec3d, 2>& box, bool inside);

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
