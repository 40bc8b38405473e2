// The octree as the view's shaders read it (svo/gl/octree_view.h): its node
// and brick buffers, a voxel's attribute index, and a ray march that finds
// the first occupied voxel along a ray. Space is "cell space": local voxel v
// covers [v, v + 1] (local coordinates + 1/2).
//
// The march walks integer cells, never a float position, so it cannot stall
// or skip: at each step it descends from the root to the deepest node that
// holds the current cell. An empty child (or the largest empty aligned 4³ or
// 2³ block of an occupied brick, else one empty voxel) is an empty box; the
// ray leaves it through the face its exit time names, the cell moves one
// past that face on that axis, and the other axes take the rounded exit
// point clamped between the old cell and the box's far side. Every
// coordinate moves only along the ray and one moves every step, so the loop
// ends within dims.x + dims.y + dims.z steps.

layout(std430, binding = SVO_BIND_VIEW_NODES) readonly restrict buffer Nodes { uint nodes[]; };
layout(std430, binding = SVO_BIND_VIEW_BRICKS) readonly restrict buffer Bricks { uint bricks[]; };
layout(std430, binding = SVO_BIND_VIEW_VOXEL_START) readonly restrict buffer VoxelStart { uint voxelStart[]; };

uniform uint uBrickLevel;
uniform ivec3 uDims; // occupied cells lie in [0, uDims)

/// The brick bit of a cell (its position inside its brick).
uint brickBit(ivec3 cell)
{
    uvec3 v = uvec3(cell) & kBrickMask;
    return (v.x << kKeyLeafXShift) | (v.y << kKeyLeafYShift) | (v.z << kKeyLeafZShift);
}

bool brickHas(uint brick, uint bit) { return (bricks[kBrickWords * brick + (bit >> 5u)] & (1u << (bit & 31u))) != 0u; }

/// A voxel's index in voxel order (attribute channels): the brick's first
/// voxel plus the voxel's rank among the brick's set bits.
uint voxelIndex(uint brick, uint bit)
{
    uint base = kBrickWords * brick, word = bit >> 5u;
    uint rank = uint(bitCount(bricks[base + word] & ((1u << (bit & 31u)) - 1u)));
    for (uint w = 0u; w < word; ++w) rank += uint(bitCount(bricks[base + w]));
    return voxelStart[brick] + rank;
}

/// Descends from the root towards `cell`: the brick holding it (true), or
/// false with log2 of the edge of the empty node holding it.
bool findBrick(ivec3 cell, out uint brick, out int emptyLog2)
{
    uint node = 0u;
    brick = 0u;
    emptyLog2 = -1;
    for (uint level = 0u; level < uBrickLevel; ++level) {
        uint shift = 2u + uBrickLevel - level; // log2 of the child's size in cells
        uvec3 c = (uvec3(cell) >> shift) & 1u;
        uint child = c.x | (c.y << 1u) | (c.z << 2u);
        if ((nodes[kNodeWords * node + 1u] & (1u << child)) == 0u) { emptyLog2 = int(shift); return false; }
        node = nodes[kNodeWords * node] + child;
    }
    if (nodes[kNodeWords * node + 1u] == 0u) { emptyLog2 = 3; return false; } // an empty brick slot
    brick = nodes[kNodeWords * node];
    return true;
}

struct VoxelHit {
    ivec3 cell;  // the voxel hit
    int axis;    // the axis of the face the ray entered it through
    float t;     // where the ray enters it
    uint brick;  // its brick and bit
    uint bit;
};

const float kNever = 3.0e38;

/// The first occupied voxel along o + t d, t in [tMin, tMax] (cell space),
/// or false when there is none.
bool marchOctree(vec3 o, vec3 d, float tMin, float tMax, out VoxelHit hit)
{
    hit.cell = ivec3(0);
    hit.axis = 0;
    hit.t = 0.0;
    hit.brick = 0u;
    hit.bit = 0u;
    vec3 dims = vec3(uDims);
    // Entry into the grid's box [0, dims].
    float tNear = tMin, tFar = tMax;
    int axis = -1;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            if (o[i] < 0.0 || o[i] > dims[i]) return false;
            continue;
        }
        float t0 = (0.0 - o[i]) / d[i], t1 = (dims[i] - o[i]) / d[i];
        float lo = min(t0, t1), hi = max(t0, t1);
        if (lo > tNear) { tNear = lo; axis = i; }
        tFar = min(tFar, hi);
    }
    if (tNear > tFar) return false;

    ivec3 step = ivec3(sign(d));
    ivec3 cell = clamp(ivec3(floor(o + d * tNear)), ivec3(0), uDims - 1);
    if (axis >= 0) cell[axis] = step[axis] > 0 ? 0 : uDims[axis] - 1;
    if (axis < 0) { // the ray starts inside the grid: a hit there faces the ray's main axis
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
            int emptyLog2;
            inBrick = findBrick(cell, brick, emptyLog2);
            if (inBrick) {
                cachedBrick = brickOf;
            } else {
                size = 1 << emptyLog2;
                lo = (cell >> emptyLog2) << emptyLog2;
            }
        }
        if (inBrick) {
            uint bit = brickBit(cell);
            if (brickHas(brick, bit)) {
                hit.cell = cell;
                hit.axis = axis;
                hit.t = t;
                hit.brick = brick;
                hit.bit = bit;
                return true;
            }
            // An empty voxel: skip the largest empty aligned 4³ or 2³ block
            // holding it (bricks are mostly empty, so this saves most steps).
            // In the brick's words, bit x·64 + y·8 + z is word 2x + y/4, bit
            // 8(y % 4) + z: a y-aligned 4-row of one x is one word.
            uvec3 v = uvec3(cell) & kBrickMask;
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
        if (exitAxis < 0 || tExit > tFar) return false;
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
        if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, uDims))) return false;
    }
    return false;
}
