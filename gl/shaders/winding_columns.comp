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

// Bit k set when the winding number at `base` + (0, 0, k) is at least 1/2.
uint windingColumn(dvec3 base)
{
    vec3 bf = vec3(base);
    float sum[8];
    for (uint k = 0u; k < 8u; ++k) sum[k] = 0.0;
    uint stack[kWindingStack];
    uint masks[kWindingStack]; // the centres whose walks reach the node
    uint top = 1u;
    stack[0] = 0u;
    masks[0] = 0xFFu;
    while (top > 0u) {
        if (overBudget()) break;
        --top;
        uint n = stack[top], mask = masks[top];
        vec4 cr = nodes[2u * n];
        vec3 area = nodes[2u * n + 1u].xyz;
        precise float reach2 = uBeta2 * cr.w * cr.w;
        uint near = 0u;
        // farNode's arithmetic for every centre, without branches (they cost
        // more than the arithmetic on SIMD lanes); adding 0 keeps a sum.
        for (uint k = 0u; k < 8u; ++k) {
            precise vec3 d = cr.xyz - vec3(bf.xy, bf.z + float(k));
            precise float d2 = dot(d, d);
            bool reached = (mask & (1u << k)) != 0u, far = d2 > reach2;
            sum[k] += reached && far ? dipoleTerm(d, d2, area) : 0.0;
            near |= reached && !far ? 1u << k : 0u;
        }
        if (near == 0u) continue;
        uvec2 l = links[n];
        if ((l.y & kWindingLeaf) != 0u) {
            uint last = l.x + (l.y & ~kWindingLeaf);
            for (uint i = l.x; i < last; ++i) {
                if (overBudget()) break;
                uint t = order[i];
                dvec3 a = position(indices[3u * t]), b = position(indices[3u * t + 1u]),
                      c = position(indices[3u * t + 2u]);
                for (uint k = 0u; k < 8u; ++k) {
                    if ((near & (1u << k)) == 0u) continue;
                    dvec3 q = dvec3(base.xy, base.z + double(k));
                    sum[k] += solidAngle(a - q, b - q, c - q);
                }
            }
        } else {
            stack[top] = l.x;
            masks[top++] = near;
            stack[top] = l.y;
            masks[top++] = near;
        }
    }
    uint bits = 0u;
    for (uint k = 0u; k < 8u; ++k)
        if (sum[k] * kInvFourPi >= 0.5) bits |= 1u << k;
    return bits;
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
