#version 450 core
// One level of the lighting volume's mip-map from the level below (design
// §7d). Radiance (premultiplied by coverage) and coverage are the mean of
// the 2³ children. Opacity seen along an axis composites the children along
// that axis (1 - Π(1 - a)) and averages the columns across it, so a wall
// across the axis stays opaque and one along it covers its share
// (Crassin's anisotropic filter). An axis already one texel wide has one
// child along it. With uLit 0 (ambient occlusion's opacity volume), opacity
// alone.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, rgba16f) readonly restrict uniform image3D uOpacityIn;
layout(binding = 1, rgba16f) readonly restrict uniform image3D uRadianceIn;
layout(binding = 2, rgba16f) writeonly restrict uniform image3D uOpacityOut;
layout(binding = 3, rgba16f) writeonly restrict uniform image3D uRadianceOut;

uniform ivec3 uInSize;
uniform ivec3 uOutSize;
uniform uint uLit; // 0: no radiance images

#include "opacity_depth.glsl"

void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, uOutSize))) return;
    ivec3 n = ivec3(uInSize.x > 1 ? 2 : 1, uInSize.y > 1 ? 2 : 1, uInSize.z > 1 ? 2 : 1);
    ivec3 base = ivec3(uInSize.x > 1 ? 2 * p.x : p.x, uInSize.y > 1 ? 2 * p.y : p.y, uInSize.z > 1 ? 2 * p.z : p.z);
    vec4 children[8];
    vec4 radiance = vec4(0.0);
    float coverage = 0.0;
    for (int i = 0; i < 8; ++i) {
        ivec3 c = ivec3(i & 1, (i >> 1) & 1, i >> 2);
        bool used = all(lessThan(c, n));
        children[i] = used ? imageLoad(uOpacityIn, base + c) : vec4(0.0);
        children[i].rgb = opacityFromStored(children[i].rgb);
        if (used && uLit != 0u) radiance += imageLoad(uRadianceIn, base + c);
        coverage += children[i].a;
    }
    float count = float(n.x * n.y * n.z);
    // Per axis: Π(1 - a) along it, summed over the columns across it.
    vec3 through = vec3(0.0);
    for (int u = 0; u < n.y; ++u) // along x: columns (y, z)
        for (int v = 0; v < n.z; ++v) {
            float t = 1.0;
            for (int x = 0; x < n.x; ++x) t *= 1.0 - children[x | (u << 1) | (v << 2)].r;
            through.x += t;
        }
    for (int u = 0; u < n.x; ++u) // along y: columns (x, z)
        for (int v = 0; v < n.z; ++v) {
            float t = 1.0;
            for (int y = 0; y < n.y; ++y) t *= 1.0 - children[u | (y << 1) | (v << 2)].g;
            through.y += t;
        }
    for (int u = 0; u < n.x; ++u) // along z: columns (x, y)
        for (int v = 0; v < n.y; ++v) {
            float t = 1.0;
            for (int z = 0; z < n.z; ++z) t *= 1.0 - children[u | (v << 1) | (z << 2)].b;
            through.z += t;
        }
    vec3 columns = vec3(n.y * n.z, n.x * n.z, n.x * n.y);
    imageStore(uOpacityOut, p, vec4(storedOpacity(vec3(1.0) - through / columns), coverage / count));
    if (uLit != 0u) imageStore(uRadianceOut, p, radiance / count);
}
