#version 450 core
// Interleaved cones, resolved (AmbientOcclusion::interleave,
// Illumination::interleave): the 16 pixels of a 4x4 tile gathered their
// light with 16 different cone patterns (view_gather.glsl, conePattern), and
// each pixel takes the mean of those in the 4x4 window around it (any such
// window holds every pattern once) that lie on its own surface, then its
// colour (view_compose.glsl). Its own surface: a normal within 25 degrees
// of its own, and a point within uPlaneTolerance voxels of its tangent
// plane, so that AO and light do not blur across edges and depth steps.
#include "gpu_layout.h"
#include "view_layout.h"
#include "view_compose.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = SVO_IMAGE_VIEW_PIXELS) uniform restrict image2D uPixels;
layout(rgba32ui, binding = SVO_IMAGE_VIEW_GATHER) uniform readonly restrict uimage2D uGathered;
// xyz: where the pixel's cones left from, cell space; w: 1, or 0 where the ray hit nothing.
layout(rgba32f, binding = SVO_IMAGE_VIEW_POINTS) uniform readonly restrict image2D uPoints;

uniform vec2 uViewport;       // pixels
uniform float uPlaneTolerance; // voxels: a voxel's centre lies up to sqrt(3)/2 from its surface

void main()
{
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(vec2(pixel), uViewport))) return;
    vec4 point = imageLoad(uPoints, pixel);
    if (point.w == 0.0) return;
    uvec4 own = imageLoad(uGathered, pixel);
    vec3 n = unpackNormal(own);
    vec3 sum = vec3(0.0);
    float count = 0.0;
    for (int dy = -2; dy < 2; ++dy) {
        for (int dx = -2; dx < 2; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(vec2(q), uViewport))) continue;
            vec4 other = imageLoad(uPoints, q);
            if (other.w == 0.0 || abs(dot(n, other.xyz - point.xyz)) > uPlaneTolerance) continue;
            uvec4 g = imageLoad(uGathered, q);
            if (dot(unpackNormal(g), n) < 0.9) continue;
            sum += unpackGathered(g);
            count += 1.0;
        }
    }
    vec4 pixelColor = imageLoad(uPixels, pixel);
    imageStore(uPixels, pixel, vec4(composePixel(pixelColor.rgb, unpackAlbedo(own), sum / count), pixelColor.a));
}
