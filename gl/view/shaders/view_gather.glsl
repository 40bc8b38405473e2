// Cones through the lighting volume (design §7d; Crassin et al. 2011): a
// mip-mapped 3D texture of the octree's voxels, sampled trilinearly. Each
// texel holds the opacity of its box seen along x, y and z, its outgoing
// radiance times its coverage; with uDirectional, from level 1 up, the
// radiance a ray along each axis direction sees, composited front to back,
// so that a wall hides the light behind it at every level. A cone samples,
// at distance t, the level whose texels are as wide as the cone there (a
// finer one near the surface), steps by a share of that width, and
// composites front to back. Ambient occlusion
// (AmbientOcclusion::Source::Volume) takes the opacity alone, and keeps it
// per sector of the cone's cross-section (coneOcclusion). With uInterleave
// each pixel of a 4x4 tile turns its ring of cones and shifts its steps its
// own way (conePattern); view_resolve.comp then averages the tile.

#include "lit_side.glsl"
#include "opacity_depth.glsl"

layout(binding = SVO_UNIT_LIGHT_OPACITY) uniform sampler3D uOpacityVolume;
layout(binding = SVO_UNIT_LIGHT_RADIANCE) uniform sampler3D uRadianceVolume;
// Six-way radiance from level 1 up (uDirectional): premultiplied radiance a
// ray travelling along +x, -x, +y, -y, +z, -z sees, composited front to
// back; texture level j is the volume's level j + 1.
layout(binding = SVO_UNIT_LIGHT_ALONG + 0) uniform sampler3D uAlongPositiveX;
layout(binding = SVO_UNIT_LIGHT_ALONG + 1) uniform sampler3D uAlongNegativeX;
layout(binding = SVO_UNIT_LIGHT_ALONG + 2) uniform sampler3D uAlongPositiveY;
layout(binding = SVO_UNIT_LIGHT_ALONG + 3) uniform sampler3D uAlongNegativeY;
layout(binding = SVO_UNIT_LIGHT_ALONG + 4) uniform sampler3D uAlongPositiveZ;
layout(binding = SVO_UNIT_LIGHT_ALONG + 5) uniform sampler3D uAlongNegativeZ;
layout(binding = SVO_UNIT_LIGHT_LIT_SIDE) uniform sampler3D uLitSide; // level 0's lit side times its light (uDirectional)
// Per texel of level 0, the coarsest level clear of voxels (uConeClearance; light_clear.comp).
layout(binding = SVO_UNIT_LIGHT_CLEAR) uniform usampler3D uClearLevel;

uniform vec3 uVolumeScale;    // cell space -> texture coordinates
uniform float uTexelCells;    // voxels per texel edge at level 0
uniform float uConeTanHalf;   // tan of half the cone aperture
uniform float uConeDistance;  // cones stop here, voxels
uniform float uConeOffset;    // cones start this far out along the normal, voxels
uniform float uConeStep;      // steps: this share of the cone's width (of twice the sample's near the surface)
uniform int uCones;           // 1: the normal; n: the normal and a ring of n - 1
uniform uint uDirectional;    // 1: the volume has six-way radiance from level 1 up
uniform uint uInterleave;     // 1: each pixel of a 4x4 tile its own cone pattern (conePattern)
uniform uint uConeClearance;  // 1: lit cones read coarse texels only clear of voxels (clearOfVoxels)

/// Where a cone samples at distance t, for a cone from `height` voxels out of
/// the surface of normal n, along dir, of half-angle tangent tanHalf: the
/// sample's width (the cone's, but near the surface no wider than a third
/// of its height above it: design §7c), the step to the next sample, and the
/// mip level. Every cone of the volume follows it.
struct ConeSample {
    float width;
    float stride;
    float lod;
};
ConeSample coneSampleAt(float t, float height, vec3 dir, vec3 n, float tanHalf)
{
    float above = height + t * dot(dir, n);
    float cone = max(uTexelCells, 2.0 * t * tanHalf);
    ConeSample k;
    k.width = max(uTexelCells, min(cone, above / 3.0));
    k.stride = uConeStep * min(cone, 2.0 * k.width);
    k.lod = log2(k.width / uTexelCells);
    return k;
}

/// Sample k of a lit cone at cell-space point q, made no coarser than the
/// coarsest level whose sample at q reads no voxel, down to level 0
/// (Illumination::clearance). A coarse texel that straddles a one-voxel wall
/// holds the light of both its sides, and a cone beside the wall sees the
/// far room's; cones held at level 0 leak 0.05 % of what isotropic cones do
/// (design §7d). One fetch: light_clear.comp gives each texel of level 0
/// the coarsest level that reads no voxel from anywhere in it (outside the
/// volume, its nearest texel's: the volume's border is empty). The steps
/// shrink with the width.
ConeSample clearOfVoxels(ConeSample k, vec3 q)
{
    if (uConeClearance == 0u || k.lod <= 0.0) return k;
    ivec3 last = textureSize(uClearLevel, 0) - 1;
    float clear = float(texelFetch(uClearLevel, clamp(ivec3(floor(q / uTexelCells)), ivec3(0), last), 0).r);
    if (clear >= k.lod) return k;
    k.lod = clear;
    k.width = uTexelCells * exp2(clear);
    k.stride = min(k.stride, uConeStep * 2.0 * k.width);
    return k;
}

/// The pixel's cone pattern: x, the ring's turn, a share of the spacing of
/// its cones in (-1/2, 1/2); y, the first step's share of a step, (0, 1]
/// (the later samples move with it). A cone set samples the coarse texels at
/// fixed places, and its error has the texel grid's pattern (stripes on the
/// Cornell box's walls) and the ring's (bands where its cones reach a wall);
/// with uInterleave the 16 pixels of a 4x4 tile take 16 different sets (any
/// 2x2 block all four turns and all four shifts), and view_resolve.comp
/// averages them, so that a pixel sees 16 sets for the time of one. Without,
/// every pixel the same set: no turn, whole steps.
vec2 conePattern(ivec2 pixel)
{
    if (uInterleave == 0u) return vec2(0.0, 1.0);
    int turn = (pixel.x + 2 * pixel.y) & 3, shift = (2 * pixel.x + pixel.y) & 3; // a bijection of the tile
    return vec2((float(turn) + 0.5) / 4.0 - 0.5, float(shift + 1) / 4.0);
}

/// Radiance (premultiplied; a: opacity) a ray along `dir` sees at level
/// `lod` >= 1, the three axes it travels along weighted by `share`.
vec4 radianceAlong(vec3 dir, vec3 share, vec3 tc, float lod)
{
    float l = lod - 1.0;
    vec4 x = dir.x >= 0.0 ? textureLod(uAlongPositiveX, tc, l) : textureLod(uAlongNegativeX, tc, l);
    vec4 y = dir.y >= 0.0 ? textureLod(uAlongPositiveY, tc, l) : textureLod(uAlongNegativeY, tc, l);
    vec4 z = dir.z >= 0.0 ? textureLod(uAlongPositiveZ, tc, l) : textureLod(uAlongNegativeZ, tc, l);
    return share.x * x + share.y * y + share.z * z;
}

/// The opacity a cone along a direction of squares `share` sees in a sample
/// of the volume at cell-space point q and level lod.
float sampleOpacity(vec3 share, vec3 q, float lod)
{
    return dot(share, textureLod(uOpacityVolume, q * uVolumeScale, lod).rgb);
}

/// Sectors of a cone's cross-section that occlusion is kept in, and their
/// centres on the unit disc (radius 0.62, near the sectors' centroids).
const int kConeSectors = 8;
const vec2 kSectorCentres[kConeSectors] = vec2[](
    vec2(0.5728, 0.2373), vec2(0.2373, 0.5728), vec2(-0.2373, 0.5728), vec2(-0.5728, 0.2373),
    vec2(-0.5728, -0.2373), vec2(-0.2373, -0.5728), vec2(0.2373, -0.5728), vec2(0.5728, -0.2373));

/// Occlusion along one cone, as coneGather's below but kept per sector of the
/// cone's cross-section. Composited samples count the same occluder again
/// when they see it at successive depths: a sphere's front and back, a box's
/// near and far faces, or a wall the cone runs beside each cover the same
/// part of the cone, and compositing them as independent samples made rows
/// of spheres too dark (AO RMSE 0.14 where a maximum over the samples gave
/// 0.08, but the maximum loses walls that cover different parts). Each
/// sample's opacity s is placed where its occluder lies: the opacity's
/// gradient across the cone (two more samples, half a texel to the side)
/// points to it, and an occluder at one side covers a cap of the disc of
/// area s there, as sharply as the gradient says (an even fog: no
/// gradient, every sector s). Each sector composites its own samples; the
/// cone's occlusion is the sectors' mean. A wall across the whole cone
/// still composites as before.
float coneOcclusion(vec3 o, vec3 dir, vec3 n, float height, float tanHalf, float firstStep)
{
    vec3 share = dir * dir;
    vec3 e1 = normalize(abs(dir.x) < 0.6 ? cross(dir, vec3(1.0, 0.0, 0.0)) : cross(dir, vec3(0.0, 1.0, 0.0)));
    vec3 e2 = cross(dir, e1);
    float open[kConeSectors];
    for (int i = 0; i < kConeSectors; ++i) open[i] = 1.0;
    float occlusion = 0.0;
    float t = 0.0;
    while (t < uConeDistance && occlusion < 0.99) {
        ConeSample k = coneSampleAt(t, height, dir, n, tanHalf);
        float width = k.width, lod = k.lod;
        float stride = t == 0.0 ? firstStep * k.stride : k.stride;
        vec3 q = o + t * dir;
        float s = sampleOpacity(share, q, lod);
        vec2 g = 2.0 * vec2(sampleOpacity(share, q + 0.5 * width * e1, lod) - s,
                            sampleOpacity(share, q + 0.5 * width * e2, lod) - s);
        float slope = length(g);
        // How sharply the occluder lies to one side: an edge across the
        // sample changes the opacity over the texel by up to twice the
        // smaller of s and 1 - s.
        float sharp = clamp(slope / max(2.0 * min(s, 1.0 - s), 1e-3), 0.0, 1.0);
        vec2 towards = slope > 1e-5 ? g / slope : vec2(1.0, 0.0);
        float chord = cos(3.14159265 * clamp(s, 0.0, 1.0)); // a cap of area s lies beyond it (nearly)
        float cover[kConeSectors];
        float mean = 0.0;
        for (int i = 0; i < kConeSectors; ++i) {
            cover[i] = clamp(dot(kSectorCentres[i], towards) - chord + 0.5, 0.0, 1.0);
            mean += cover[i] / float(kConeSectors);
        }
        float left = 0.0;
        for (int i = 0; i < kConeSectors; ++i) {
            float capped = mean > 1e-4 ? min(1.0, cover[i] * s / mean) : s;
            open[i] *= 1.0 - pathOpacity(mix(s, capped, sharp), stride / width);
            left += open[i] / float(kConeSectors);
        }
        occlusion = 1.0 - left;
        t += stride;
    }
    return occlusion;
}

/// Radiance gathered (rgb; 0 unless `lit`) and occlusion (a) along one cone
/// of half-angle tangent `tanHalf` from o, which lies `height` voxels out of
/// the surface along its normal n. Near the surface a sample must not see
/// the surface's own texels (design §7c): a trilinear sample between two
/// levels reaches 1.5 texels of the coarser one, up to twice its width, and
/// a surface's texel can sit half a texel above it, so a sample takes a
/// level no wider than a third of its height above the surface (then an
/// open plane is unoccluded), and the cone steps by uConeStep of its width
/// but (at the default of a half) by at most the sample's width, so that it
/// cannot step over a thin wall; each sample's opacity is corrected to the
/// path its step covers. Unlit (AO), the occlusion is coneOcclusion's. The
/// first step is `firstStep` of a step (conePattern).
vec4 coneGather(vec3 o, vec3 dir, vec3 n, float height, bool lit, float tanHalf, float firstStep)
{
    if (!lit) return vec4(vec3(0.0), coneOcclusion(o, dir, n, height, tanHalf, firstStep));
    vec3 share = dir * dir; // directional opacity, weighted by the direction's squares (they sum to 1)
    float occlusion = 0.0;
    vec3 radiance = vec3(0.0);
    float t = 0.0;
    while (t < uConeDistance && occlusion < 0.99) {
        ConeSample k = clearOfVoxels(coneSampleAt(t, height, dir, n, tanHalf), o + t * dir);
        float width = k.width, lod = k.lod;
        float stride = t == 0.0 ? firstStep * k.stride : k.stride;
        vec3 tc = (o + t * dir) * uVolumeScale;
        // The sample stands for a slab as deep as the texel is wide; its
        // opacity is corrected to the path the step covers.
        float a = pathOpacity(dot(share, textureLod(uOpacityVolume, tc, lod).rgb), stride / width);
        // Six-way: from level 1 up, what a ray along dir sees; between levels
        // 0 and 1, blended with level 0's isotropic radiance.
        // Level 0 sends its light only towards its lit side.
        vec4 r;
        if (uDirectional != 0u) {
            vec4 base = vec4(0.0);
            if (lod < 1.0) {
                base = textureLod(uRadianceVolume, tc, 0.0);
                base.rgb *= towardsLitSide(litSideOf(textureLod(uLitSide, tc, 0.0).xyz, base.rgb), -dir);
            }
            r = lod <= 0.0 ? base : (lod >= 1.0 ? radianceAlong(dir, share, tc, lod)
                                                : mix(base, radianceAlong(dir, share, tc, 1.0), lod));
        } else {
            r = textureLod(uRadianceVolume, tc, lod);
        }
        vec3 l = r.a > 1e-4 ? r.rgb / r.a : vec3(0.0);
        radiance += (1.0 - occlusion) * a * l;
        occlusion += (1.0 - occlusion) * a;
        t += stride;
    }
    return vec4(radiance, occlusion);
}

/// Level 0's opacity at cell-space point q, the mean of x, y and z.
float opacityNear(vec3 q)
{
    return dot(opacityFromStored(textureLod(uOpacityVolume, q * uVolumeScale, 0.0).rgb), vec3(1.0 / 3.0));
}

/// Point o, out of its surface along that surface's unit normal n, moved
/// away from any other surface beside it. Beside a concave edge o lies among
/// the other surface's texels: every cone from there would composite that
/// surface again and again (the pixels along the edge came out nearly
/// black), and a shadow ray from there starts inside it. Level 0's opacity
/// gradient across n points to it; o moves up to 2 texels away, in
/// proportion to the opacity it lies in (all 2 from a third), at the same
/// height above its own surface, and never away from the viewer (unit
/// toViewer): the camera sees the edge from the open side of the other
/// surface. Where that surface is one voxel thick and o lies in its voxel,
/// the gradient points across it (to the voxel's centre), and o would move
/// through it into the room behind.
vec3 awayFromBeside(vec3 o, vec3 n, vec3 toViewer)
{
    float h = uTexelCells;
    vec3 g = vec3(opacityNear(o + vec3(h, 0.0, 0.0)) - opacityNear(o - vec3(h, 0.0, 0.0)),
                  opacityNear(o + vec3(0.0, h, 0.0)) - opacityNear(o - vec3(0.0, h, 0.0)),
                  opacityNear(o + vec3(0.0, 0.0, h)) - opacityNear(o - vec3(0.0, 0.0, h)));
    g -= dot(g, n) * n;
    if (length(g) < 1e-4) return o;
    vec3 away = -normalize(g);
    if (dot(away, toViewer) < 0.0) away = -away;
    return o + 2.0 * h * min(1.0, 3.0 * opacityNear(o)) * away;
}

/// Where the cones of a point p with unit normal n start: uConeOffset out
/// along n, away from any other surface there (awayFromBeside).
vec3 coneStart(vec3 p, vec3 n, vec3 toViewer) { return awayFromBeside(p + uConeOffset * n, n, toViewer); }

/// Cosine-weighted gather over the hemisphere of unit normal n at p: the
/// normal's cone (up to 30 degrees) weighs a quarter, a ring of cones tilted
/// 60 degrees three quarters. rgb: the mean incoming radiance (times albedo,
/// the light one diffuse bounce reflects; 0 unless `lit`); a: the mean
/// occlusion. `pattern` turns the ring and shifts the steps (conePattern);
/// toViewer (unit) keeps the start on the camera's side (awayFromBeside).
vec4 hemisphereGather(vec3 p, vec3 n, vec3 toViewer, bool lit, vec2 pattern)
{
    vec3 o = coneStart(p, n, toViewer);
    if (uCones <= 1) return coneGather(o, n, n, uConeOffset, lit, uConeTanHalf, pattern.y);
    vec3 t1 = normalize(abs(n.x) < 0.6 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0)));
    vec3 t2 = cross(n, t1);
    vec4 sum = 0.25 * coneGather(o, n, n, uConeOffset, lit, uConeTanHalf, pattern.y);
    int ring = uCones - 1;
    for (int i = 0; i < ring; ++i) {
        float phi = 6.2831853 * (float(i) + 0.5 + pattern.x) / float(ring);
        vec3 dir = normalize(0.5 * n + 0.8660254 * (cos(phi) * t1 + sin(phi) * t2));
        sum += 0.75 / float(ring) * coneGather(o, dir, n, uConeOffset, lit, uConeTanHalf, pattern.y);
    }
    return sum;
}
