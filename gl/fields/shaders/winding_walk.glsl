// Generalized winding numbers from the winding tree (svo/core/winding_tree.h
// has the method): the buffers, the triangles' exact solid angles and the
// loop budget that winding_number.comp and winding_columns.comp share. Far
// nodes add their far field to second order (float); leaf triangles add
// their exact solid angle, the orientation decided in double from the local
// double positions.
#include "gpu_layout.h"
#include "field_layout.h"

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
uniform uvec3 uBricks;      // the box of bricks (per brick)
uniform uvec3 uBrickOrigin; // ... and its first brick
uniform float uBeta2;  // beta^2; nodes nearer than beta radii are opened
// Loop iterations an invocation may run before the driver would end its loops
// silently (ContextInfo::loopLimit, less the loops around the walks); past it
// the invocation stops and sets word uFlagWord of the output, which the host
// reports. No limit: 0xFFFFFFFF. Each walk charges its steps with overBudget.
uniform uint uStepBudget;
uniform uint uFlagWord;

uint gSteps = 0u;
bool gStopped = false;
// Charges `steps` loop iterations: llvmpipe counts every iteration of every
// loop of an invocation against one limit, inner loops included.
bool overBudget(uint steps)
{
    gSteps += steps;
    if (gSteps <= uStepBudget) return false;
    gStopped = true;
    return true;
}

const float kInvFourPi = 0.0795774715459476679;
const float kPi = 3.14159265358979324;
const float kHalfPi = 1.57079632679489662;

dvec3 position(uint i) { return dvec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]); }

// Solid angle of a triangle whose corners, relative to the point it is seen
// from, are x, y, z (van Oosterom and Strackee). `precise` (here and in
// farNode) keeps the compiler from fusing operations differently in the two
// walks, which must give the same bits.
float solidAngle(dvec3 x, dvec3 y, dvec3 z)
{
    precise double lx = sqrt(dot(x, x)), ly = sqrt(dot(y, y)), lz = sqrt(dot(z, z));
    precise double det = dot(x, cross(y, z));
    if (det == 0.0LF) return 0.0; // the point in the triangle's plane
    precise double den = lx * ly * lz + dot(x, y) * lz + dot(y, z) * lx + dot(z, x) * ly;
    // Half the solid angle is atan2(det, den). GLSL has no double atan, and
    // llvmpipe's float atan(y, x) returned the wrong quadrant for some far
    // triangles: the angle is built from the one-argument atan of a ratio in
    // [0, 1], its quadrant chosen here, the sign of det kept apart.
    double ad = abs(det), aden = abs(den);
    precise float base = ad <= aden ? atan(float(ad / aden)) : kHalfPi - atan(float(aden / ad)); // in [0, pi/2]
    precise float angle = den >= 0.0LF ? base : kPi - base;                                     // in [0, pi]
    return det > 0.0LF ? 2.0 * angle : -2.0 * angle;
}

// The solid angle of triangle t seen from q.
float solidAngle(dvec3 q, uint t)
{
    return solidAngle(position(indices[3u * t]) - q, position(indices[3u * t + 1u]) - q,
                      position(indices[3u * t + 2u]) - q);
}

// A node's expansion (winding_tree.h): vec4s 1 to 8 of its kWindingNodeVec4s.
struct Expansion {
    vec4 b;  // N, C_00
    vec4 c1; // C_01 C_02 C_10 C_11
    vec4 c2; // C_12 C_20 C_21 C_22
    vec4 m0; // M_000 M_001 M_002 M_011
    vec4 m1; // M_012 M_022 M_100 M_101
    vec4 m2; // M_102 M_111 M_112 M_122
    vec4 m3; // M_200 M_201 M_202 M_211
    vec4 m4; // M_212 M_222 0 0
};

Expansion expansionOf(uint n)
{
    uint i = kWindingNodeVec4s * n;
    return Expansion(nodes[i + 1u], nodes[i + 2u], nodes[i + 3u], nodes[i + 4u], nodes[i + 5u], nodes[i + 6u],
                     nodes[i + 7u], nodes[i + 8u]);
}

// One row i of the second moments, S = M_i.. (symmetric: 00 01 02 11 12 22),
// added to the sums of the second-order term: a = sum_i (S d)_i,
// b = sum_i d_i tr(S), c = sum_i d_i d^T S d.
void addSecondMoments(float s00, float s01, float s02, float s11, float s12, float s22, vec3 d, float di,
                      float sdi, inout float a, inout float b, inout float c)
{
    precise vec3 sd = vec3(s00 * d.x + s01 * d.y + s02 * d.z, s01 * d.x + s11 * d.y + s12 * d.z,
                           s02 * d.x + s12 * d.y + s22 * d.z);
    precise float na = a + sdi, nb = b + di * (s00 + s11 + s22), nc = c + di * dot(d, sd);
    a = na;
    b = nb;
    c = nc;
}

// A far node's term (times 4 pi) at d = c - q, d2 = |d|^2: the Taylor series
// of winding_tree.h to second order.
float farTerm(vec3 d, float d2, Expansion e)
{
    precise vec3 cd = vec3(e.b.w * d.x + e.c1.x * d.y + e.c1.y * d.z, e.c1.z * d.x + e.c1.w * d.y + e.c2.x * d.z,
                           e.c2.y * d.x + e.c2.z * d.y + e.c2.w * d.z);
    precise float inv3 = 1.0 / (d2 * sqrt(d2));
    precise float inv5 = inv3 / d2;
    float a = 0.0, b = 0.0, c = 0.0;
    // (S d)_i needs row i of S d: the i-th component of each row's product.
    addSecondMoments(e.m0.x, e.m0.y, e.m0.z, e.m0.w, e.m1.x, e.m1.y, d, d.x,
                     e.m0.x * d.x + e.m0.y * d.y + e.m0.z * d.z, a, b, c);
    addSecondMoments(e.m1.z, e.m1.w, e.m2.x, e.m2.y, e.m2.z, e.m2.w, d, d.y,
                     e.m1.w * d.x + e.m2.y * d.y + e.m2.z * d.z, a, b, c);
    addSecondMoments(e.m3.x, e.m3.y, e.m3.z, e.m3.w, e.m4.x, e.m4.y, d, d.z,
                     e.m3.z * d.x + e.m4.x * d.y + e.m4.y * d.z, a, b, c);
    precise float first = (dot(d, e.b.xyz) + (e.b.w + e.c1.w + e.c2.w)) * inv3 - 3.0 * dot(d, cd) * inv5;
    precise float second = 0.5 * (15.0 * c * inv5 / d2 - 3.0 * (2.0 * a + b) * inv5);
    precise float term = first + second;
    return term;
}

// Whether node n, of centre and radius cr, is farther than beta radii from
// q; if so, `term` is its far-field term.
bool farNode(uint n, vec4 cr, vec3 q, out float term)
{
    precise vec3 d = cr.xyz - q;
    precise float d2 = dot(d, d);
    precise float reach2 = uBeta2 * cr.w * cr.w;
    term = 0.0;
    if (!(d2 > reach2)) return false;
    term = farTerm(d, d2, expansionOf(n));
    return true;
}

// The origin of brick `brick` of the per-voxel list, in local voxels.
dvec3 listedBrick(uint brick)
{
    return dvec3(uvec3(bricks[3u * brick], bricks[3u * brick + 1u], bricks[3u * brick + 2u]) << kBrickLog2);
}

// Sets bits `bits` of a column's byte in brick `brick`'s inside mask: bit
// (x, y, z) of a Brick is x * 64 + y * 8 + z, so a column's 8 bits are one
// byte of one word.
void setColumnBits(uint brick, uint x, uint y, uint bits)
{
    if (bits != 0u) atomicOr(outWords[16u * brick + (x << 1u) + (y >> 2u)], bits << ((y & 3u) << 3u));
}
