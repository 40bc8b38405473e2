// Triangle / axis-aligned cube overlap by the separating-axis theorem
// (Akenine-Moller, "Fast 3D triangle-box overlap testing", 2001): the three
// cube normals, the triangle normal and the nine edge x cube-axis products.
//
// This text is the single source of truth for "does a triangle touch a voxel",
// in both modes: the cube (conservative) and the three centre segments (thin).
// The GLSL shaders include it, and so does C++ (svo/core/overlap.h), which
// defines SVO_FN, svo_real and svo_vec3 first.
//
// Guarantees, for any triangle, degenerate ones included:
// - Any axis that separates proves disjointness, even one computed with
//   rounding; so an inaccurate axis can only make the test more inclusive.
// - A zero axis (the normal of a needle, the edges of a point) never separates;
//   the remaining axes are exactly the separating axes of the segment or point.
// - halfSide is the cube's halfSide side: 0.5 for the exact voxel, 0.5 + g for a cube
//   grown by a guard band g, 0.5 - g for a shrunk one. Rounding errors move a
//   projection by at most a few ulps of the coordinates' magnitude, which a
//   guard band of that size covers (see docs/precision.md).

SVO_FN bool svo_separated(svo_real p0, svo_real p1, svo_real p2, svo_real r)
{
    return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

// The three axes cross(e, X), cross(e, Y), cross(e, Z), written out.
SVO_FN bool svo_edge_axes_separate(svo_vec3 e, svo_vec3 v0, svo_vec3 v1, svo_vec3 v2, svo_real halfSide)
{
    if (svo_separated(e.z * v0.y - e.y * v0.z, e.z * v1.y - e.y * v1.z,
                      e.z * v2.y - e.y * v2.z, halfSide * (abs(e.y) + abs(e.z))))
        return true;
    if (svo_separated(e.x * v0.z - e.z * v0.x, e.x * v1.z - e.z * v1.x,
                      e.x * v2.z - e.z * v2.x, halfSide * (abs(e.x) + abs(e.z))))
        return true;
    if (svo_separated(e.y * v0.x - e.x * v0.y, e.y * v1.x - e.x * v1.y,
                      e.y * v2.x - e.x * v2.y, halfSide * (abs(e.x) + abs(e.y))))
        return true;
    return false;
}

// True when triangle (a, b, c) meets the closed cube of halfSide side `halfSide`
// centred at `centre`.
SVO_FN bool svo_triangle_box_overlap(svo_vec3 a, svo_vec3 b, svo_vec3 c, svo_vec3 centre, svo_real halfSide)
{
    svo_vec3 v0 = a - centre;
    svo_vec3 v1 = b - centre;
    svo_vec3 v2 = c - centre;
    if (svo_separated(v0.x, v1.x, v2.x, halfSide)) return false;
    if (svo_separated(v0.y, v1.y, v2.y, halfSide)) return false;
    if (svo_separated(v0.z, v1.z, v2.z, halfSide)) return false;

    svo_vec3 e0 = v1 - v0;
    svo_vec3 e1 = v2 - v1;
    svo_vec3 e2 = v0 - v2;
    if (svo_edge_axes_separate(e0, v0, v1, v2, halfSide)) return false;
    if (svo_edge_axes_separate(e1, v0, v1, v2, halfSide)) return false;
    if (svo_edge_axes_separate(e2, v0, v1, v2, halfSide)) return false;

    svo_vec3 n = cross(e0, e1);
    if (svo_separated(dot(n, v0), dot(n, v1), dot(n, v2),
                      halfSide * (abs(n.x) + abs(n.y) + abs(n.z))))
        return false;
    return true;
}

// Dominant axis of a normal; ties go to the higher axis (z over y over x), a
// fixed rule so that every backend projects a tied triangle the same way.
SVO_FN int svo_dominant_axis(svo_vec3 n)
{
    svo_real ax = abs(n.x);
    svo_real ay = abs(n.y);
    svo_real az = abs(n.z);
    if (az >= ax && az >= ay) return 2;
    if (ay >= ax) return 1;
    return 0;
}

// The same test for a box with its own half extent on each axis (each >= 0;
// zero extents make the box a rectangle, a segment or a point), given the
// triangle's corners relative to the box centre, its edges and its normal.
// Still complete when extents are zero: two disjoint compact sets stay
// disjoint when the box is thickened a little, and one of these 13 axes
// separates the thickened box, so it separates the thinner one too. It is
// kept apart from svo_triangle_box_overlap so that the conservative test,
// measured and validated as it is, rounds exactly as before.
SVO_FN bool svo_aabb_separated(svo_vec3 v0, svo_vec3 v1, svo_vec3 v2, svo_vec3 e0, svo_vec3 e1, svo_vec3 e2,
                               svo_vec3 n, svo_vec3 h)
{
    if (svo_separated(v0.x, v1.x, v2.x, h.x)) return true;
    if (svo_separated(v0.y, v1.y, v2.y, h.y)) return true;
    if (svo_separated(v0.z, v1.z, v2.z, h.z)) return true;
    // cross(e, X) = (0, e.z, -e.y), cross(e, Y) = (-e.z, 0, e.x), cross(e, Z) = (e.y, -e.x, 0).
    for (int i = 0; i < 3; ++i) {
        svo_vec3 e = i == 0 ? e0 : (i == 1 ? e1 : e2);
        if (svo_separated(e.z * v0.y - e.y * v0.z, e.z * v1.y - e.y * v1.z, e.z * v2.y - e.y * v2.z,
                          h.y * abs(e.z) + h.z * abs(e.y)))
            return true;
        if (svo_separated(e.x * v0.z - e.z * v0.x, e.x * v1.z - e.z * v1.x, e.x * v2.z - e.z * v2.x,
                          h.x * abs(e.z) + h.z * abs(e.x)))
            return true;
        if (svo_separated(e.y * v0.x - e.x * v0.y, e.y * v1.x - e.x * v1.y, e.y * v2.x - e.x * v2.y,
                          h.x * abs(e.y) + h.y * abs(e.x)))
            return true;
    }
    return svo_separated(dot(n, v0), dot(n, v1), dot(n, v2), h.x * abs(n.x) + h.y * abs(n.y) + h.z * abs(n.z));
}

// True when triangle (a, b, c) meets the closed box centred at `centre` with
// half extents `halfSize`.
SVO_FN bool svo_triangle_aabb_overlap(svo_vec3 a, svo_vec3 b, svo_vec3 c, svo_vec3 centre, svo_vec3 halfSize)
{
    svo_vec3 v0 = a - centre;
    svo_vec3 v1 = b - centre;
    svo_vec3 v2 = c - centre;
    svo_vec3 e0 = v1 - v0;
    svo_vec3 e1 = v2 - v1;
    svo_vec3 e2 = v0 - v2;
    return !svo_aabb_separated(v0, v1, v2, e0, e1, e2, cross(e0, e1), halfSize);
}

// The thin (6-separating) test: true when triangle (a, b, c) meets one of the
// voxel's three axis-aligned centre segments, centre +- halfLength along x,
// y or z, each thickened to a box of half width `thickness` across its axis.
// halfLength = 0.5, thickness = 0 is the exact definition (closed segments
// one voxel long); a guard band g grows both (0.5 + g, g), which bounds the
// same rounding as for the cube: every axis's radius grows by g times the
// axis's L1 norm, whatever the extents. Shrinking (g < 0) shortens the
// segments and leaves thickness 0.
SVO_FN bool svo_triangle_thin_overlap(svo_vec3 a, svo_vec3 b, svo_vec3 c, svo_vec3 centre, svo_real halfLength,
                                      svo_real thickness)
{
    svo_vec3 v0 = a - centre;
    svo_vec3 v1 = b - centre;
    svo_vec3 v2 = c - centre;
    svo_vec3 e0 = v1 - v0;
    svo_vec3 e1 = v2 - v1;
    svo_vec3 e2 = v0 - v2;
    svo_vec3 n = cross(e0, e1);
    // The segment along the normal's dominant axis first: it is the one that
    // meets the triangle in most voxels kept, so most of them cost one test.
    int w = svo_dominant_axis(n);
    for (int i = 0; i < 3; ++i) {
        svo_vec3 h = svo_vec3(thickness, thickness, thickness);
        h[(w + i) % 3] = halfLength;
        if (!svo_aabb_separated(v0, v1, v2, e0, e1, e2, n, h)) return true;
    }
    return false;
}

// The edge of triangle (a, b, c) with the largest coordinate difference:
// 0 for b - a, 1 for c - a, 2 for c - b.
SVO_FN int svo_longest_edge(svo_vec3 a, svo_vec3 b, svo_vec3 c)
{
    svo_vec3 e0 = abs(b - a);
    svo_vec3 e1 = abs(c - a);
    svo_vec3 e2 = abs(c - b);
    svo_real m0 = max(e0.x, max(e0.y, e0.z));
    svo_real m1 = max(e1.x, max(e1.y, e1.z));
    svo_real m2 = max(e2.x, max(e2.y, e2.z));
    if (m0 >= m1 && m0 >= m2) return 0;
    return m1 >= m2 ? 1 : 2;
}

// The axis along which the voxel columns of triangle (a, b, c) run: the
// dominant axis of its normal, unless the computed normal is mostly rounding
// (a needle or a point: dn below is its error bound, as in svo_column_range);
// then the axis along which the longest edge is shortest, so that the
// triangle crosses each column in a few voxels and its work follows what it
// covers. Any axis gives the same voxels: the overlap test decides, and
// svo_column_range is conservative for every axis.
SVO_FN int svo_projection_axis(svo_vec3 a, svo_vec3 b, svo_vec3 c, svo_real ulp)
{
    int longest = svo_longest_edge(a, b, c);
    svo_vec3 d = longest == 0 ? b - a : (longest == 1 ? c - a : c - b);
    svo_vec3 ad = abs(d);
    svo_real E = max(ad.x, max(ad.y, ad.z));
    svo_vec3 n = cross(b - a, c - a);
    int w = svo_dominant_axis(n);
    if (abs(n[w]) > 4.0 * (8.0 * ulp * E * E)) return w;
    if (ad.x <= ad.y && ad.x <= ad.z) return 0;
    return ad.y <= ad.z ? 1 : 2;
}

// Heights along axis w at which triangle (a, b, c) can meet a cube of halfSide side
// `halfSide` in the column centred at (cu, cv) on axes u = (w+1)%3, v = (w+2)%3.
// Returns (lo, hi, 0): the voxels to test are ceil(lo) .. floor(hi).
//
// The triangle's plane narrows the range to at most about three voxels when w
// is dominant. With unit roundoff `ulp`, the computed normal is off by at most
// dn = 8 ulp E^2 (E: longest edge); the resulting slope error widens the range,
// and a triangle too degenerate for a reliable plane gets its full extent. The
// range is therefore conservative in float as in double.
//
// What does not depend on the column is planned once (svo_column_plan), so
// that a caller walking many columns of one triangle (the CPU voxelizer)
// computes it once; svo_plan_range does the rest, by the same operations.
struct svo_ColumnPlan {
    int w, u, v;
    svo_real lo, hi;       // the triangle's extent along w, grown by halfSide
    bool sloped;           // the plane narrows the range
    svo_real su, sv;       // its slopes along u and v
    svo_vec3 a;            // the corner the plane is measured from
    svo_real E;            // the longest edge's largest coordinate difference
    svo_real slopeError;   // the plane's height error, before the column's magnitude
    svo_real spread;       // halfSide (|su| + |sv|)
    bool lineBound;        // the sliver bound applies (a longest edge of some length)
    svo_vec3 p, d;         // that edge's line
    svo_real cornerMag;    // the corners' largest coordinate
    svo_real delta;        // the triangle's distance from the line, bounded
    svo_real halfSide, ulp;
};

SVO_FN svo_ColumnPlan svo_column_plan(svo_vec3 a, svo_vec3 b, svo_vec3 c, int w, svo_real halfSide, svo_real ulp)
{
    svo_ColumnPlan q;
    q.w = w;
    q.u = (w + 1) % 3;
    q.v = (w + 2) % 3;
    q.a = a;
    q.halfSide = halfSide;
    q.ulp = ulp;
    q.lo = min(a[w], min(b[w], c[w])) - halfSide;
    q.hi = max(a[w], max(b[w], c[w])) + halfSide;
    svo_vec3 e0 = b - a;
    svo_vec3 e1 = c - a;
    svo_vec3 e2 = c - b;
    q.E = max(max(max(abs(e0.x), abs(e0.y)), max(abs(e0.z), abs(e1.x))),
              max(max(abs(e1.y), abs(e1.z)), max(abs(e2.x), max(abs(e2.y), abs(e2.z)))));
    svo_vec3 n = cross(e0, e1);
    svo_real dn = 8.0 * ulp * q.E * q.E;
    svo_real nw = abs(n[w]);
    q.sloped = nw > 2.0 * dn;
    q.su = 0.0;
    q.sv = 0.0;
    q.slopeError = 0.0;
    q.spread = 0.0;
    if (q.sloped) {
        q.su = -n[q.u] / n[w];
        q.sv = -n[q.v] / n[w];
        q.slopeError = 4.0 * dn / (nw - dn) * (q.E + 1.0);
        q.spread = halfSide * (abs(q.su) + abs(q.sv));
    }
    // The sliver bound, tight where the plane's is not: the triangle lies
    // within delta of the line through its longest edge (p, d) (the distance
    // to a line is convex, so it peaks at the third corner, |n| / |d| away),
    // so its points in this column are near the line's points in the column
    // grown by delta, whose heights follow from the line's parameter range.
    int longest = svo_longest_edge(a, b, c);
    q.p = longest == 2 ? b : a;
    q.d = longest == 0 ? e0 : (longest == 1 ? e1 : e2);
    svo_real dmax = max(abs(q.d.x), max(abs(q.d.y), abs(q.d.z)));
    q.lineBound = dmax > 0.0;
    q.cornerMag = max(max(max(abs(a.x), abs(a.y)), max(abs(a.z), abs(b.x))),
                      max(max(abs(b.y), abs(b.z)), max(abs(c.x), max(abs(c.y), abs(c.z)))));
    q.delta = q.lineBound ? (abs(n.x) + abs(n.y) + abs(n.z) + 3.0 * dn) / dmax * (1.0 + 8.0 * ulp) : 0.0;
    return q;
}

SVO_FN svo_vec3 svo_plan_range(svo_ColumnPlan q, svo_real cu, svo_real cv)
{
    int w = q.w;
    int u = q.u;
    int v = q.v;
    svo_real halfSide = q.halfSide;
    svo_real ulp = q.ulp;
    svo_real lo = q.lo;
    svo_real hi = q.hi;
    if (q.sloped) {
        svo_real h = q.a[w] + q.su * (cu - q.a[u]) + q.sv * (cv - q.a[v]);
        svo_real mag = max(abs(q.a[w]), max(abs(cu), abs(cv))) + q.E;
        svo_real err = q.slopeError + 8.0 * ulp * mag;
        svo_real dz = q.spread + err;
        lo = max(lo, h - dz - halfSide);
        hi = min(hi, h + dz + halfSide);
    }
    // The margin g holds the rounding of the line's parameter range.
    if (q.lineBound) {
        svo_vec3 p = q.p;
        svo_vec3 d = q.d;
        svo_real mag = max(q.cornerMag, max(abs(cu), abs(cv))) + 1.0;
        svo_real delta = q.delta;
        svo_real g = halfSide + delta + 16.0 * ulp * mag;
        svo_real t0 = -3.0e38;
        svo_real t1 = 3.0e38;
        if (d[u] != 0.0) {
            svo_real s0 = (cu - g - p[u]) / d[u];
            svo_real s1 = (cu + g - p[u]) / d[u];
            t0 = max(t0, min(s0, s1));
            t1 = min(t1, max(s0, s1));
        }
        if (d[v] != 0.0) {
            svo_real s0 = (cv - g - p[v]) / d[v];
            svo_real s1 = (cv + g - p[v]) / d[v];
            t0 = max(t0, min(s0, s1));
            t1 = min(t1, max(s0, s1));
        }
        if (t0 > t1) return svo_vec3(1.0, 0.0, 0.0); // the column misses the grown line: no voxel
        if (t1 - t0 < 1.0e38) {
            svo_real y0 = p[w] + t0 * d[w];
            svo_real y1 = p[w] + t1 * d[w];
            svo_real slack = delta + halfSide + 16.0 * ulp * (abs(y0) + abs(y1) + mag);
            lo = max(lo, min(y0, y1) - slack);
            hi = min(hi, max(y0, y1) + slack);
        }
    }
    return svo_vec3(lo, hi, 0.0);
}

SVO_FN svo_vec3 svo_column_range(svo_vec3 a, svo_vec3 b, svo_vec3 c, int w, svo_real cu, svo_real cv,
                                 svo_real halfSide, svo_real ulp)
{
    return svo_plan_range(svo_column_plan(a, b, c, w, halfSide, ulp), cu, cv);
}
