#version 450 core
// The compute backend: triangle-parallel voxelization with the raster
// backend's column walk (column_walk.glsl), so both keep the same voxels.
//
// Pass 0, one thread per triangle: project the triangle on its projection
// axis (svo_projection_axis) and take the columns whose squares can meet its
// bounding box. A triangle of at most kSmall columns walks them itself. A
// larger one is cut into chunks of 64 columns (its box in row-major order,
// or for a thin triangle the rows along its longest edge, alongLine): pass 1
// runs one workgroup of 64 threads per chunk, one column per thread,
// so that a large triangle is spread over many workgroups instead of
// serializing one thread. The host lays out pass 1's items (a bound on every
// triangle's chunks, in triangle order), so no shader loops over a
// triangle's chunks, whose count has no bound but the grid's. Pass-1
// workgroups loop over the items of their dispatch.
layout(local_size_x = 64) in;
#include "glsl_types.glsl"
#include "overlap.glsl"
#include "column_walk.glsl"

layout(std430, binding = SVO_BIND_COMPUTE_POSITIONS) readonly restrict buffer Positions { float positions[]; };
layout(std430, binding = SVO_BIND_COMPUTE_INDICES) readonly restrict buffer Indices { uint indices[]; };
// (triangle, its first item) for every triangle the host bounds at more than
// kSmall columns, in triangle order (so first items ascend).
layout(std430, binding = SVO_BIND_COMPUTE_WORK) readonly restrict buffer Work { uvec2 large[]; };

uniform uint uPass;
uniform uint uTriangles;
uniform uint uLarge; // entries of large[]
uniform uint uItemFirst; // pass 1: this dispatch's items, [uItemFirst, uItemEnd)
uniform uint uItemEnd;
const uint kSmall = 64u; // columns a pass-0 thread walks itself
const uint kChunk = 64u; // columns of one work item: one per thread of a pass-1 workgroup

struct Triangle {
    vec3 a, b, c;
    int w;
    vec4 box;
    ivec2 first, last; // columns (u, v) whose squares can meet the box, clamped to the clip box
    uint columns;      // the columns walked: the box's, or rows x width along the line
    // Along the longest edge's line (width > 0): row r on axis `major` (0: u,
    // 1: v) walks `width` columns from ceil(lineAt(r) - reach) on the other.
    int major;
    uint width;
    vec2 p;            // a point of the line, (u, v)
    float slope;       // d(other) / d(major)
    float reach;
};

vec3 position(uint i) { return vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]); }

// A thin triangle (a needle, a sliver) walks the columns along its longest
// edge instead of its box, when they are fewer: it lies within delta of that
// edge's line (as in svo_column_range), so a column can hold one of its
// voxels only where the line passes within uHalf + delta of the column's
// square on both axes, which in row r along the line's major axis is within
// reach = (uHalf + delta)(1 + |slope|) of the line's point there, plus a
// margin for rounding. The walk keeps exactly the voxels it would keep in
// the box: the columns left out hold none.
void alongLine(inout Triangle T, int u, int v, uvec2 n)
{
    int longest = svo_longest_edge(T.a, T.b, T.c);
    vec3 P = longest == 2 ? T.b : T.a;
    vec3 D = longest == 0 ? T.b - T.a : (longest == 1 ? T.c - T.a : T.c - T.b);
    vec2 d = vec2(D[u], D[v]);
    int major = abs(d.x) >= abs(d.y) ? 0 : 1;
    if (d[major] == 0.0) return;
    float E = max(abs(D.x), max(abs(D.y), abs(D.z)));
    vec3 nrm = cross(T.b - T.a, T.c - T.a);
    float dn = 8.0 * kUlp * E * E;
    float delta = (abs(nrm.x) + abs(nrm.y) + abs(nrm.z) + 3.0 * dn) / E * (1.0 + 8.0 * kUlp);
    float slope = d[1 - major] / d[major];
    vec3 m3 = max(abs(T.a), max(abs(T.b), abs(T.c)));
    float mag = max(m3.x, max(m3.y, m3.z)) + 1.0;
    float reach = (uHalf + delta) * (1.0 + abs(slope)) + 1.0 / 64.0 + 16.0 * kUlp * mag * (1.0 + abs(slope));
    float width = floor(2.0 * reach) + 2.0;
    float rows = float(n[major]);
    if (!(rows * width < float(T.columns))) return;
    T.major = major;
    T.width = uint(width);
    T.columns = n[major] * T.width;
    T.p = vec2(P[u], P[v]);
    T.slope = slope;
    T.reach = reach;
}

// Column c (0 <= c < T.columns) of the triangle's walk, as (u, v).
vec2 columnOf(Triangle T, uint c)
{
    if (T.width == 0u) {
        uint boxWidth = uint(T.last.x - T.first.x) + 1u;
        return vec2(T.first.x + int(c % boxWidth), T.first.y + int(c / boxWidth));
    }
    int row = T.first[T.major] + int(c / T.width);
    float at = T.p[1 - T.major] + (float(row) - T.p[T.major]) * T.slope;
    vec2 col;
    col[T.major] = float(row);
    col[1 - T.major] = ceil(at - T.reach) + float(c % T.width);
    return col;
}

Triangle load(uint t)
{
    Triangle T;
    T.a = position(indices[3u * t]);
    T.b = position(indices[3u * t + 1u]);
    T.c = position(indices[3u * t + 2u]);
    T.w = svo_projection_axis(T.a, T.b, T.c, kUlp);
    int u = (T.w + 1) % 3;
    int v = (T.w + 2) % 3;
    vec2 p0 = vec2(T.a[u], T.a[v]);
    vec2 p1 = vec2(T.b[u], T.b[v]);
    vec2 p2 = vec2(T.c[u], T.c[v]);
    vec2 lo = min(p0, min(p1, p2));
    vec2 hi = max(p0, max(p1, p2));
    T.box = vec4(lo, hi);
    // One column more on each side than the box needs, for rounding: the
    // walk's own test, the raster backend's, decides which of them count.
    T.first = max(ivec2(ceil(lo - uHalf)) - 1, ivec2(uClipLo[u], uClipLo[v]));
    T.last = min(ivec2(floor(hi + uHalf)) + 1, ivec2(uClipHi[u], uClipHi[v]) - 1);
    T.width = 0u;
    T.columns = 0u;
    if (T.last.x < T.first.x || T.last.y < T.first.y) return T;
    uvec2 n = uvec2(T.last - T.first) + 1u;
    T.columns = n.x * n.y; // below 2^32 - 64: the host checks every triangle's box
    alongLine(T, u, v, n);
    return T;
}

uint workgroupIndex() { return gl_WorkGroupID.x + gl_NumWorkGroups.x * gl_WorkGroupID.y; }

void main()
{
    if (uPass == 0u) {
        uint t = workgroupIndex() * 64u + gl_LocalInvocationID.x;
        if (t >= uTriangles) return;
        Triangle T = load(t);
        if (T.columns <= kSmall)
            for (uint c = 0u; c < T.columns; ++c) svo_walk_column(T.a, T.b, T.c, T.w, columnOf(T, c), T.box, t);
    } else {
        uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
        for (uint item = uItemFirst + workgroupIndex(); item < uItemEnd; item += groups) {
            // The last entry whose first item is at most this one.
            uint lo = 0u, hi = uLarge - 1u;
            while (lo < hi) {
                uint mid = (lo + hi + 1u) / 2u;
                if (large[mid].y <= item) lo = mid;
                else hi = mid - 1u;
            }
            uint t = large[lo].x;
            Triangle T = load(t);
            if (T.columns <= kSmall) continue; // pass 0 walked it
            uint c = (item - large[lo].y) * kChunk + gl_LocalInvocationID.x;
            if (c < T.columns) svo_walk_column(T.a, T.b, T.c, T.w, columnOf(T, c), T.box, t);
        }
    }
}
