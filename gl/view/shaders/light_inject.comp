#version 450 core
// Light injection (design §7d): level 0 of the lighting volume. One
// invocation per texel, a block of uTexelCells³ voxels inside one brick:
// opacity = its voxels over the voxels of one face of the block, at most 1
// (a surface crossing a box of k³ voxels fills about k² of them), the same
// along x, y and z; radiance = the mean outgoing radiance of its voxels,
// ρ/π · irradiance (two-sided Lambertian), times that opacity; each voxel's
// irradiance by side, for the picture's direct light; and the lit
// side (view_lights.glsl), averaged over the voxels by their light, which
// six-way radiance (Illumination::directional) reads. With uLit 0 (ambient
// occlusion's opacity volume), opacity alone: no lights, no normals.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#include "gpu_layout.h"
#include "view_layout.h"
#include "view_octree.glsl"
#include "view_lights.glsl"
#include "loop_cut.glsl"
#include "opacity_depth.glsl"
#include "lit_side.glsl"

layout(binding = 0, rgba16f) writeonly restrict uniform image3D uOpacityOut;
layout(binding = 1, rgba16f) writeonly restrict uniform image3D uRadianceOut;
layout(binding = 2, rgba16f) writeonly restrict uniform image3D uLitSideOut;

uniform ivec3 uBaseSize;  // level 0's texels
uniform int uTexelCells;  // voxels per texel edge: 1, 2, 4 or 8
uniform uint uDirectional; // 1: write the lit side
uniform uint uLit;         // 0: opacity only

/// One texel of level 0, into the images.
void injectTexel(ivec3 texel)
{
    ivec3 first = texel * uTexelCells;
    vec4 opacity = vec4(0.0), radiance = vec4(0.0);
    vec3 litSide = vec3(0.0);
    uint brick;
    int emptyLog2;
    if (all(lessThan(first, uDims)) && findBrick(first, brick, emptyLog2)) {
        uint count = 0u, shown = 0u; // voxels; those not hidden behind their own surface
        vec3 sum = vec3(0.0);
        for (int x = 0; x < uTexelCells; ++x)
            for (int y = 0; y < uTexelCells; ++y)
                for (int z = 0; z < uTexelCells; ++z) {
                    ivec3 cell = first + ivec3(x, y, z);
                    uint bit = brickBit(cell);
                    if (any(greaterThanEqual(cell, uDims)) || !brickHas(brick, bit)) continue;
                    ++count;
                    if (uLit == 0u) continue;
                    uint v = voxelIndex(brick, bit);
                    vec3 n = voxelNormal(v);
                    float len = length(n);
                    n = len > 1e-6 ? n / len : vec3(0.0);
                    vec3 front, back, seen, side;
                    bool hidden;
                    irradianceBySide(vec3(cell) + 0.5, n, true, front, back, seen, side, hidden);
                    storeIrradiance(v, front, back); // the picture's direct light
                    if (hidden) continue;             // the back of its surface: no light, no coverage
                    ++shown;
                    vec3 l = voxelAlbedo(v) * (1.0 / 3.14159265) * seen;
                    sum += l;
                    litSide += dot(l, vec3(1.0)) * side;
                }
        float k = float(uTexelCells);
        float cover = min(1.0, float(count) / (k * k));
        opacity = vec4(storedOpacity(vec3(cover)), cover);
        // Radiance over the voxels that show a side (hidden ones occlude,
        // above, but neither light nor darken it).
        if (shown > 0u) radiance = vec4(sum / float(shown) * cover, cover);
        float total = dot(sum, vec3(1.0));
        if (total > 0.0) litSide /= total;
    }
    imageStore(uOpacityOut, texel, opacity);
    if (uLit == 0u) return;
    imageStore(uRadianceOut, texel, radiance);
    // Times the texel's light, so that a trilinear sample's lit side is
    // that of the light it holds (lit_side.glsl).
    if (uDirectional != 0u) imageStore(uLitSideOut, texel, vec4(litSide * lightOf(radiance.rgb), 0.0));
}

void main()
{
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(texel, uBaseSize))) return;
    injectTexel(texel);
    countIfLoopsWereCut();
}
