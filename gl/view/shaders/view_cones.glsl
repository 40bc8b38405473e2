// Cone-traced ambient occlusion through the octree (Crassin et al. 2011),
// included by view_voxels.frag, which declares the node and brick buffers.
//
// The octree is the mip-map: per node two opacities, uploaded (its voxels
// over the voxels of one face of its box, at most 1; and that or its most
// opaque child's, the Max filter); inside a brick the 4³ and 2³ blocks and
// single voxels give three finer levels, counted from the brick's bits here.
// A cone samples, at each step, the cell half as wide as the cone there (a
// finer one near the surface, see coneOcclusion), and composites front to
// back; AO is one minus the cones' occlusion weighted by their shares of
// the cosine-weighted hemisphere.

layout(std430, binding = SVO_BIND_VIEW_OPACITY) readonly restrict buffer Opacity { float opacity[]; };

uniform int uAoCones;          // 0: no AO; else 1 (the normal) or 1 + a ring of uAoCones - 1
uniform float uAoTanHalf;      // tan of half the cone aperture
uniform float uAoOffset;       // start along the normal, voxels
uniform float uAoDistance;     // cones stop here, voxels
uniform float uAoStep;         // steps: this share of the cone's width
uniform uint uAoFilter;        // 0: face-share opacity; 1: at least the most opaque child's

/// The opacity of the cell of `level` holding cell-space point p: levels
/// 0 .. uBrickLevel are nodes, then 4³ blocks, 2³ blocks and voxels.
float opacityAt(vec3 p, uint level)
{
    if (any(lessThan(p, vec3(0.0))) || any(greaterThanEqual(p, vec3(uDims)))) return 0.0;
    uvec3 cell = uvec3(p);
    uint node = 0u;
    uint nodeLevel = min(level, uBrickLevel);
    for (uint l = 0u; l < nodeLevel; ++l) {
        uint shift = 2u + uBrickLevel - l;
        uvec3 c = (cell >> shift) & 1u;
        uint child = c.x | (c.y << 1u) | (c.z << 2u);
        if ((nodes[kNodeWords * node + 1u] & (1u << child)) == 0u) return 0.0;
        node = nodes[kNodeWords * node] + child;
    }
    if (level <= uBrickLevel) return opacity[2u * node + uAoFilter];
    if (nodes[kNodeWords * node + 1u] == 0u) return 0.0;
    uint base = kBrickWords * nodes[kNodeWords * node];
    uvec3 v = cell & kBrickMask;
    if (level == uBrickLevel + 1u) { // a 4³ block: four words, half of each
        uvec3 b = v & ~3u;
        uint n = 0u;
        for (uint x = b.x; x < b.x + 4u; ++x)
            n += uint(bitCount(bricks[base + 2u * x + (b.y >> 2u)] & (0x0F0F0F0Fu << b.z)));
        return min(1.0, float(n) / 16.0);
    }
    if (level == uBrickLevel + 2u) { // a 2³ block: two words
        uvec3 b = v & ~1u;
        uint mask = 0x303u << (((b.y & 3u) << 3u) | b.z);
        uint word = 2u * b.x + (b.y >> 2u);
        return min(1.0, float(bitCount(bricks[base + word] & mask) + bitCount(bricks[base + word + 2u] & mask)) / 4.0);
    }
    uint bit = (v.x << kKeyLeafXShift) | (v.y << kKeyLeafYShift) | (v.z << kKeyLeafZShift);
    return float((bricks[base + (bit >> 5u)] >> (bit & 31u)) & 1u);
}

/// Occlusion along one cone from `o` (cell space) in unit direction `dir`,
/// for the surface point `p` with axis normal `n`. Octree cells are aligned,
/// not centred on the sample, so the cell as wide as the cone can reach back
/// through the surface the cone leaves and hold that surface itself. Such a
/// sample takes instead the coarsest finer cell around it that stays in
/// front of the tangent plane at p (what lies behind that plane cannot
/// occlude the hemisphere): near the surface a cone samples cells finer than
/// its width, and walls that meet the surface are still seen.
float coneOcclusion(vec3 o, vec3 dir, vec3 p, vec3 n)
{
    float occlusion = 0.0;
    float t = 0.5 / uAoTanHalf; // where the cone is one voxel wide
    uint finest = uBrickLevel + 3u;
    int axis = abs(n.x) > 0.5 ? 0 : (abs(n.y) > 0.5 ? 1 : 2);
    float side = n[axis];
    while (t < uAoDistance && occlusion < 0.99) {
        float width = max(1.0, 2.0 * t * uAoTanHalf);
        uint up = uint(max(floor(log2(width)) - 1.0, 0.0)); // levels above the voxels: cells half the cone wide
        uint level = finest - min(up, finest);
        vec3 q = o + t * dir;
        float cellWidth;
        bool behind;
        for (;;) {
            cellWidth = exp2(float(finest - level));
            float lo = floor(q[axis] / cellWidth) * cellWidth;
            behind = side > 0.0 ? lo < p[axis] - 1e-3 : lo + cellWidth > p[axis] + 1e-3;
            if (!behind || level == finest) break;
            ++level;
        }
        float a = behind ? 0.0 : opacityAt(q, level);
        // A sample stands for a slab as long as the cone is wide; the step
        // is uAoStep of that (a half by default), and no longer than the
        // cell at that default, so that a finer cell
        // near the surface cannot step over a thin wall. The opacity is
        // corrected for the path the step covers.
        float step = uAoStep * min(width, 2.0 * cellWidth);
        a = 1.0 - pow(1.0 - a, step / cellWidth);
        occlusion += (1.0 - occlusion) * a;
        t += step;
    }
    return occlusion;
}

/// Ambient occlusion at a point on a face with unit normal n (an axis).
float ambientOcclusion(vec3 p, vec3 n)
{
    if (uAoCones <= 0) return 1.0;
    vec3 t1 = abs(n.x) > 0.5 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(n, t1);
    vec3 o = p + uAoOffset * n; // cones start off the surface
    int ring = uAoCones - 1;
    if (ring == 0) return 1.0 - coneOcclusion(o, n, p, n);
    // Each cone weighs its share of the cosine-weighted hemisphere: the
    // normal's cone (up to 30 degrees) a quarter, the ring (30 to 90
    // degrees, cones tilted 60) three quarters, shared equally.
    float sum = 0.25 * coneOcclusion(o, n, p, n);
    for (int i = 0; i < ring; ++i) {
        float phi = 6.2831853 * (float(i) + 0.5) / float(ring);
        vec3 dir = normalize(0.5 * n + 0.8660254 * (cos(phi) * t1 + sin(phi) * t2));
        sum += 0.75 / float(ring) * coneOcclusion(o, dir, p, n);
    }
    return 1.0 - sum;
}
