// Six-way radiance's rule for level 0 (design §7d), included by the mip-map
// that builds level 1 from it (light_mip_along.comp) and by the cones that
// read level 0 (view_gather.glsl).

/// How much light a texel's premultiplied radiance holds: the weight its
/// lit side is stored with. The injection stores m times it; a trilinear
/// sample of both then gives the lit side of the light the sample holds
/// (litSideOf), not a blend with the empty or unlit texels beside it, which
/// shortened m at a lit wall's face into "lit from both sides" and let
/// samples on the wall's dark side see its light.
float lightOf(vec3 premultiplied) { return dot(premultiplied, vec3(1.0 / 3.0)); }

/// The lit side m of the light in `premultiplied` radiance, from the stored
/// (or sampled) m times lightOf.
vec3 litSideOf(vec3 stored, vec3 premultiplied)
{
    float l = lightOf(premultiplied);
    return l > 0.0 ? stored / l : vec3(0.0);
}

/// The share of a texel's light that leaves towards unit direction v when
/// its lit side is m (light_inject.comp): the cosine between them, as a
/// lit surface's projected area falls off (a voxel's box does not), none
/// behind it; a texel lit from both sides (m short) sends light both ways.
/// A voxel where the wall between two rooms meets their floor is lit from
/// one room; only the cosine keeps its light out of the other.
float towardsLitSide(vec3 m, vec3 v) { return clamp(1.0 - length(m) + dot(m, v), 0.0, 1.0); }
