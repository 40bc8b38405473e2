// Where a triangle crosses a voxel column along z: the single text of the
// parity pass (gl/fields/shaders/parity_flips.comp) and of the CPU backend
// (core/src/parity_crossings.cpp), so that both decide every column and
// place every crossing with the same operations, the same bits. The shader
// includes it after field_double.glsl; C++ through svo/core/column_crossing.h.
// Each includer spells first: SVO_FN (C++: inline), svo_dvec3 (dvec3,
// svo::Vec3d), SVO_INOUT(T) (inout T, T&), SVO_DOUBLE(x), a double literal
// (x##LF, x), and SVO_PRECISE (precise; nothing in C++, which is compiled
// without contraction, -ffp-contract=off).
//
// Ties (simulation of simplicity). Each voxel centre is perturbed to
// (i + e^2, j + e^3, k + e) for an infinitesimal e, so no centre lies on a
// face, edge or vertex: in projection the column point misses every edge and
// vertex (svo_edge_side), and a centre at the crossing's exact height counts
// as above it, since e outweighs the crossing's own shift of order e^2. A
// column over an edge shared by two triangles crosses exactly one of them.
// Each edge function is evaluated with its end points in a fixed order and
// precise, so the two triangles of an edge compute the same value and decide
// alike even where double rounding is inexact.

// Side of the perturbed column point (qx, qy) + (e^2, e^3) of the directed
// edge p0 -> p1 projected on z (+1 left, -1 right; 0 only for an edge of
// zero length in projection).
SVO_FN int svo_edge_side(svo_dvec3 p0, svo_dvec3 p1, double qx, double qy)
{
    bool swapped = p0.x > p1.x || (p0.x == p1.x && p0.y > p1.y);
    svo_dvec3 a = swapped ? p1 : p0, b = swapped ? p0 : p1;
    SVO_PRECISE double e = (b.x - a.x) * (qy - a.y) - (b.y - a.y) * (qx - a.x);
    int s = e > SVO_DOUBLE(0.0) ? 1 : e < SVO_DOUBLE(0.0) ? -1 : 0;
    if (s == 0) s = a.y > b.y ? 1 : a.y < b.y ? -1 : b.x > a.x ? 1 : b.x < a.x ? -1 : 0; // the e^2, then e^3 term
    return swapped ? -s : s;
}

// Whether column (qx, qy) crosses triangle ABC, and where: zc, the height
// of the crossing from barycentric weights of the same edge functions. False
// when the column misses the triangle, or the triangle has zero area in
// projection after rounding (no crossing to place). Precise: a driver that
// fuses multiply-adds (NVIDIA's does) would move a crossing within rounding
// of a centre to the other side of it, and the CPU path, which rounds each
// operation, would no longer give the same signs.
SVO_FN bool svo_column_crossing(svo_dvec3 A, svo_dvec3 B, svo_dvec3 C, double qx, double qy, SVO_INOUT(double) zc)
{
    int sa = svo_edge_side(B, C, qx, qy), sb = svo_edge_side(C, A, qx, qy), sc = svo_edge_side(A, B, qx, qy);
    if (sa == 0 || sa != sb || sb != sc) return false;
    SVO_PRECISE double wa = (C.x - B.x) * (qy - B.y) - (C.y - B.y) * (qx - B.x);
    SVO_PRECISE double wb = (A.x - C.x) * (qy - C.y) - (A.y - C.y) * (qx - C.x);
    SVO_PRECISE double wc = (B.x - A.x) * (qy - A.y) - (B.y - A.y) * (qx - A.x);
    SVO_PRECISE double sum = wa + wb + wc;
    if (sum == SVO_DOUBLE(0.0)) return false;
    SVO_PRECISE double z = (wa * A.z + wb * B.z + wc * C.z) / sum;
    zc = z;
    return true;
}
