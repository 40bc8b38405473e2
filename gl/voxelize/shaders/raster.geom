#version 450 core
// Projects each triangle along its projection axis (the dominant one but
// for needles, svo_projection_axis) onto the plane of voxel
// columns and enlarges it so that every column whose square (half side uHalf)
// meets the triangle gets a fragment.
//
// Enlargement is Hasselgren's conservative rasterization as Crassin and Green
// use it: each edge moves outward by uDilate * (|n.x| + |n.y|), the offset that
// makes a line touch a square of half side uDilate, and the new corners are
// the intersections of adjacent moved edges. The float error of that
// intersection grows as the triangle gets thinner; it is bounded and added to
// the offset, and a triangle too thin for that (or degenerate) is drawn as its
// enlarged box along its longest edge instead (emitThinBox). Acute corners overshoot; the fragment shader
// clips to the bounding box passed along.
#include "glsl_types.glsl"
#include "overlap.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;

in vec3 vPosition[];
flat out vec3 gA;
flat out vec3 gB;
flat out vec3 gC;
flat out int gAxis;
flat out vec4 gBox; // (umin, vmin, umax, vmax) of the triangle, local units

uniform vec2 uTileOrigin; // local (u, v) of the tile's first pixel column
uniform vec2 uTileSize;   // pixels
uniform float uHalf;      // voxel half side incl. guard band
uniform float uDilate;    // how far the rasterized shape must reach, pixels
uniform uint uCentroidPush; // 1: the seed report's dilation, as a baseline only (it misses voxels)
const float kUlp = 5.96046448e-08;

void emitAt(vec2 p)
{
    gA = vPosition[0];
    gB = vPosition[1];
    gC = vPosition[2];
    gl_PrimitiveID = gl_PrimitiveIDIn; // the triangle index, for the triangle-id list
    // Column i has its centre at window coordinate i - origin + 0.5.
    vec2 win = p - uTileOrigin + 0.5;
    gl_Position = vec4(2.0 * win / uTileSize - 1.0, 0.0, 1.0);
    EmitVertex();
}

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// A triangle too thin for moved edges (a needle, or degenerate): the box of
// its corners in the frame of its longest edge, grown by the dilation (a
// square's reach along a unit direction e is uDilate * (|e.x| + |e.y|)) and a
// margin for the frame's rounding. It holds the enlarged triangle as the
// bounding box does, but a needle across the columns gets fragments along
// itself only, not over its whole bounding box (whose area grows as its
// length squared).
void emitThinBox(vec2 p0, vec2 q[3], float E)
{
    vec2 e = q[1];
    if (dot(q[2], q[2]) > dot(e, e)) e = q[2];
    if (dot(q[2] - q[1], q[2] - q[1]) > dot(e, e)) e = q[2] - q[1];
    float len = length(e);
    e = len > 0.0 ? e / len : vec2(1.0, 0.0);
    vec2 n = vec2(-e.y, e.x);
    vec2 s = vec2(0.0); // extents along e and n, from p0
    vec2 t = vec2(0.0);
    for (int i = 1; i < 3; ++i) {
        float se = dot(q[i], e), sn = dot(q[i], n);
        s = vec2(min(s.x, se), max(s.y, se));
        t = vec2(min(t.x, sn), max(t.y, sn));
    }
    float m = 1.0 / 64.0 + 32.0 * kUlp * (E + max(abs(p0.x), abs(p0.y)));
    float ge = uDilate * (abs(e.x) + abs(e.y)) + m;
    float gn = uDilate * (abs(n.x) + abs(n.y)) + m;
    s += vec2(-ge, ge);
    t += vec2(-gn, gn);
    emitAt(p0 + s.x * e + t.x * n);
    emitAt(p0 + s.y * e + t.x * n);
    emitAt(p0 + s.x * e + t.y * n);
    emitAt(p0 + s.y * e + t.y * n);
    EndPrimitive();
}

void main()
{
    vec3 a = vPosition[0];
    vec3 b = vPosition[1];
    vec3 c = vPosition[2];
    int w = svo_projection_axis(a, b, c, kUlp);
    int u = (w + 1) % 3;
    int v = (w + 2) % 3;
    gAxis = w;
    vec2 p0 = vec2(a[u], a[v]);
    vec2 p1 = vec2(b[u], b[v]);
    vec2 p2 = vec2(c[u], c[v]);
    vec2 lo = min(p0, min(p1, p2));
    vec2 hi = max(p0, max(p1, p2));
    gBox = vec4(lo, hi);

    if (uCentroidPush != 0u) {
        // Each corner moves half a pixel diagonal away from the centroid. Edges
        // move out by less than that wherever a corner is acute, so columns
        // the triangle touches can get no fragment.
        vec2 g = (p0 + p1 + p2) / 3.0;
        float push = 0.70710678 + 0.5 * (uDilate - 0.5 - 1.0 / 128.0);
        emitAt(p0 + push * normalize(p0 - g));
        emitAt(p1 + push * normalize(p1 - g));
        emitAt(p2 + push * normalize(p2 - g));
        EndPrimitive();
        return;
    }
    // Work relative to p0 so that errors scale with the triangle, not the grid.
    vec2 q[3] = vec2[3](vec2(0.0), p1 - p0, p2 - p0);
    float area2 = cross2(q[1], q[2]);
    if (area2 < 0.0) {
        vec2 t = q[1];
        q[1] = q[2];
        q[2] = t;
        area2 = -area2;
    }
    vec2 ext = hi - lo;
    float E = max(max(ext.x, ext.y), 1.0);
    // Corner error of the moved-edge intersection: ~ ulp * E / sin(angle),
    // with sin(angle) >= area2 / E^2.
    float margin = 1.0 / 64.0 + 64.0 * kUlp * E * E * E / max(area2, 1e-30);

    if (margin > 0.25) {
        emitThinBox(p0, q, E);
        return;
    }
    float d = uDilate + margin;
    vec3 line[3];
    for (int i = 0; i < 3; ++i) {
        vec2 e = q[(i + 1) % 3] - q[i];
        vec2 n = vec2(e.y, -e.x); // outward for a counter-clockwise triangle
        line[i] = vec3(n, -(dot(n, q[i]) + d * (abs(n.x) + abs(n.y))));
    }
    for (int i = 0; i < 3; ++i) {
        vec3 h = cross(line[(i + 2) % 3], line[i]);
        emitAt(p0 + h.xy / h.z);
    }
    EndPrimitive();
}
