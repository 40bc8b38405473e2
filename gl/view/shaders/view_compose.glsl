// A voxel-pass pixel's colour from its parts (view_voxels.comp, and
// view_resolve.comp when the cones are interleaved): its own part, and the
// light its cones gathered, which the resolve pass averages over the
// pixel's 4x4 tile before composing. Also the packing of the parts the
// resolve pass reads.

uniform int uLightMode;  // 0: head light (and AO); 1: direct light; 2: direct and one diffuse bounce
uniform uint uAoOnly;    // 1: the voxels are their AO, grey
uniform float uExposure; // lit modes: radiance x exposure ...
uniform float uGamma;    // ... to the power 1 / gamma

/// The colour: lit, own = the radiance the pixel sends without the bounce
/// (direct, glossy), plus for the bounce albedo x gathered (the mean incoming
/// radiance), exposed and gamma-corrected; unlit, own = the base colour
/// times the head light, times AO (gathered.r), or AO alone, grey.
vec3 composePixel(vec3 own, vec3 albedo, vec3 gathered)
{
    if (uLightMode == 0) return uAoOnly != 0u ? vec3(gathered.r) : own * gathered.r;
    vec3 radiance = uLightMode == 2 ? own + albedo * gathered : own;
    return pow(clamp(radiance * uExposure, 0.0, 1.0), vec3(1.0 / uGamma));
}

/// A unit vector in 32 bits: octahedral, two snorm16.
uint packUnitVector(vec3 n)
{
    vec2 e = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if (n.z < 0.0) e = (1.0 - abs(e.yx)) * vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
    return packSnorm2x16(e);
}
vec3 unpackUnitVector(uint bits)
{
    vec2 e = unpackSnorm2x16(bits);
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

/// What the resolve pass reads of a pixel whose cones are interleaved:
/// the gathered light (half floats), the albedo (unorm8) and the normal its
/// cones left along.
uvec4 packGathered(vec3 gathered, vec3 albedo, vec3 n)
{
    return uvec4(packHalf2x16(gathered.rg), packHalf2x16(vec2(gathered.b, 0.0)),
                 packUnorm4x8(vec4(clamp(albedo, 0.0, 1.0), 0.0)), packUnitVector(n));
}
vec3 unpackGathered(uvec4 g) { return vec3(unpackHalf2x16(g.x), unpackHalf2x16(g.y).x); }
vec3 unpackAlbedo(uvec4 g) { return unpackUnorm4x8(g.z).rgb; }
vec3 unpackNormal(uvec4 g) { return unpackUnitVector(g.w); }
