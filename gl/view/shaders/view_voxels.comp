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
#include "view_layout.h"
#include "view_octree.glsl"
#include "loop_cut.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
// rgb = the pixel's colour; a = its window depth, or -1 where the ray hits no voxel.
layout(rgba32f, binding = SVO_IMAGE_VIEW_PIXELS) uniform writeonly restrict image2D uPixels;
// With uInterleave, the pixel's parts for view_resolve.comp: uPixels gets
// its own part (rgb; view_compose.glsl), these the light its cones gathered
// and where they left from.
layout(rgba32ui, binding = SVO_IMAGE_VIEW_GATHER) uniform writeonly restrict uimage2D uGathered;
layout(rgba32f, binding = SVO_IMAGE_VIEW_POINTS) uniform writeonly restrict image2D uPoints;

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
#include "view_compose.glsl"

uniform uint uAoVolume;  // 1: AO from cones through the opacity volume (view_gather.glsl); 0: through the octree
uniform uint uAoNormals; // 1: the octree has a normal channel (Volume AO leaves along it)
uniform vec3 uSpecular;         // glossy reflectance (Illumination::specular)
uniform float uSpecularTanHalf; // tan of half the glossy cone's aperture

uniform uint uSurface;    // 1: shade the mesh's surface (ViewLayers::surface = Mesh), not the voxels rays hit
layout(binding = SVO_UNIT_VIEW_SURFACE_TRIANGLE) uniform usampler2D uSurfaceTriangle; // view_surface.frag
layout(std430, binding = SVO_BIND_VIEW_MESH_POSITIONS) readonly restrict buffer MeshPositions { float meshPosition[]; };
layout(std430, binding = SVO_BIND_VIEW_MESH_TRIANGLES) readonly restrict buffer MeshTriangles { uint meshCorner[]; };

vec3 meshVertex(uint corner)
{
    uint v = meshCorner[corner];
    return vec3(meshPosition[3u * v], meshPosition[3u * v + 1u], meshPosition[3u * v + 2u]);
}

/// Where the ray o + t d meets triangle `triangle`'s plane (p), and its unit
/// normal (either side). The rasterizer found the triangle; the point is
/// computed here, exactly as far as floats go. False for a triangle seen
/// exactly edge-on or of no area, which the rasterizer should not have
/// drawn: the pixel then sees nothing rather than a point at infinity.
bool meshHit(uint triangle, vec3 o, vec3 d, out vec3 p, out vec3 normal)
{
    vec3 a = meshVertex(3u * triangle), b = meshVertex(3u * triangle + 1u), c = meshVertex(3u * triangle + 2u);
    vec3 m = cross(b - a, c - a);
    float along = dot(m, d);
    p = o;
    normal = vec3(0.0, 0.0, 1.0);
    if (along == 0.0 || dot(m, m) == 0.0) return false;
    normal = normalize(m);
    p = o + (dot(m, a - o) / along) * d;
    return true;
}

/// The voxel holding cell-space point p, if the octree has it (a point of
/// the mesh lies in a voxel of its conservative set, up to rounding).
bool voxelAt(vec3 p, out uint brick, out uint bit)
{
    ivec3 cell = ivec3(floor(p));
    bit = 0u;
    int emptyLog2;
    if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, uDims)) || !findBrick(cell, brick, emptyLog2))
        return false;
    bit = brickBit(cell);
    return brickHas(brick, bit);
}

/// A pixel whose ray hit nothing: depth -1, and for the resolve pass no point.
void missed(ivec2 pixel)
{
    imageStore(uPixels, pixel, vec4(0.0, 0.0, 0.0, -1.0));
    if (uInterleave != 0u) imageStore(uPoints, pixel, vec4(0.0));
}

/// One pixel's ray, shaded, into uPixels (with uInterleave, its parts).
void castRay(ivec2 pixel)
{
    vec2 ndc = (vec2(pixel) + 0.5) / uViewport * 2.0 - 1.0;
    vec4 a = uInverseViewProjection * vec4(ndc, -1.0, 1.0);
    vec4 b = uInverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w;
    vec3 d = b.xyz / b.w - o; // t in [0, 1] spans the near to the far plane
    vec3 toViewer = -normalize(d);

    // What the pixel sees: a voxel of the octree (its centre shaded along
    // its normal channel, or the face the ray entered), or a point of the
    // mesh with its triangle's normal, in the voxel holding it where the
    // octree has that voxel (for its attributes).
    vec3 p, c, face, surfaceNormal = vec3(0.0);
    uint brick = 0u, bit = 0u;
    bool inVoxel = true;
    if (uSurface != 0u) {
        uint triangle = texelFetch(uSurfaceTriangle, pixel, 0).r;
        if (triangle == 0u || !meshHit(triangle - 1u, o, d, p, surfaceNormal)) {
            missed(pixel);
            return;
        }
        c = p;
        if (dot(surfaceNormal, d) > 0.0) surfaceNormal = -surfaceNormal;
        int axis = abs(surfaceNormal.x) >= max(abs(surfaceNormal.y), abs(surfaceNormal.z)) ? 0
                   : (abs(surfaceNormal.y) >= abs(surfaceNormal.z) ? 1 : 2);
        face = vec3(0.0);
        face[axis] = sign(surfaceNormal[axis]);
        inVoxel = voxelAt(p, brick, bit);
    } else {
        VoxelHit hit;
        if (!marchOctree(o, d, 0.0, 1.0, hit)) {
            missed(pixel);
            return;
        }
        face = vec3(0.0);
        face[hit.axis] = -sign(d[hit.axis]);
        p = o + d * hit.t;
        c = vec3(hit.cell) + 0.5;
        brick = hit.brick;
        bit = hit.bit;
    }
    bool mesh = uSurface != 0u;
    // The colour's parts (view_compose.glsl), and the normal the cones leave along.
    vec3 own, albedo = vec3(0.0), gathered = vec3(1.0), coneNormal = vec3(0.0);
    vec2 pattern = conePattern(pixel);
    if (uLightMode != 0) {
        // Lit: the surface's normal (the triangle's; or the voxel's channel,
        // or the face's where the normals cancel), turned to the viewer,
        // direct light there, and for GI the albedo times the light the
        // cones gather. A voxel's direct light on the side the camera sees
        // was computed once by the injection; a mesh's point, and a voxel
        // without a normal (whose face depends on the ray), march their own
        // shadow rays.
        vec3 n = surfaceNormal;
        bool stored = false, front = true;
        uint v = 0u;
        if (inVoxel) v = voxelIndex(brick, bit);
        if (!mesh) {
            vec3 m = voxelNormal(v);
            stored = length(m) > 1e-6;
            n = stored ? normalize(m) : face;
            front = dot(n, d) <= 0.0;
            if (!front) n = -n;
        }
        albedo = inVoxel ? voxelAlbedo(v) : uAlbedo;
        // A mesh's point beside another surface (a room's corner) moves its
        // shadow ray's start away from it, as its cones' (awayFromBeside):
        // pushed out along n alone, it starts among the other surface's
        // voxels, and the corner's pixels came out in shadow.
        vec3 shadowFrom = mesh ? awayFromBeside(c + uShadowOffset * n, n, toViewer) - uShadowOffset * n : c;
        vec3 e = stored ? storedIrradiance(v, front) : irradiance(shadowFrom, n);
        own = albedo * (1.0 / 3.14159265) * e;
        if (uLightMode == 2) {
            gathered = hemisphereGather(c, n, toViewer, true, pattern).rgb;
            coneNormal = n;
            // Glossy: one cone along the view ray mirrored about the normal.
            if (any(greaterThan(uSpecular, vec3(0.0))))
                own += uSpecular * coneGather(c + uConeOffset * n, reflect(normalize(d), n), n, uConeOffset, true,
                                              uSpecularTanHalf, 1.0).rgb;
        }
    } else {
        // Lit by the surface's normal: a head light plus a little ambient.
        vec3 lightNormal = mesh ? surfaceNormal : face;
        float light = 0.45 + 0.55 * abs(dot(lightNormal, normalize(d)));
        float ao = 1.0;
        if (uAoVolume == 0u) {
            ao = ambientOcclusion(p, face);
        } else if (uCones > 0) {
            // From the mesh's point along its normal, or from the voxel's
            // centre along its normal (the face's where it has none, or its
            // normals cancel), turned to the viewer.
            vec3 n = mesh ? surfaceNormal : face;
            if (!mesh && uAoNormals != 0u) {
                vec3 m = voxelNormal(voxelIndex(brick, bit));
                if (length(m) > 1e-6) n = normalize(dot(m, d) > 0.0 ? -m : m);
            }
            ao = 1.0 - hemisphereGather(c, n, toViewer, false, pattern).a;
            coneNormal = n;
        }
        vec3 base = inVoxel ? voxelColor(brick, bit) : uColor;
        own = base * light;
        gathered = vec3(ao);
    }
    vec4 clip = uViewProjection * vec4(p, 1.0);
    float depth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);
    if (uInterleave != 0u) { // the resolve pass averages the gathered light, then composes
        imageStore(uPixels, pixel, vec4(own, depth));
        imageStore(uGathered, pixel, packGathered(gathered, albedo, coneNormal));
        imageStore(uPoints, pixel, vec4(c, 1.0));
    } else {
        imageStore(uPixels, pixel, vec4(composePixel(own, albedo, gathered), depth));
    }
}

void main()
{
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(vec2(pixel), uViewport))) return;
    castRay(pixel);
    countIfLoopsWereCut();
}
