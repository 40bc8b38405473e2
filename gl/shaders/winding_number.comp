#version 450 core
// Generalized winding numbers from the winding tree (svo/core/winding_tree.h
// has the method). Two modes:
//   per voxel  one workgroup of 64 threads per brick of a list; each thread
//              takes a column of 8 voxel centres and sets the bits of those
//              whose winding number is at least 1/2;
//   per brick  one thread per brick of the grid's box, at the brick's centre,
//              writing the winding number itself.
// Far nodes add their dipole (float); leaf triangles add their exact solid
// angle, the orientation decided in double from the local double positions.
layout(local_size_x = 64) in;
#include "gpu_layout.h"

layout(std430, binding = SVO_BIND_FIELD_POSITIONS) readonly restrict buffer Positions { double positions[]; };
layout(std430, binding = SVO_BIND_FIELD_INDICES) readonly restrict buffer Indices { uint indices[]; };
layout(std430, binding = SVO_BIND_WINDING_NODES) readonly restrict buffer Nodes { vec4 nodes[]; };
layout(std430, binding = SVO_BIND_WINDING_LINKS) readonly restrict buffer Links { uvec2 links[]; };
layout(std430, binding = SVO_BIND_WINDING_ORDER) readonly restrict buffer Order { uint order[]; };
layout(std430, binding = SVO_BIND_WINDING_BRICKS) readonly restrict buffer Bricks { uint bricks[]; };
layout(std430, binding = SVO_BIND_WINDING_OUT) restrict buffer Out { uint outWords[]; };

uniform uint uMode;    // 0 per voxel, 1 per brick
uniform uint uFirst;   // the first brick of this dispatch
uniform uint uCount;   // one past the last brick of this dispatch (of the list, or of the grid's box)
uniform uvec3 uBricks; // the grid's box in bricks (per brick)
uniform float uBeta2;  // beta^2; nodes nearer than beta radii are opened
// Loop iterations an invocation may run before the driver would end its loops
// silently (ContextInfo::loopLimit, less the loops around the walks); past it
// the invocation stops and sets word uFlagWord of the output, which the host
// reports. No limit: 0xFFFFFFFF.
uniform uint uStepBudget;
uniform uint uFlagWord;

uint gSteps = 0u;
bool gStopped = false;
bool overBudget()
{
    if (++gSteps <= uStepBudget) return false;
    gStopped = true;
    return true;
}

const float kInvFourPi = 0.0795774715459476679;
const float kPi = 3.14159265358979324;
const float kHalfPi = 1.57079632679489662;

dvec3 position(uint i) { return dvec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]); }

// Solid angle of triangle t seen from q (van Oosterom and Strackee).
float solidAngle(dvec3 q, uint t)
{
    dvec3 x = position(indices[3u * t]) - q, y = position(indices[3u * t + 1u]) - q,
          z = position(indices[3u * t + 2u]) - q;
    double lx = sqrt(dot(x, x)), ly = sqrt(dot(y, y)), lz = sqrt(dot(z, z));
    double det = dot(x, cross(y, z));
    if (det == 0.0LF) return 0.0; // q in the triangle's plane
    double den = lx * ly * lz + dot(x, y) * lz + dot(y, z) * lx + dot(z, x) * ly;
    // Half the solid angle is atan2(det, den). GLSL has no double atan, and
    // llvmpipe's float atan(y, x) returned the wrong quadrant for some far
    // triangles: the angle is built from the one-argument atan of a ratio in
    // [0, 1], its quadrant chosen here, the sign of det kept apart.
    double ad = abs(det), aden = abs(den);
    float base = ad <= aden ? atan(float(ad / aden)) : kHalfPi - atan(float(aden / ad)); // in [0, pi/2]
    float angle = den >= 0.0LF ? base : kPi - base;                                     // in [0, pi]
    return det > 0.0LF ? 2.0 * angle : -2.0 * angle;
}

float windingNumber(dvec3 q)
{
    vec3 qf = vec3(q);
    uint stack[kWindingStack];
    uint top = 1u;
    stack[0] = 0u;
    float sum = 0.0;
    while (top > 0u) {
        if (overBudget()) break;
        uint n = stack[--top];
        vec4 cr = nodes[2u * n];
        vec3 d = cr.xyz - qf;
        float d2 = dot(d, d);
        if (d2 > uBeta2 * cr.w * cr.w) {
            sum += dot(d, nodes[2u * n + 1u].xyz) / (d2 * sqrt(d2));
            continue;
        }
        uvec2 l = links[n];
        if ((l.y & kWindingLeaf) != 0u) {
            uint last = l.x + (l.y & ~kWindingLeaf);
            for (uint i = l.x; i < last; ++i) {
                if (overBudget()) break;
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
            outWords[g] = floatBitsToUint(windingNumber(dvec3(b << kBrickLog2) + 3.5LF));
        }
        if (gStopped) atomicOr(outWords[uFlagWord], 1u);
        return;
    }
    uint x = gl_LocalInvocationID.x >> 3u, y = gl_LocalInvocationID.x & 7u;
    for (uint brick = uFirst + group; brick < uCount; brick += groups) {
        dvec3 lo = dvec3(uvec3(bricks[3u * brick], bricks[3u * brick + 1u], bricks[3u * brick + 2u]) << kBrickLog2);
        uint bits = 0u;
        for (uint z = 0u; z < 8u; ++z)
            if (windingNumber(lo + dvec3(x, y, z)) >= 0.5) bits |= 1u << z;
        // Bit (x, y, z) of a Brick is x * 64 + y * 8 + z: a thread's 8 bits
        // are one byte of one word.
        if (bits != 0u) atomicOr(outWords[16u * brick + (x << 1u) + (y >> 2u)], bits << ((y & 3u) << 3u));
    }
    if (gStopped) atomicOr(outWords[uFlagWord], 1u);
}
