#pragma once
/// @file light_volume.h
/// The lighting volume behind Illumination (svo/gl/octree_view.h, design
/// §7d): light injected from the octree's voxels into level 0 of a 3D
/// texture pair, then mip-mapped on the GPU. The view binds it to draw.
/// Ambient occlusion's Volume source uses its opacity alone.
#include <array>
#include <cstdint>

#include "svo/gl/buffer.h"
#include "svo/gl/program.h"
#include "svo/gl/texture_3d.h"
#include "svo/gl/context.h"
#include "svo/gl/octree_view.h"

namespace svo::gl {

/// The octree's buffers as OctreeView uploaded them; the channels are null
/// when the octree lacks them.
struct ViewBuffers {
    const GridSpec& grid;
    uint32_t brickLevel;
    const Buffer& nodes;
    const Buffer& bricks;
    const Buffer* voxelStart;
    const Buffer* normals;
    const Buffer* colors;
};

struct LightVolumeTextures {
    /// rgba16f: opacity seen along x, y, z (as opacity_depth.glsl says:
    /// optical depth when `opticalDepth`); coverage
    Texture3D opacity;
    Texture3D radiance; ///< rgba16f: radiance x coverage; coverage (lit volumes only)
    /// rgba16f, with Illumination::directional only: the premultiplied
    /// radiance (a: opacity) a ray travelling along +x, -x, +y, -y, +z, -z
    /// sees, from level 1 up (texture level j is the volume's level j + 1)
    std::array<Texture3D, 6> along;
    /// rgba16f, level 0 only, with Illumination::directional: each texel's
    /// lit side (the normal turned to its lights, averaged by light) times
    /// its light (lit_side.glsl)
    Texture3D litSide;
    /// r8ui, level 0 only, once Illumination::clearance asks for it
    /// (buildClearance): per texel, the coarsest level a cone may sample
    /// anywhere in it and read no voxel (light_clear.comp). Geometry alone:
    /// a moved light keeps it.
    Texture3D clear;
    Buffer lights;      ///< 2 vec4 per light, cell space (view_lights.glsl)
    Buffer direct;      ///< per voxel: irradiance on each side, packed halves (view_lights.glsl), lit volumes only
    int lightCount = 0;
    uint32_t texelVoxels = 1;
    int size[3] = {0, 0, 0}; ///< level 0, texels
    bool lit = false;        ///< false: opacity only (buildOpacityVolume)
    bool opticalDepth = false; ///< the opacity texture holds -ln(1 - a) (six-way volumes)
    Illumination built;      ///< what it was injected with, when lit
};

/// Throws svo::Error naming the first option of `light` out of range, or the
/// missing normal channel.
void checkIllumination(const Illumination& light, const ViewBuffers& octree);

/// Throws svo::Error unless `resolution` is a power of two from 8 to 2048
/// large enough for the grid (a texel holds at most 8³ voxels). `what`
/// names the option in the message.
void checkVolumeResolution(const GridSpec& grid, uint32_t resolution, const char* what);

/// Voxels per texel edge at level 0 for a volume of at most `resolution`
/// texels a side.
uint32_t texelVoxels(const GridSpec& grid, uint32_t resolution);

/// The opacity volume alone, for ambient occlusion: no lights, no normals.
/// Throws svo::Error as checkVolumeResolution does, and when the GPU cannot
/// hold the texture.
LightVolumeTextures buildOpacityVolume(const Context& context, const ViewBuffers& octree, uint32_t resolution);

/// Binds the volume's opacity and sets the cone uniforms of `program` (one
/// that includes view_gather.glsl) for `cones` cones of `apertureDegrees`,
/// from `offset` texels to `distance` voxels (0: the grid's diagonal),
/// stepping by `step` of the cone's width, isotropic.
void bindOpacityVolume(const Program& program, const LightVolumeTextures& volume, const GridSpec& grid, int cones,
                       double apertureDegrees, double offset, double distance, double step);

/// Whether a volume injected for `a` is the one `b` needs.
bool sameInjection(const Illumination& a, const Illumination& b);

/// Injects and mip-maps. Throws svo::Error as checkIllumination does, and
/// when the GPU cannot hold the textures.
LightVolumeTextures buildLightVolume(const Context& context, const ViewBuffers& octree, const Illumination& light);

/// Injects `light` again into `volume` (a moved light) and mip-maps; the
/// volume resolution must be the one it was built for.
void injectLight(const Context& context, const ViewBuffers& octree, const Illumination& light,
                 LightVolumeTextures& volume);

/// Builds `volume.clear` from level 0's opacity, unless built: three passes
/// of a max-norm distance transform on the GPU. Throws svo::Error when the
/// GPU cannot hold the textures.
void buildClearance(const Context& context, LightVolumeTextures& volume);

/// Whether a volume built for `a` can be re-injected for `b` (the same textures).
inline bool sameVolume(const Illumination& a, const Illumination& b)
{
    return a.volumeResolution == b.volumeResolution && a.directional == b.directional;
}

/// Binds the octree's lighting inputs (lights, normals, albedo) and sets the
/// lighting uniforms of `program` (one that includes view_lights.glsl).
void bindLights(const Program& program, const LightVolumeTextures& volume, const ViewBuffers& octree,
                const Illumination& light);

/// bindLights, plus the volume's textures and the cone uniforms
/// (view_gather.glsl).
void bindLightVolume(const Program& program, const LightVolumeTextures& volume, const ViewBuffers& octree,
                     const Illumination& light);

/// Every level read back.
LightVolume readLightVolume(const LightVolumeTextures& volume);

} // namespace svo::gl
