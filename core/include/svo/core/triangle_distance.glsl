// The distance from a voxel centre to a triangle in double precision, and
// the tests that skip centres beyond the band: the single text of the band
// distance passes (gl/fields/shaders/band_distance*.comp) and of the CPU
// backend (core/src/band_distances.cpp), so that both compute every distance
// with the same operations in the same order, the same bits. The shaders
// include it after field_double.glsl; C++ through svo/core/triangle_distance.h.
// Each includer spells first: SVO_FN (C++: inline), svo_dvec3 (dvec3,
// svo::Vec3d), SVO_INOUT(T) (inout T, T&) and SVO_DOUBLE(x), a double
// literal (x##LF, x). C++ compiles it without contraction (-ffp-contract=off)
// as GLSL rounds each operation.

// Squared distance from p to the segment [a, b]; a point when a == b.
SVO_FN double svo_segment_distance2(svo_dvec3 p, svo_dvec3 a, svo_dvec3 b)
{
    svo_dvec3 ab = b - a;
    double len2 = dot(ab, ab);
    double t = len2 > SVO_DOUBLE(0.0) ? min(max(dot(p - a, ab) / len2, SVO_DOUBLE(0.0)), SVO_DOUBLE(1.0))
                                      : SVO_DOUBLE(0.0);
    svo_dvec3 d = p - (a + t * ab);
    return dot(d, d);
}

// Squared distance from p to the closed triangle abc: the distance to its
// plane where p projects inside it, else the least of the edges'. Needles and
// points are their edges, so nothing degenerate divides by zero.
SVO_FN double svo_triangle_distance2(svo_dvec3 p, svo_dvec3 a, svo_dvec3 b, svo_dvec3 c)
{
    svo_dvec3 n = cross(b - a, c - a);
    double n2 = dot(n, n);
    if (n2 > SVO_DOUBLE(0.0) && dot(cross(b - a, p - a), n) >= SVO_DOUBLE(0.0) &&
        dot(cross(c - b, p - b), n) >= SVO_DOUBLE(0.0) && dot(cross(a - c, p - c), n) >= SVO_DOUBLE(0.0)) {
        double h = dot(p - a, n);
        return h * h / n2;
    }
    return min(svo_segment_distance2(p, a, b), min(svo_segment_distance2(p, b, c), svo_segment_distance2(p, c, a)));
}

// The same, for a thread that queries one triangle at many centres (CPU
// rasterizers and the CPU backend): what does not depend on p computed once,
// the rest by the same operations in the same order, so both forms give the
// same bits. (On an H100, holding these values across the loop made the
// GPUs' pass 1.5-2 times slower: bench/results/nvidia-h100/level_set_peers.md.)
struct svo_Triangle {
    svo_dvec3 a, b, c, ab, bc, ca, n;
    double n2, lab, lbc, lca;
};

SVO_FN svo_Triangle svo_triangle_of(svo_dvec3 a, svo_dvec3 b, svo_dvec3 c)
{
    svo_Triangle t;
    t.a = a, t.b = b, t.c = c;
    t.ab = b - a, t.bc = c - b, t.ca = a - c;
    t.n = cross(t.ab, c - a);
    t.n2 = dot(t.n, t.n);
    t.lab = dot(t.ab, t.ab), t.lbc = dot(t.bc, t.bc), t.lca = dot(t.ca, t.ca);
    return t;
}

SVO_FN double svo_edge_distance2(svo_dvec3 p, svo_dvec3 a, svo_dvec3 ab, double len2)
{
    double t = len2 > SVO_DOUBLE(0.0) ? min(max(dot(p - a, ab) / len2, SVO_DOUBLE(0.0)), SVO_DOUBLE(1.0))
                                      : SVO_DOUBLE(0.0);
    svo_dvec3 d = p - (a + t * ab);
    return dot(d, d);
}

SVO_FN double svo_prepared_distance2(svo_dvec3 p, svo_Triangle t)
{
    if (t.n2 > SVO_DOUBLE(0.0) && dot(cross(t.ab, p - t.a), t.n) >= SVO_DOUBLE(0.0) &&
        dot(cross(t.bc, p - t.b), t.n) >= SVO_DOUBLE(0.0) && dot(cross(t.ca, p - t.c), t.n) >= SVO_DOUBLE(0.0)) {
        double h = dot(p - t.a, t.n);
        return h * h / t.n2;
    }
    return min(svo_edge_distance2(p, t.a, t.ab, t.lab),
               min(svo_edge_distance2(p, t.b, t.bc, t.lbc), svo_edge_distance2(p, t.c, t.ca, t.lca)));
}

// The plane slab of triangle abc for a band of `band` voxels: a centre
// farther than the band from the triangle's plane is farther from the
// triangle, so work can skip it. Its unnormalized normal n and the band
// measured along n, widened by 1e-6 (above float's half ulp, so no centre
// whose rounded distance could be kept is skipped) and by
// 1e-10 |b - a| |c - a| (|b - a| + |c - a| + band), far above the rounding
// of n (each component off by up to about 2^-52 |b - a| |c - a|) times any
// distance from a within the grown box: a needle whose corners lie on a line
// has a normal of pure rounding noise, and its slab then holds the whole box.
struct svo_Slab {
    svo_dvec3 a, n;
    double limit;
};

SVO_FN svo_Slab svo_slab_of(svo_dvec3 a, svo_dvec3 b, svo_dvec3 c, double band)
{
    svo_Slab s;
    s.a = a;
    s.n = cross(b - a, c - a);
    double e1 = sqrt(dot(b - a, b - a)), e2 = sqrt(dot(c - a, c - a));
    s.limit = band * sqrt(dot(s.n, s.n)) * (SVO_DOUBLE(1.0) + SVO_DOUBLE(1e-6)) +
              SVO_DOUBLE(1e-10) * e1 * e2 * (e1 + e2 + band);
    return s;
}

// Whether every point of the box [lo, hi] lies beyond the slab on one side.
SVO_FN bool svo_box_beyond_slab(svo_Slab s, svo_dvec3 lo, svo_dvec3 hi)
{
    double h = dot(s.n, SVO_DOUBLE(0.5) * (lo + hi) - s.a), r = dot(abs(s.n), SVO_DOUBLE(0.5) * (hi - lo));
    return h - r > s.limit || h + r < -s.limit;
}

// Narrows the centres [zLo, zHi] (whole numbers) of column (x, y) to those
// inside the slab; false when none is.
SVO_FN bool svo_slab_run(svo_Slab s, double x, double y, SVO_INOUT(double) zLo, SVO_INOUT(double) zHi)
{
    double h0 = s.n.x * (x - s.a.x) + s.n.y * (y - s.a.y) - s.n.z * s.a.z;
    if (s.n.z == SVO_DOUBLE(0.0)) return abs(h0) <= s.limit;
    double z0 = (-s.limit - h0) / s.n.z, z1 = (s.limit - h0) / s.n.z;
    zLo = max(zLo, ceil(min(z0, z1) - SVO_DOUBLE(1e-6)));
    zHi = min(zHi, floor(max(z0, z1) + SVO_DOUBLE(1e-6)));
    return zLo <= zHi;
}

// Narrows the centres [zLo, zHi] of column (x, y) to those whose distance to
// the box [boxLo, boxHi] (the triangle's) is within the band, band2 its
// square, found from the gap across the column and widened for rounding;
// false when none is.
SVO_FN bool svo_box_run(svo_dvec3 boxLo, svo_dvec3 boxHi, double x, double y, double band2, SVO_INOUT(double) zLo,
                        SVO_INOUT(double) zHi)
{
    double gx = max(max(boxLo.x - x, x - boxHi.x), SVO_DOUBLE(0.0));
    double gy = max(max(boxLo.y - y, y - boxHi.y), SVO_DOUBLE(0.0));
    double rest = band2 - (gx * gx + gy * gy);
    if (rest < SVO_DOUBLE(0.0)) return false;
    double r = sqrt(rest) * (SVO_DOUBLE(1.0) + SVO_DOUBLE(1e-9)) + SVO_DOUBLE(1e-9);
    zLo = max(zLo, ceil(boxLo.z - r));
    zHi = min(zHi, floor(boxHi.z + r));
    return zLo <= zHi;
}
