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

// Written by the injection, read by the picture: per voxel in voxel order,
// the irradiance on the side its normal points to and on the other (rgb
// each, as halves: front.rg, front.b back.r, back.gb), so that a picture's
// pixel needs no shadow ray of its own.
layout(std430, binding = SVO_BIND_VIEW_DIRECT) restrict buffer DirectLight { uvec4 directLight[]; };

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
/// centre c of a voxel with unit normal n, from the lights on n's side
/// (`front`) and from those on the other side (`back`): a voxel stands for
/// a thin surface seen from both sides. n = 0 (a voxel whose normals cancel)
/// takes every light as if facing it, in front.
///
/// With `centre` (c is the voxel's centre: the injection), also what the
/// lighting volume takes: `seen`, the irradiance from the lights whose push
/// out of the voxel enters no other voxel on its way. A tilted surface's
/// conservative voxels lie two or three deep, and only those on the light's
/// side of it show the lit side: a voxel on the far side, pushed along the
/// normal through the others into the lit room, would send the lit side's
/// light out of the dark side (a wall one voxel thick, as the axis-aligned
/// walls of the two rooms, has no such voxel). `hidden`: every light that reaches one of the voxel's sides was pushed
/// into another voxel (it is the back of its surface; not set for a voxel no
/// light faces). `litSide` gets the normal turned to each seen light's side,
/// averaged by the light each gives (0 when none arrives; short when lights
/// reach both sides). Without `centre`, `seen` is front + back and nothing
/// is hidden.
void irradianceBySide(vec3 c, vec3 n, bool centre, out vec3 front, out vec3 back, out vec3 seen, out vec3 litSide,
                      out bool hidden)
{
    front = vec3(0.0);
    back = vec3(0.0);
    seen = vec3(0.0);
    litSide = vec3(0.0);
    float power = 0.0;
    int facing = 0, blocked = 0;
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
        if (cosTheta == 0.0) continue;
        vec3 side = isotropic ? l : (cosTheta > 0.0 ? n : -n);
        vec3 o = c + uShadowOffset * side;
        // The push, from just past the voxel's own faces (the centre's
        // nearest exit along `side`) to o.
        bool pushedIn = false;
        if (centre) {
            vec3 ad = abs(side);
            float leave = 0.5 / max(ad.x, max(ad.y, ad.z)) + 1e-3;
            VoxelHit p;
            pushedIn = leave < uShadowOffset && marchOctree(c, side, leave, uShadowOffset, p);
            ++facing;
            if (pushedIn) ++blocked;
        }
        if (a.w != 0.0) reach = dot(a.xyz - o, l);
        VoxelHit h;
        if (reach > 0.0 && marchOctree(o, l, 0.0, reach, h)) continue;
        if (cosTheta > 0.0) front += e * cosTheta;
        else back -= e * cosTheta;
        if (pushedIn) continue;
        seen += e * abs(cosTheta);
        float p = dot(e, vec3(1.0)) * abs(cosTheta);
        litSide += p * side;
        power += p;
    }
    if (power > 0.0) litSide /= power;
    hidden = facing > 0 && blocked == facing;
}

/// One-sided: the lights on n's side (n not 0).
vec3 irradiance(vec3 c, vec3 n)
{
    vec3 front, back, seen, litSide;
    bool hidden;
    irradianceBySide(c, n, false, front, back, seen, litSide, hidden);
    return front;
}

/// Voxel v's stored irradiance on the side of unit normal n (`front`: n is
/// the voxel's normal, not its opposite).
vec3 storedIrradiance(uint v, bool front)
{
    uvec4 p = directLight[v];
    vec2 a = unpackHalf2x16(p.x), b = unpackHalf2x16(p.y), c = unpackHalf2x16(p.z);
    return front ? vec3(a, b.x) : vec3(b.y, c);
}

void storeIrradiance(uint v, vec3 front, vec3 back)
{
    directLight[v] = uvec4(packHalf2x16(front.rg), packHalf2x16(vec2(front.b, back.r)), packHalf2x16(back.gb), 0u);
}

