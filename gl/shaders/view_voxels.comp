#version 450 core
// Voxels by ray-marching the octree (svo/gl/octree_view.h, view_octree.glsl):
// one ray per pixel, shaded by a head light, by a voxel attribute, by cone-
// traced ambient occlusion, or lit: direct light with shadows and one diffuse
// bounce gathered by cones through the lighting volume.
//
// A compute pass, not a full-screen fragment pass, because chips built for
// compute (the H100) run fragment shaders on a few of their cores only; the
// pixels go to an image that view_pixels.frag then writes, with their depth,
// into the framebuffer.
#include "gpu_layout.h"
#include "view_octree.glsl"
#include "loop_cut.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
// rgb = the pixel's colour; a = its window depth, or -1 where the ray hits no voxel.
layout(rgba32f, binding = SVO_IMAGE_VIEW_PIXELS) uniform writeonly restrict image2D uPixels;

layout(std430, binding = SVO_BIND_VIEW_ATTRIBUTE) readonly restrict buffer Attribute { uint channel[]; };

uniform mat4 uInverseViewProjection; // clip -> cell space
uniform mat4 uViewProjection;        // cell space -> clip
uniform vec2 uViewport;              // pixels
uniform vec3 uColor;
uniform int uColorMode;              // SVO_VIEW_COLOR_*: flat uColor or a voxel attribute

/// The voxel's colour: flat, or its attribute.
vec3 voxelColor(uint brick, uint bit)
{
    if (uColorMode == SVO_VIEW_COLOR_FLAT) return uColor;
    uint v = voxelIndex(brick, bit);
    if (uColorMode == SVO_VIEW_COLOR_TRIANGLE) { // distinct colours for neighbouring ids
        uint h = channel[v] * 2654435761u;
        return vec3(float(h >> 24u), float((h >> 16u) & 255u), float((h >> 8u) & 255u)) / 255.0 * 0.8 + 0.2;
    }
    vec3 c = vec3(uintBitsToFloat(channel[3u * v]), uintBitsToFloat(channel[3u * v + 1u]),
                  uintBitsToFloat(channel[3u * v + 2u]));
    return uColorMode == SVO_VIEW_COLOR_NORMAL ? 0.5 + 0.5 * c : c;
}

#include "view_cones.glsl"
#include "view_lights.glsl"
#include "view_gather.glsl"

uniform uint uAoOnly;    // 1: the voxels are their AO, grey
uniform uint uAoVolume;  // 1: AO from cones through the opacity volume (view_gather.glsl); 0: through the octree
uniform uint uAoNormals; // 1: the octree has a normal channel (Volume AO leaves along it)
uniform int uLightMode;  // 0: head light; 1: direct light; 2: direct and one diffuse bounce
uniform float uExposure; // lit modes: radiance x exposure ...
uniform float uGamma;    // ... to the power 1 / gamma
uniform vec3 uSpecular;         // glossy reflectance (Illumination::specular)
uniform float uSpecularTanHalf; // tan of half the glossy cone's aperture

/// One pixel's ray, shaded, into uPixels.
void castRay(ivec2 pixel)
{
    vec2 ndc = (vec2(pixel) + 0.5) / uViewport * 2.0 - 1.0;
    vec4 a = uInverseViewProjection * vec4(ndc, -1.0, 1.0);
    vec4 b = uInverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w;
    vec3 d = b.xyz / b.w - o; // t in [0, 1] spans the near to the far plane
    VoxelHit hit;
    if (!marchOctree(o, d, 0.0, 1.0, hit)) {
        imageStore(uPixels, pixel, vec4(0.0, 0.0, 0.0, -1.0));
        return;
    }

    vec3 face = vec3(0.0);
    face[hit.axis] = -sign(d[hit.axis]);
    vec3 p = o + d * hit.t;
    vec4 color;
    if (uLightMode != 0) {
        // Lit: the surface's normal (its channel, turned to the viewer; the
        // face's where the normals cancel), direct light at the voxel's
        // centre, and for GI the albedo times the light the cones gather.
        // The direct light on the side the camera sees was computed once per
        // voxel by the injection; a voxel without a normal takes the face's,
        // which depends on the ray, and marches its own shadow rays.
        uint v = voxelIndex(hit.brick, hit.bit);
        vec3 m = voxelNormal(v);
        bool hasNormal = length(m) > 1e-6;
        vec3 n = hasNormal ? normalize(m) : face;
        bool front = dot(n, d) <= 0.0;
        if (!front) n = -n;
        vec3 c = vec3(hit.cell) + 0.5;
        vec3 albedo = voxelAlbedo(v);
        vec3 e = hasNormal ? storedIrradiance(v, front) : irradiance(c, n);
        vec3 radiance = albedo * (1.0 / 3.14159265) * e;
        if (uLightMode == 2) {
            radiance += albedo * hemisphereGather(c, n, true).rgb;
            // Glossy: one cone along the view ray mirrored about the normal.
            if (any(greaterThan(uSpecular, vec3(0.0))))
                radiance += uSpecular * coneGather(c + uConeOffset * n, reflect(normalize(d), n), n, uConeOffset,
                                                   true, uSpecularTanHalf).rgb;
        }
        color = vec4(pow(clamp(radiance * uExposure, 0.0, 1.0), vec3(1.0 / uGamma)), 1.0);
    } else {
        // Lit by the face normal: a head light plus a little ambient.
        float light = 0.45 + 0.55 * abs(dot(face, normalize(d)));
        float ao = 1.0;
        if (uAoVolume == 0u) {
            ao = ambientOcclusion(p, face);
        } else if (uCones > 0) {
            // From the voxel's centre along its normal (the face's where it
            // has none, or its normals cancel), turned to the viewer.
            vec3 n = face;
            if (uAoNormals != 0u) {
                vec3 m = voxelNormal(voxelIndex(hit.brick, hit.bit));
                if (length(m) > 1e-6) n = normalize(dot(m, d) > 0.0 ? -m : m);
            }
            ao = 1.0 - hemisphereGather(vec3(hit.cell) + 0.5, n, false).a;
        }
        color = uAoOnly != 0u ? vec4(vec3(ao), 1.0) : vec4(voxelColor(hit.brick, hit.bit) * light * ao, 1.0);
    }
    vec4 clip = uViewProjection * vec4(p, 1.0);
    imageStore(uPixels, pixel, vec4(color.rgb, clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0)));
}

void main()
{
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(vec2(pixel), uViewport))) return;
    castRay(pixel);
    countIfLoopsWereCut();
}
