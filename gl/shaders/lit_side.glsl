// Six-way radiance's rule for level 0 (design §7d), included by the mip-map
// that builds level 1 from it (light_mip_along.comp) and by the cones that
// read level 0 (view_gather.glsl).

/// The share of a texel's light that leaves towards unit direction v when
/// its lit side is m (light_inject.comp): the cosine between them, as a
/// lit surface's projected area falls off (a voxel's box does not), none
/// behind it; a texel lit from both sides (m short) sends light both ways.
/// A voxel where the wall between two rooms meets their floor is lit from
/// one room; only the cosine keeps its light out of the other.
float towardsLitSide(vec3 m, vec3 v) { return clamp(1.0 - length(m) + dot(m, v), 0.0, 1.0); }
