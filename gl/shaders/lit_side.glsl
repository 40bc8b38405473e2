// Six-way radiance's rule for level 0 (design §7d), included by the mip-map
// that builds level 1 from it (light_mip_along.comp) and by the cones that
// read level 0 (view_gather.glsl).

/// The share of a texel's light that leaves towards unit direction v when
/// its lit side is m (light_inject.comp): all of it in front of the lit
/// side and along it, none behind it; a texel lit from both sides (m short)
/// sends light both ways.
float towardsLitSide(vec3 m, vec3 v) { return clamp(1.0 + 2.0 * dot(m, v), 0.0, 1.0); }
