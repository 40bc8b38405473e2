// How the lighting volume's opacity texture holds a texel's opacity seen
// along x, y and z (design §7d): the opacity a itself, or, in six-way
// volumes (Illumination::directional), its optical depth -ln(1 - a), so that
// trilinear samples between an opaque wall's texel and its empty neighbours
// still composite to an opaque wall: interpolated opacities 0.5 and 0.5 let
// a quarter of the light through a wall that stops all of it, interpolated
// depths add up to the wall's. Included by the injection, the mip-map and
// the cones.

uniform uint uOpticalDepth; // 1: the opacity texture holds optical depth

/// The deepest a texel is stored: opacity 0.999 (a half float holds it).
const float kOpacityDepthMax = 6.9;

/// Opacity as the texture holds it.
vec3 storedOpacity(vec3 a)
{
    return uOpticalDepth != 0u ? min(-log(max(1.0 - a, vec3(0.0))), vec3(kOpacityDepthMax)) : a;
}

/// Opacity from what the texture holds.
vec3 opacityFromStored(vec3 s) { return uOpticalDepth != 0u ? 1.0 - exp(-s) : s; }

/// The opacity of a path `share` times as long as a texel is wide through a
/// sample `s` of the texture (a blend of texels): the optical depth scales
/// with the path, 1 - (1 - a)^share.
float pathOpacity(float s, float share)
{
    return uOpticalDepth != 0u ? 1.0 - exp(-s * share) : 1.0 - pow(max(1.0 - s, 0.0), share);
}
