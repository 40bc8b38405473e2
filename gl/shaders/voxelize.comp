#version 450 core
// The compute backend: triangle-parallel voxelization with the raster
// backend's column walk (column_walk.glsl), so both keep the same voxels.
//
// Pass 0, one thread per triangle: project the triangle on its projection
// axis (svo_projection_axis) and take the columns whose squares can meet its
// bounding box. A triangle of at most kSmall columns walks them itself. A
// larger one is cut into chunks of 64 columns (its box in row-major order):
// pass 1 runs one workgroup of 64 threads per chunk, one column per thread,
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
uniform uint uItemFirst; // pass 1: this dispatch's queue items, [uItemFirst, uItemEnd)
uniform uint uItemEnd;
const uint kSmall = 64u; // columns a pass-0 thread walks itself
const uint kChunk = 64u; // columns of one work item: one per thread of a pass-1 workgroup

struct Triangle {
    vec3 a, b, c;
    int w;
    vec4 box;
    ivec2 first, last; // columns (u, v) whose squares can meet the box, clamped to the clip box
};

vec3 position(uint i) { return vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]); }

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
    return T;
}

uint workgroupIndex() { return gl_WorkGroupID.x + gl_NumWorkGroups.x * gl_WorkGroupID.y; }

void main()
{
    if (uPass == 0u) {
        uint t = workgroupIndex() * 64u + gl_LocalInvocationID.x;
        if (t >= uTriangles) return;
        Triangle T = load(t);
        if (T.last.x < T.first.x || T.last.y < T.first.y) return;
        uvec2 n = uvec2(T.last - T.first) + 1u;
        uint columns = n.x * n.y; // below 2^32 - 64: the host checks every triangle's box
        if (columns <= kSmall)
            for (int j = T.first.y; j <= T.last.y; ++j)
                for (int i = T.first.x; i <= T.last.x; ++i)
                    svo_walk_column(T.a, T.b, T.c, T.w, vec2(i, j), T.box, t);
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
            if (T.last.x < T.first.x || T.last.y < T.first.y) continue;
            uint width = uint(T.last.x - T.first.x) + 1u;
            uint columns = width * (uint(T.last.y - T.first.y) + 1u);
            if (columns <= kSmall) continue; // pass 0 walked it
            uint c = (item - large[lo].y) * kChunk + gl_LocalInvocationID.x;
            if (c < columns)
                svo_walk_column(T.a, T.b, T.c, T.w, vec2(T.first.x + int(c % width), T.first.y + int(c / width)),
                                T.box, t);
        }
    }
}
