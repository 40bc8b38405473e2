#version 450 core
// Winding numbers (winding_walk.glsl) with a walk per point. Two modes:
//   per voxel  one workgroup of 64 threads per brick of a list; each thread
//              takes a column of 8 voxel centres, walks the tree for each
//              and sets the bits of those whose winding number is at least
//              1/2 (winding_columns.comp does this on CPU rasterizers);
//   per brick  one thread per brick of the grid's box, at the brick's centre,
//              writing the winding number itself.
layout(local_size_x = 64) in;
#include "winding_walk.glsl"

float windingNumber(dvec3 q)
{
    vec3 qf = vec3(q);
    uint stack[kWindingStack];
    uint top = 1u;
    stack[0] = 0u;
    float sum = 0.0;
    while (top > 0u) {
        if (overBudget(1u)) break;
        uint n = stack[--top];
        float term;
        if (farNode(n, nodes[kWindingNodeVec4s * n], qf, term)) {
            sum += term;
            continue;
        }
        uvec2 l = links[n];
        if ((l.y & kWindingLeaf) != 0u) {
            uint last = l.x + (l.y & ~kWindingLeaf);
            for (uint i = l.x; i < last; ++i) {
                if (overBudget(1u)) break;
                sum += solidAngle(q, order[i]);
            }
        } else {
            stack[top++] = l.x;
            stack[top++] = l.y;
        }
    }
    return sum * kInvFourPi;
}

void main()
{
    uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
    uint group = gl_WorkGroupID.x + gl_NumWorkGroups.x * gl_WorkGroupID.y;
    if (uMode == 1u) {
        for (uint g = uFirst + group * 64u + gl_LocalInvocationID.x; g < uCount; g += groups * 64u) {
            uvec3 b = uvec3(g % uBricks.x, (g / uBricks.x) % uBricks.y, g / (uBricks.x * uBricks.y));
            outWords[g] = floatBitsToUint(windingNumber(dvec3((uBrickOrigin + b) << kBrickLog2) + 3.5LF));
        }
        if (gStopped) atomicOr(outWords[uFlagWord], 1u);
        return;
    }
    uint x = gl_LocalInvocationID.x >> 3u, y = gl_LocalInvocationID.x & 7u;
    for (uint brick = uFirst + group; brick < uCount; brick += groups) {
        dvec3 lo = listedBrick(brick);
        uint bits = 0u;
        for (uint z = 0u; z < 8u; ++z)
            if (windingNumber(lo + dvec3(x, y, z)) >= 0.5) bits |= 1u << z;
        setColumnBits(brick, x, y, bits);
    }
    if (gStopped) atomicOr(outWords[uFlagWord], 1u);
}
