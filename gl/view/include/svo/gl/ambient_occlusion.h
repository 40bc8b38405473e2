#pragma once
/// @file ambient_occlusion.h
/// @brief Cone-traced ambient occlusion on the octree view's voxels: its options
/// (AmbientOcclusion), their rules and their declaration for the front ends.
#include <cstdint>
#include <string>

#include "svo/core/enum_names.h"
#include "svo/core/option_info.h"

namespace svo::gl {

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

/// @brief Checks AO options before any work, as checkIllumination (svo/gl/illumination.h).
/// @throw svo::InvalidInput, in one line naming the option, for an option out of range
void checkAmbientOcclusion(const AmbientOcclusion& ao);
/// @name One AO option each, as front ends check what they are given
/// @brief Each throws svo::InvalidInput "<name> <value>: <the rule>"
/// (argument() @a name); @a name is the flag or keyword, or the field's
/// identifier where checkAmbientOcclusion runs them on a struct.
/// @{
/// @brief AmbientOcclusion::cones: 0 (none) to 16.
void checkAoConeCount(int64_t cones, const std::string& name);
/// @brief A cone's full angle (AO, the bounce, the glossy cone): in (0, 180) degrees.
void checkConeAperture(double degrees, const std::string& name);
/// @brief Where cones start (AmbientOcclusion::offset, Illumination::offset): in [0, 1e6).
void checkConeOffset(double offset, const std::string& name);
/// @brief AmbientOcclusion::distance: in (0, 1e7] voxels.
void checkAoConeDistance(double voxels, const std::string& name);
/// @brief A cone's step, its share of the cone's width (AO and the bounce): in (0, 1].
void checkConeStep(double share, const std::string& name);
/// @}

/// @brief The AO options the front ends take, declared once (svo/core/option_info.h):
/// `svo view --ao ...` and Python's Octree.render(ao=...). AmbientOcclusion::only
/// and ::interleave are not here: the front ends set them their own ways
/// (--render ao and ao_only; --cone-pattern), and volumeResolution is
/// Illumination's light_volume, which sets both.
template <typename Visit>
void forEachOption(AmbientOcclusion& ao, Visit&& visit)
{
    visit(OptionInfo{"AmbientOcclusion::cones", "ao", "Ambient occlusion, cone-traced: cones per pixel (0: off, 1 to 16)"},
          CheckedInteger<int>{ao.cones, checkAoConeCount});
    visit(OptionInfo{"AmbientOcclusion::apertureDegrees", "ao_aperture", "AO cone aperture, degrees"},
          CheckedNumber{ao.apertureDegrees, checkConeAperture});
    visit(OptionInfo{"AmbientOcclusion::offset", "ao_offset",
                     "AO cones start this far from the surface, texels of the volume (voxels with --ao-source octree; "
                     "less: more contact shadow, more self-occlusion)"},
          CheckedNumber{ao.offset, checkConeOffset});
    visit(OptionInfo{"AmbientOcclusion::distance", "ao_distance", "AO cones stop this far away, voxels"},
          CheckedNumber{ao.distance, checkAoConeDistance});
    visit(OptionInfo{"AmbientOcclusion::step", "ao_step",
                     "AO cone steps, share of the cone's width, (0, 1] (smaller: slower, fewer thin walls missed)"},
          CheckedNumber{ao.step, checkConeStep});
    visit(OptionInfo{"AmbientOcclusion::source", "ao_source",
                     "AO opacity: volume (the lighting volume's opacity, mip-mapped and sampled trilinearly: closer to "
                     "a path tracer, faster) or octree (the octree's nodes as the mip-map: no extra memory, fewer "
                     "leaks in closed rooms)"},
          ao.source);
    visit(OptionInfo{"AmbientOcclusion::filter", "ao_filter",
                     "--ao-source octree: opacity up the octree: max (a node as opaque as its most opaque child: fewer "
                     "leaks through walls) or average (its face share)"},
          ao.filter);
}

} // namespace svo::gl
