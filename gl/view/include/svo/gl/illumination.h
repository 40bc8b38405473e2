#pragma once
/// @file illumination.h
/// @brief Light injected into the octree and gathered by cones: the octree
/// view's lighting options (Illumination), their rules, their declaration for
/// the front ends, and the lights a picture gets when none are given.
#include <array>
#include <cstdint>
#include <string>

#include "svo/core/enum_names.h"
#include "svo/core/lights.h"
#include "svo/core/option_info.h"
#include "svo/core/vec3.h"
#include "svo/gl/ambient_occlusion.h"

namespace svo::gl {

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
/// @brief Lights for a scene in the world box @a box when none are given.
///
/// For a room seen from inside (@a inside, e.g. the Cornell box), a point light a
/// tenth of the box's height below the top's centre, with intensity π d²
/// for d its distance to the box's centre; otherwise a directional light
/// from above, left and in front (travelling along (0.4, -1, -0.6)) with
/// irradiance π. Either way a white surface facing the light at the centre
/// reflects radiance 1.
Lights defaultLights(const std::array<Vec3d, 2>& box, bool inside);

/// @name One lighting option each, as front ends check what they are given
/// @brief Each throws svo::InvalidInput "<name> <value>: <the rule>"
/// (argument() @a name); @a name is the flag or keyword, or the field's
/// identifier where checkIllumination runs them on a struct. The cones'
/// aperture, offset and step are ambient_occlusion.h's.
/// @{
/// @brief Illumination::cones: 1 to 16.
void checkGiConeCount(int64_t cones, const std::string& name);
/// @brief Illumination::distance: in [0, 1e7] voxels (0: the grid's diagonal).
void checkGiConeDistance(double voxels, const std::string& name);
/// @brief Illumination::shadowOffset: in [0, 1e6) voxels.
void checkShadowOffset(double voxels, const std::string& name);
/// @brief A lighting volume's largest side (Illumination::volumeResolution,
/// AmbientOcclusion::volumeResolution): a power of two, 8 to 2048.
void checkVolumeResolution(int64_t texels, const std::string& name);
/// @brief Illumination::exposure and ::gamma: positive and finite.
void checkPositive(double value, const std::string& name);
/// @}

/// @brief The lighting options the front ends take, declared once
/// (svo/core/option_info.h): `svo view --gi-cones ...` and Python's
/// Octree.render(gi_cones=...). Not here, each front end's own: the mode (svo
/// view --render, Python's lighting), the lights, albedo and specular colour
/// (their text forms differ), and interleave (--cone-pattern). light_volume
/// sets AmbientOcclusion::volumeResolution too (the front ends copy it).
template <typename Visit>
void forEachOption(Illumination& l, Visit&& visit)
{
    visit(OptionInfo{"Illumination::specularApertureDegrees", "specular_aperture",
                     "gi: the glossy cone's aperture, degrees (narrower: shinier)"},
          CheckedNumber{l.specularApertureDegrees, checkConeAperture});
    visit(OptionInfo{"Illumination::cones", "gi_cones", "gi: cones gathering the bounce, 1 to 16"},
          CheckedInteger<int>{l.cones, checkGiConeCount});
    visit(OptionInfo{"Illumination::apertureDegrees", "gi_aperture", "gi: cone aperture, degrees"},
          CheckedNumber{l.apertureDegrees, checkConeAperture});
    visit(OptionInfo{"Illumination::offset", "gi_offset",
                     "gi: cones start this far out along the normal, texels of the lighting volume (less: more "
                     "contact light, more self-lighting)"},
          CheckedNumber{l.offset, checkConeOffset});
    visit(OptionInfo{"Illumination::step", "gi_step", "gi: cone steps, share of the cone's width, (0, 1]"},
          CheckedNumber{l.step, checkConeStep});
    visit(OptionInfo{"Illumination::distance", "gi_distance",
                     "gi: cones stop this far away, voxels (0: the grid's diagonal)"},
          CheckedNumber{l.distance, checkGiConeDistance});
    visit(OptionInfo{"Illumination::directional", "gi_emission",
                     "gi: isotropic (one radiance per texel: faster) or directional (from the second level up, the "
                     "radiance seen along each of six directions, composited front to back: thin walls leak less)"},
          NamedBool{l.directional, "isotropic", "directional"});
    visit(OptionInfo{"Illumination::clearance", "gi_clearance",
                     "gi: cones read coarse texels only clear of voxels (no light averaged across a thin wall; "
                     "slower, noisier)"},
          l.clearance);
    visit(OptionInfo{"Illumination::shadowOffset", "shadow_offset",
                     "direct/gi: shadow rays start this far out of the surface, voxels (less: light through thinner "
                     "gaps, more self-shadowing)"},
          CheckedNumber{l.shadowOffset, checkShadowOffset});
    visit(OptionInfo{"Illumination::volumeResolution", "light_volume",
                     "direct/gi, and ao from the volume: the lighting volume's largest side in texels, a power of two "
                     "(a texel holds 1 to 8³ voxels)"},
          CheckedInteger<uint32_t>{l.volumeResolution, checkVolumeResolution});
    visit(OptionInfo{"Illumination::exposure", "exposure", "direct/gi: the picture is (radiance x exposure)^(1/gamma)"},
          CheckedNumber{l.exposure, checkPositive});
    visit(OptionInfo{"Illumination::gamma", "gamma", "direct/gi: display gamma (1: linear radiance)"},
          CheckedNumber{l.gamma, checkPositive});
}

} // namespace svo::gl
