#version 450 core
// The per-voxel mode of winding_number.comp on a CPU rasterizer, whose SIMD
// lanes are a workgroup's threads: one workgroup of 64 threads per brick of
// a list, a column of 8 voxel centres a thread, and one walk of the tree for
// the column instead of 8. The walk carries, per node, the mask of the
// centres whose own walk reaches it, and treats each centre as its own walk
// would, in the same order: the same bits as winding_number.comp, with a
// node's loads, a triangle's corners and the loop's overhead shared by up
// to 8 centres (on a GPU the 8 sums and the masks cost more in threads
// that run at once than they save).
layout(local_size_x = 64) in;
#include "winding_walk.glsl"

// Centre k of the column at `base`, if `mask` has it: adds node n's far
// term to `sum` and returns 0 when the node is far from it, else returns
// bit k (the node is near). farNode's arithmetic without its branches
// (they cost more than the arithmetic on SIMD lanes); adding 0 keeps a sum.
uint nodeAtCentre(uint k, vec4 cr, Expansion e, vec3 bf, uint mask, inout float sum)
{
    precise vec3 d = cr.xyz - vec3(bf.xy, bf.z + float(k));
    precise float d2 = dot(d, d);
    precise float reach2 = uBeta2 * cr.w * cr.w;
    bool reached = (mask & (1u << k)) != 0u, far = d2 > reach2;
    sum += reached && far ? farTerm(d, d2, e) : 0.0;
    return reached && !far ? 1u << k : 0u;
}

// Centre k, if `near` has it: adds the exact solid angle of the triangle
// with corners a, b, c.
void triangleAtCentre(uint k, dvec3 a, dvec3 b, dvec3 c, dvec3 base, uint near, inout float sum)
{
    if ((near & (1u << k)) == 0u) return;
    dvec3 q = dvec3(base.xy, base.z + double(k));
    sum += solidAngle(a - q, b - q, c - q);
}

// Bit k set when the winding number at `base` + (0, 0, k) is at least 1/2.
// The 8 centres are written out, not looped over: llvmpipe counts every
// loop iteration against its limit, so the walk's steps are all it runs.
uint windingColumn(dvec3 base)
{
    vec3 bf = vec3(base);
    float s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0, s5 = 0.0, s6 = 0.0, s7 = 0.0;
    uint stack[kWindingStack];
    uint masks[kWindingStack]; // the centres whose walks reach the node
    uint top = 1u;
    stack[0] = 0u;
    masks[0] = 0xFFu;
    while (top > 0u) {
        if (overBudget(1u)) break;
        --top;
        uint n = stack[top], mask = masks[top];
        vec4 cr = nodes[kWindingNodeVec4s * n];
        Expansion e = expansionOf(n);
        uint near = nodeAtCentre(0u, cr, e, bf, mask, s0) | nodeAtCentre(1u, cr, e, bf, mask, s1) |
                    nodeAtCentre(2u, cr, e, bf, mask, s2) | nodeAtCentre(3u, cr, e, bf, mask, s3) |
                    nodeAtCentre(4u, cr, e, bf, mask, s4) | nodeAtCentre(5u, cr, e, bf, mask, s5) |
                    nodeAtCentre(6u, cr, e, bf, mask, s6) | nodeAtCentre(7u, cr, e, bf, mask, s7);
        if (near == 0u) continue;
        uvec2 l = links[n];
        if ((l.y & kWindingLeaf) != 0u) {
            uint last = l.x + (l.y & ~kWindingLeaf);
            for (uint i = l.x; i < last; ++i) {
                if (overBudget(1u)) break;
                uint t = order[i];
                dvec3 a = position(indices[3u * t]), b = position(indices[3u * t + 1u]),
                      c = position(indices[3u * t + 2u]);
                triangleAtCentre(0u, a, b, c, base, near, s0);
                triangleAtCentre(1u, a, b, c, base, near, s1);
                triangleAtCentre(2u, a, b, c, base, near, s2);
                triangleAtCentre(3u, a, b, c, base, near, s3);
                triangleAtCentre(4u, a, b, c, base, near, s4);
                triangleAtCentre(5u, a, b, c, base, near, s5);
                triangleAtCentre(6u, a, b, c, base, near, s6);
                triangleAtCentre(7u, a, b, c, base, near, s7);
            }
        } else {
            stack[top] = l.x;
            masks[top++] = near;
            stack[top] = l.y;
            masks[top++] = near;
        }
    }
    vec4 lower = vec4(s0, s1, s2, s3) * kInvFourPi, upper = vec4(s4, s5, s6, s7) * kInvFourPi;
    uvec4 lo = uvec4(greaterThanEqual(lower, vec4(0.5))), hi = uvec4(greaterThanEqual(upper, vec4(0.5)));
    return lo.x | lo.y << 1u | lo.z << 2u | lo.w << 3u | hi.x << 4u | hi.y << 5u | hi.z << 6u | hi.w << 7u;
}

void main()
{
    uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
    uint group = gl_WorkGroupID.x + gl_NumWorkGroups.x * gl_WorkGroupID.y;
    uint x = gl_LocalInvocationID.x >> 3u, y = gl_LocalInvocationID.x & 7u;
    for (uint brick = uFirst + group; brick < uCount; brick += groups)
        setColumnBits(brick, x, y, windingColumn(listedBrick(brick) + dvec3(x, y, 0u)));
    if (gStopped) atomicOr(outWords[uFlagWord], 1u);
}
