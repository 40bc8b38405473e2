#!/usr/bin/env python3
"""Variants of gl/fields/shaders/band_distance.comp for bench/gpu_host_shader_ab.sh.

Each variant is written as OUT/<name>/band_distance.comp, made from the
built-in shader's text, so a folder can be given to SVO_SHADER_DIR on a GPU
host without a rebuild. Every variant must give the same bytes as the
built-in pass (the A/B script compares the files; LevelSet.BothCuts... checks
them against the CPU's field when run with SVO_SHADER_DIR set):

  sqrtskip          no double sqrt for a centre beyond the band with a margin
  centres           a thread a centre of the item's box (64 a group), not a column
  centres_sqrtskip  both
  centres32         the same, 32 threads a group
  shared_setup      the item's triangle, box and slab set up by one thread, shared
  edgecull          a centre farther than the band outside one edge's line
                    (well-shaped triangles only, a margin of 1e-6) is skipped;
                    with sqrtskip
  centres_edgecull  both, a thread a centre

  python3 bench/band_distance_variants.py OUT
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
BUILTIN = os.path.join(HERE, "..", "gl", "fields", "shaders", "band_distance.comp")

PLAIN = "            float d = float(sqrt(svo_triangle_distance2(p, A, B, C)));"
SKIP = """            double d2 = svo_triangle_distance2(p, A, B, C);
            if (d2 > keep2) continue; // beyond the band with a wide margin: no sqrt
            float d = float(sqrt(d2));"""
KEEP = "        double keep2 = band2 * (1.0LF + 1e-5LF);\n"
BAND2 = "        double band2 = double(uBand) * double(uBand);\n"
CULL_SETUP = """        dvec3 n = cross(B - A, C - A);
        dvec3 wab = cross(B - A, n), wbc = cross(C - B, n), wca = cross(A - C, n);
        double eab = dot(B - A, B - A), eca = dot(C - A, C - A);
        bool cull = dot(n, n) > 1e-12LF * eab * eca;
        double margin = double(uBand) * (1.0LF + 1e-6LF) + 1e-6LF;
        double lab = margin * sqrt(dot(wab, wab)), lbc = margin * sqrt(dot(wbc, wbc)), lca = margin * sqrt(dot(wca, wca));
"""
CULL_TEST = ("            if (cull && (dot(p - A, wab) > lab || dot(p - B, wbc) > lbc || dot(p - C, wca) > lca)) "
             "continue;\n")

# The item loop with a thread a centre of the item's box.
CENTRES = """    uint first, end;
    itemRun(first, end);
    uint t = first < end ? triangleOfItem(first) : 0u;
    for (uint item = first; item < end; ++item) {
        t = triangleOfItemFrom(item, t);
        uvec3 lo, size;
        voxelBoxOfTriangleItem(item, t, lo, size); // one brick's part of the box
        uvec3 b = lo >> kBrickLog2;
        uint brick = lookupBrick(b);
        if (brick == kNoChild) continue; // no voxel of this brick is in the band
        dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
        dvec3 boxLo = min(A, min(B, C)), boxHi = max(A, max(B, C));
        dvec3 brickLo = dvec3(b << kBrickLog2), brickHi = brickLo + 7.0LF;
        dvec3 gap = max(max(boxLo - brickHi, brickLo - boxHi), dvec3(0.0LF));
        double band2 = double(uBand) * double(uBand);
@KEEP        if (dot(gap, gap) > band2) continue; // the whole brick is beyond the band from the triangle's box
        dvec3 w = dvec3(uBand);
        svo_Slab slab = svo_slab_of(A, B, C, double(uBand));
        if (svo_box_beyond_slab(slab, max(brickLo, boxLo - w), min(brickHi, boxHi + w))) continue;
@CULL_SETUP        uint count = size.x * size.y * size.z;
        for (uint c = gl_LocalInvocationID.x; c < count; c += gl_WorkGroupSize.x) {
            uvec3 v = lo + uvec3(c % size.x, (c / size.x) % size.y, c / (size.x * size.y));
            dvec3 p = dvec3(v);
            dvec3 g = max(max(boxLo - p, p - boxHi), dvec3(0.0LF));
            if (dot(g, g) > band2) continue;
            if (abs(dot(slab.n, p - slab.a)) > slab.limit) continue; // beyond the band of the plane
@CULL_TEST@DIST
            if (d > uBand) continue;
            uvec3 l = v & 7u;
            uint i = 512u * brick + ((l.x << kKeyLeafXShift) | (l.y << kKeyLeafYShift) | l.z);
            if (uPass == 0u) atomicMin(distances[i], floatBitsToUint(d));
            else if (distances[i] == floatBitsToUint(d)) atomicMin(closest[i], t);
        }
    }
"""

# The item loop with the set-up by one thread, in shared memory.
SHARED_DECLS = """
shared bool sSkip;
shared dvec3 sA, sB, sC, sBoxLo, sBoxHi, sN;
shared double sLimit;
shared uint sBrick, sT;
shared uvec3 sLo, sSize;

void main()
{
"""
SHARED = """    uint first, end;
    itemRun(first, end);
    uint t = first < end ? triangleOfItem(first) : 0u;
    for (uint item = first; item < end; ++item) {
        if (gl_LocalInvocationID.x == 0u) {
            t = triangleOfItemFrom(item, t);
            uvec3 lo, size;
            voxelBoxOfTriangleItem(item, t, lo, size); // one brick's part of the box
            uvec3 b = lo >> kBrickLog2;
            uint brick = lookupBrick(b);
            sSkip = brick == kNoChild;
            if (!sSkip) {
                dvec3 A = position(indices[3u * t]), B = position(indices[3u * t + 1u]), C = position(indices[3u * t + 2u]);
                dvec3 boxLo = min(A, min(B, C)), boxHi = max(A, max(B, C));
                dvec3 brickLo = dvec3(b << kBrickLog2), brickHi = brickLo + 7.0LF;
                dvec3 gap = max(max(boxLo - brickHi, brickLo - boxHi), dvec3(0.0LF));
                double band2 = double(uBand) * double(uBand);
                dvec3 w = dvec3(uBand);
                svo_Slab slab = svo_slab_of(A, B, C, double(uBand));
                sSkip = dot(gap, gap) > band2 || svo_box_beyond_slab(slab, max(brickLo, boxLo - w), min(brickHi, boxHi + w));
                sA = A, sB = B, sC = C, sBoxLo = boxLo, sBoxHi = boxHi, sN = slab.n, sLimit = slab.limit;
                sBrick = brick, sT = t, sLo = lo, sSize = size;
            }
        }
        barrier();
        if (!sSkip) {
            dvec3 A = sA, B = sB, C = sC, boxLo = sBoxLo, boxHi = sBoxHi, n = sN;
            double limit = sLimit;
            uint brick = sBrick, tt = sT;
            uvec3 lo = sLo, size = sSize;
            double band2 = double(uBand) * double(uBand);
            double keep2 = band2 * (1.0LF + 1e-5LF);
            uint count = size.x * size.y * size.z;
            for (uint c = gl_LocalInvocationID.x; c < count; c += gl_WorkGroupSize.x) {
                uvec3 v = lo + uvec3(c % size.x, (c / size.x) % size.y, c / (size.x * size.y));
                dvec3 p = dvec3(v);
                dvec3 g = max(max(boxLo - p, p - boxHi), dvec3(0.0LF));
                if (dot(g, g) > band2) continue;
                if (abs(dot(n, p - A)) > limit) continue; // beyond the band of the plane
                double d2 = svo_triangle_distance2(p, A, B, C);
                if (d2 > keep2) continue; // beyond the band with a wide margin: no sqrt
                float d = float(sqrt(d2));
                if (d > uBand) continue;
                uvec3 l = v & 7u;
                uint i = 512u * brick + ((l.x << kKeyLeafXShift) | (l.y << kKeyLeafYShift) | l.z);
                if (uPass == 0u) atomicMin(distances[i], floatBitsToUint(d));
                else if (distances[i] == floatBitsToUint(d)) atomicMin(closest[i], tt);
            }
        }
        barrier();
    }
"""


def variants(base):
    for needle in (PLAIN, BAND2, "    uint x = gl_LocalInvocationID.x >> 3u", "\nvoid main()\n{\n"):
        if needle not in base:
            sys.exit(f"band_distance_variants: the built-in shader changed; no '{needle.strip()[:40]}' in it")
    start = base.index("    uint x = gl_LocalInvocationID.x >> 3u")
    end = base.rindex("}")

    def loop(body, keep="", cull=False, dist=PLAIN, head=base[:start]):
        body = body.replace("@KEEP", keep).replace("@CULL_SETUP", CULL_SETUP if cull else "")
        body = body.replace("@CULL_TEST", CULL_TEST if cull else "").replace("@DIST", dist)
        return head + body + base[end:]

    skipping = loop(CENTRES, KEEP, False, SKIP)
    return {
        "sqrtskip": base.replace(BAND2, BAND2 + KEEP).replace(PLAIN, SKIP),
        "centres": loop(CENTRES),
        "centres_sqrtskip": skipping,
        "centres32": skipping.replace("layout(local_size_x = 64) in;", "layout(local_size_x = 32) in;"),
        "shared_setup": loop(SHARED, head=base[:start].replace("\nvoid main()\n{\n", SHARED_DECLS)),
        "edgecull": base.replace(BAND2, BAND2 + KEEP + CULL_SETUP).replace(PLAIN, CULL_TEST + SKIP),
        "centres_edgecull": loop(CENTRES, KEEP, True, SKIP),
    }


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with open(BUILTIN) as f:
        base = f.read()
    for name, text in variants(base).items():
        os.makedirs(os.path.join(sys.argv[1], name), exist_ok=True)
        with open(os.path.join(sys.argv[1], name, "band_distance.comp"), "w") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
