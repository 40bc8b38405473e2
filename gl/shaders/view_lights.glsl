// Direct light at a voxel, shadowed by the octree's own voxels (design §7d):
// included after view_octree.glsl by the light injection and by the view.
//
// Lights come in cell space, two vec4 each: (direction of travel, unit; 0)
// and (irradiance E; 0) for a directional light, (position; 1) and
// (intensity I; 0) for a point light. A light is seen from a voxel when a
// ray from the voxel's centre, pushed uShadowOffset voxels out of the surface
// along the normal on the light's side, reaches it without entering an
// occupied voxel: the conservative voxels of the surface itself reach up to
// √3 voxels from it, so a smaller push lets a surface shadow itself.

layout(std430, binding = SVO_BIND_VIEW_LIGHTS) readonly restrict buffer LightList { vec4 lights[]; };
layout(std430, binding = SVO_BIND_VIEW_NORMALS) readonly restrict buffer Normals { float normals[]; };
layout(std430, binding = SVO_BIND_VIEW_ALBEDO) readonly restrict buffer Albedo { float albedos[]; };

uniform int uLightCount;
uniform float uShadowOffset; // voxels
uniform float uVoxelSize;    // world units per voxel: point lights fall off with world distance
uniform vec3 uAlbedo;        // when the octree has no colour channel
uniform uint uHasAlbedo;     // 1: the colour channel is the albedo

vec3 voxelNormal(uint v) { return vec3(normals[3u * v], normals[3u * v + 1u], normals[3u * v + 2u]); }

vec3 voxelAlbedo(uint v)
{
    if (uHasAlbedo == 0u) return uAlbedo;
    return clamp(vec3(albedos[3u * v], albedos[3u * v + 1u], albedos[3u * v + 2u]), 0.0, 1.0);
}

/// The irradiance Σ E cos θ V (Σ I cos θ / r² V for point lights) at the
/// centre c of a voxel with unit normal n. Two-sided: each light lights the
/// side it is on (the voxel stands for a thin surface seen from both sides);
/// one-sided: only lights on n's side count. n = 0 (a voxel whose normals
/// cancel) takes every light as if facing it. `litSide` gets the normal
/// turned to each light's side, averaged by the light each gives (0 when
/// none arrives; short when lights reach both sides).
vec3 irradiance(vec3 c, vec3 n, bool twoSided, out vec3 litSide)
{
    vec3 sum = vec3(0.0);
    litSide = vec3(0.0);
    float power = 0.0;
    for (int i = 0; i < uLightCount; ++i) {
        vec4 a = lights[2 * i], b = lights[2 * i + 1];
        vec3 l, e;
        float reach; // cells from the pushed origin to the light
        if (a.w == 0.0) {
            l = -a.xyz;
            e = b.rgb;
            reach = kNever;
        } else {
            vec3 to = a.xyz - c;
            float r = length(to);
            if (r == 0.0) continue;
            l = to / r;
            float world = r * uVoxelSize;
            e = b.rgb / (world * world);
            reach = r;
        }
        bool isotropic = dot(n, n) == 0.0;
        float cosTheta = isotropic ? 1.0 : dot(n, l);
        if (twoSided) cosTheta = abs(cosTheta);
        if (cosTheta <= 0.0) continue;
        vec3 side = isotropic ? l : (dot(n, l) >= 0.0 ? n : -n);
        vec3 o = c + uShadowOffset * side;
        if (a.w != 0.0) reach = dot(a.xyz - o, l);
        VoxelHit h;
        if (reach > 0.0 && marchOctree(o, l, 0.0, reach, h)) continue;
        sum += e * cosTheta;
        float p = dot(e, vec3(1.0)) * cosTheta;
        litSide += p * side;
        power += p;
    }
    if (power > 0.0) litSide /= power;
    return sum;
}

vec3 irradiance(vec3 c, vec3 n, bool twoSided)
{
    vec3 litSide;
    return irradiance(c, n, twoSided, litSide);
}

/// The share of a texel's light that leaves towards unit direction v when
/// its lit side is m (light_inject.comp): all of it in front of the lit
/// side and along it, none behind it; a texel lit from both sides (m short)
/// sends light both ways.
float towardsLitSide(vec3 m, vec3 v) { return clamp(1.0 + 2.0 * dot(m, v), 0.0, 1.0); }
