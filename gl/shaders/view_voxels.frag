#version 450 core
// Voxels by ray-marching the octree (svo/gl/octree_view.h). Space is "cell
// space": local voxel v covers [v, v + 1] (local coordinates + 1/2).
//
// The march walks integer cells, never a float position, so it cannot stall
// or skip: at each step it descends from the root to the deepest node that
// holds the current cell. An empty child (or the largest empty aligned 4³ or
// 2³ block of an occupied brick, else one empty voxel) is an empty box; the ray leaves it through the face its exit time
// names, the cell moves one past that face on that axis, and the other axes
// take the rounded exit point clamped between the old cell and the box's far
// side. Every coordinate moves only along the ray and one moves every step,
// so the loop ends within dims.x + dims.y + dims.z steps.
#include "gpu_layout.h"

layout(std430, binding = SVO_BIND_VIEW_NODES) readonly restrict buffer Nodes { uint nodes[]; };
layout(std430, binding = SVO_BIND_VIEW_BRICKS) readonly restrict buffer Bricks { uint bricks[]; };
layout(std430, binding = SVO_BIND_VIEW_VOXEL_START) readonly restrict buffer VoxelStart { uint voxelStart[]; };
layout(std430, binding = SVO_BIND_VIEW_ATTRIBUTE) readonly restrict buffer Attribute { uint channel[]; };

uniform mat4 uInverseViewProjection; // clip -> cell space
uniform mat4 uViewProjection;        // cell space -> clip
uniform vec2 uViewport;              // pixels
uniform uint uBrickLevel;
uniform ivec3 uDims;                 // occupied cells lie in [0, uDims)
uniform vec3 uColor;
uniform int uColorMode;              // SVO_VIEW_COLOR_*: flat uColor or a voxel attribute

/// The voxel's colour: flat, or its attribute (voxel order: the brick's first
/// voxel plus the voxel's rank among the brick's set bits).
vec3 voxelColor(uint brick, uint bit)
{
    if (uColorMode == SVO_VIEW_COLOR_FLAT) return uColor;
    uint base = kBrickWords * brick, word = bit >> 5u;
    uint rank = uint(bitCount(bricks[base + word] & ((1u << (bit & 31u)) - 1u)));
    for (uint w = 0u; w < word; ++w) rank += uint(bitCount(bricks[base + w]));
    uint v = voxelStart[brick] + rank;
    if (uColorMode == SVO_VIEW_COLOR_TRIANGLE) { // distinct colours for neighbouring ids
        uint h = channel[v] * 2654435761u;
        return vec3(float(h >> 24u), float((h >> 16u) & 255u), float((h >> 8u) & 255u)) / 255.0 * 0.8 + 0.2;
    }
    vec3 c = vec3(uintBitsToFloat(channel[3u * v]), uintBitsToFloat(channel[3u * v + 1u]),
                  uintBitsToFloat(channel[3u * v + 2u]));
    return uColorMode == SVO_VIEW_COLOR_NORMAL ? 0.5 + 0.5 * c : c;
}

#include "view_cones.glsl"

uniform uint uAoOnly; // 1: the voxels are their AO, grey

out vec4 fragColor;

const float kNever = 3.0e38;

void main()
{
    vec2 ndc = gl_FragCoord.xy / uViewport * 2.0 - 1.0;
    vec4 a = uInverseViewProjection * vec4(ndc, -1.0, 1.0);
    vec4 b = uInverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w;
    vec3 d = b.xyz / b.w - o; // t in [0, 1] spans the near to the far plane
    vec3 dims = vec3(uDims);

    // Entry into the grid's box [0, dims].
    float tNear = 0.0, tFar = 1.0;
    int axis = -1;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            if (o[i] < 0.0 || o[i] > dims[i]) discard;
            continue;
        }
        float t0 = (0.0 - o[i]) / d[i], t1 = (dims[i] - o[i]) / d[i];
        float lo = min(t0, t1), hi = max(t0, t1);
        if (lo > tNear) { tNear = lo; axis = i; }
        tFar = min(tFar, hi);
    }
    if (tNear > tFar) discard;

    ivec3 step = ivec3(sign(d));
    ivec3 cell = clamp(ivec3(floor(o + d * tNear)), ivec3(0), uDims - 1);
    if (axis >= 0) cell[axis] = step[axis] > 0 ? 0 : uDims[axis] - 1;
    if (axis < 0) { // the near plane cuts the grid: shade by the ray's main axis
        vec3 ad = abs(d);
        axis = ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2);
    }
    float t = tNear;

    ivec3 cachedBrick = ivec3(-1);
    uint brick = 0u;
    int maxSteps = uDims.x + uDims.y + uDims.z + 4;
    for (int s = 0; s < maxSteps; ++s) {
        // The empty box holding `cell`, or a hit.
        ivec3 lo;
        int size;
        ivec3 brickOf = cell >> 3;
        bool inBrick = all(equal(brickOf, cachedBrick));
        if (!inBrick) {
            uint node = 0u;
            int emptyLog2 = -1;
            for (uint level = 0u; level < uBrickLevel; ++level) {
                uint shift = 2u + uBrickLevel - level; // log2 of the child's size in cells
                uvec3 c = (uvec3(cell) >> shift) & 1u;
                uint child = c.x | (c.y << 1u) | (c.z << 2u);
                if ((nodes[kNodeWords * node + 1u] & (1u << child)) == 0u) { emptyLog2 = int(shift); break; }
                node = nodes[kNodeWords * node] + child;
            }
            if (emptyLog2 < 0 && nodes[kNodeWords * node + 1u] == 0u) emptyLog2 = 3; // an empty brick slot
            if (emptyLog2 < 0) {
                inBrick = true;
                cachedBrick = brickOf;
                brick = nodes[kNodeWords * node];
            } else {
                size = 1 << emptyLog2;
                lo = (cell >> emptyLog2) << emptyLog2;
            }
        }
        if (inBrick) {
            uvec3 v = uvec3(cell) & kBrickMask;
            uint bit = (v.x << kKeyLeafXShift) | (v.y << kKeyLeafYShift) | (v.z << kKeyLeafZShift);
            if ((bricks[kBrickWords * brick + (bit >> 5u)] & (1u << (bit & 31u))) != 0u) {
                vec3 n = vec3(0.0);
                n[axis] = -float(step[axis]);
                // Lit by the face normal: a head light plus a little ambient.
                float light = 0.45 + 0.55 * abs(dot(n, normalize(d)));
                vec3 hit = o + d * t;
                float ao = ambientOcclusion(hit, n);
                fragColor = uAoOnly != 0u ? vec4(vec3(ao), 1.0) : vec4(voxelColor(brick, bit) * light * ao, 1.0);
                vec4 clip = uViewProjection * vec4(hit, 1.0);
                gl_FragDepth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);
                return;
            }
            // An empty voxel: skip the largest empty aligned 4³ or 2³ block
            // holding it (bricks are mostly empty, so this saves most steps).
            // In the brick's words, bit x·64 + y·8 + z is word 2x + y/4, bit
            // 8(y % 4) + z: a y-aligned 4-row of one x is one word.
            uint base = kBrickWords * brick;
            uvec3 b4 = v & ~3u;
            uint mask4 = 0x0F0F0F0Fu << b4.z;
            uint any4 = 0u;
            for (uint x = b4.x; x < b4.x + 4u; ++x) any4 |= bricks[base + 2u * x + (b4.y >> 2u)] & mask4;
            if (any4 == 0u) {
                size = 4;
                lo = cell & ~3;
            } else {
                uvec3 b2 = v & ~1u;
                uint mask2 = 0x303u << (((b2.y & 3u) << 3u) | b2.z);
                uint word = 2u * b2.x + (b2.y >> 2u);
                if (((bricks[base + word] | bricks[base + word + 2u]) & mask2) == 0u) {
                    size = 2;
                    lo = cell & ~1;
                } else {
                    size = 1;
                    lo = cell;
                }
            }
        }
        // Leave the box [lo, lo + size).
        float tExit = kNever;
        int exitAxis = -1;
        for (int i = 0; i < 3; ++i) {
            if (step[i] == 0) continue;
            float face = float(step[i] > 0 ? lo[i] + size : lo[i]);
            float ti = (face - o[i]) / d[i];
            if (ti < tExit) { tExit = ti; exitAxis = i; }
        }
        if (exitAxis < 0 || tExit > tFar) discard;
        t = max(t, tExit);
        vec3 p = o + d * t;
        ivec3 next;
        for (int i = 0; i < 3; ++i) {
            int far = step[i] > 0 ? lo[i] + size - 1 : lo[i];
            int r = int(floor(p[i]));
            next[i] = step[i] > 0 ? clamp(r, cell[i], far) : (step[i] < 0 ? clamp(r, far, cell[i]) : cell[i]);
        }
        next[exitAxis] = step[exitAxis] > 0 ? lo[exitAxis] + size : lo[exitAxis] - 1;
        cell = next;
        axis = exitAxis;
        if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, uDims))) discard;
    }
    discard;
}
