// Generalized winding numbers from the winding tree (svo/core/winding_tree.h
// has the method): the buffers, the triangles' exact solid angles and the
// loop budget that winding_number.comp and winding_columns.comp share. Far
// nodes add their dipole (float); leaf triangles add their exact solid
// angle, the orientation decided in double from the local double positions.
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

// A node's dipole term N . d / |d|^3 (times 4 pi), d = c - q, d2 = |d|^2.
float dipoleTerm(vec3 d, float d2, vec3 area)
{
    precise float term = dot(d, area) / (d2 * sqrt(d2));
    return term;
}

// Whether node n, of centre and radius cr, is farther than beta radii from
// q; if so, `dipole` is its term.
bool farNode(uint n, vec4 cr, vec3 q, out float dipole)
{
    precise vec3 d = cr.xyz - q;
    precise float d2 = dot(d, d);
    precise float reach2 = uBeta2 * cr.w * cr.w;
    dipole = 0.0;
    if (!(d2 > reach2)) return false;
    dipole = dipoleTerm(d, d2, nodes[2u * n + 1u].xyz);
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
