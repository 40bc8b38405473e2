#version 450 core
// Light injection (design §7d): level 0 of the lighting volume. One
// invocation per texel, a block of uTexelCells³ voxels inside one brick:
// opacity = its voxels over the voxels of one face of the block, at most 1
// (a surface crossing a box of k³ voxels fills about k² of them), the same
// along x, y and z; radiance = the mean outgoing radiance of its voxels,
// ρ/π · irradiance (two-sided Lambertian), times that opacity; and, for
// Illumination::directional, per face direction the share of it that leaves
// towards that face (the lit sides'
// normals, view_lights.glsl), times the radiance's mean over rgb, so that
// the box filter up the mip-map weighs each texel's shares by its light.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#include "gpu_layout.h"
#include "view_octree.glsl"
#include "view_lights.glsl"

layout(binding = 0, rgba8) writeonly restrict uniform image3D uOpacityOut;
layout(binding = 1, rgba16f) writeonly restrict uniform image3D uRadianceOut;
layout(binding = 2, rgba16f) writeonly restrict uniform image3D uTowardsPositiveOut;
layout(binding = 3, rgba16f) writeonly restrict uniform image3D uTowardsNegativeOut;

uniform ivec3 uBaseSize;  // level 0's texels
uniform int uTexelCells;  // voxels per texel edge: 1, 2, 4 or 8
uniform uint uDirectional; // 1: write the shares by direction

void main()
{
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(texel, uBaseSize))) return;
    ivec3 first = texel * uTexelCells;
    vec4 opacity = vec4(0.0), radiance = vec4(0.0), positive = vec4(0.0), negative = vec4(0.0);
    uint brick;
    int emptyLog2;
    if (all(lessThan(first, uDims)) && findBrick(first, brick, emptyLog2)) {
        uint count = 0u;
        vec3 sum = vec3(0.0), sumPositive = vec3(0.0), sumNegative = vec3(0.0);
        for (int x = 0; x < uTexelCells; ++x)
            for (int y = 0; y < uTexelCells; ++y)
                for (int z = 0; z < uTexelCells; ++z) {
                    ivec3 cell = first + ivec3(x, y, z);
                    uint bit = brickBit(cell);
                    if (any(greaterThanEqual(cell, uDims)) || !brickHas(brick, bit)) continue;
                    uint v = voxelIndex(brick, bit);
                    vec3 n = voxelNormal(v);
                    float len = length(n);
                    n = len > 1e-6 ? n / len : vec3(0.0);
                    vec3 towardsPositive, towardsNegative;
                    vec3 l = voxelAlbedo(v) * (1.0 / 3.14159265) *
                             irradiance(vec3(cell) + 0.5, n, true, towardsPositive, towardsNegative);
                    float mean = dot(l, vec3(1.0 / 3.0));
                    sum += l;
                    sumPositive += mean * towardsPositive;
                    sumNegative += mean * towardsNegative;
                    ++count;
                }
        float k = float(uTexelCells);
        float cover = min(1.0, float(count) / (k * k));
        opacity = vec4(vec3(cover), cover);
        if (count > 0u) {
            float scale = cover / float(count);
            radiance = vec4(sum * scale, cover);
            positive = vec4(sumPositive * scale, 0.0);
            negative = vec4(sumNegative * scale, 0.0);
        }
    }
    imageStore(uOpacityOut, texel, opacity);
    imageStore(uRadianceOut, texel, radiance);
    if (uDirectional != 0u) {
        imageStore(uTowardsPositiveOut, texel, positive);
        imageStore(uTowardsNegativeOut, texel, negative);
    }
}
