#version 450 core
// Pass 7, when NanoGridHeader::checksum asks for it: each node's CRC-32 for
// NanoVDB's full checksum (zlib's CRC-32: reflected polynomial 0xEDB88320,
// all bits set before and after), for the nodes of one level.
//
// CRC-32 is linear over GF(2): with R(s) the register after stream s from 0,
// R(A||B) = R(A)·x^(8|B|) mod P xor R(B), zero bytes before a stream leave
// R unchanged, and starting from all bits set equals inverting the stream's
// first four bytes. So each node is seen front-padded with zeros to whole
// blocks of 64 pieces; a work group takes one block of one node, each
// invocation one piece, whose register it shifts to the block's end
// (uShiftBy[t]) before the group xors all 64. The first dispatch's pieces
// are slices of uSliceWords grid words (read into shared memory coalesced,
// CRC'd with the table the host put at regs[0, 256)); further dispatches fold
// the blocks' registers (regs[]) 64 at a time, until one block is the node:
// then ~R is its CRC, written to stats[]. The host hashes the headers and the
// list of node CRCs (nano_grid_builder.cpp). An invocation's loops take
// about 110 iterations in all, whatever the node's size.
layout(local_size_x = 64) in;
#include "gpu_layout.h"
#include "nano_layout.h"

layout(std430, binding = SVO_BIND_NANO_GRID) readonly buffer Grid { uint grid[]; };
layout(std430, binding = SVO_BIND_NANO_STATS) buffer Stats { uint stats[]; };
// The CRC table (256 words), then the blocks' registers; the sort keys' slot, free by this pass.
layout(std430, binding = SVO_BIND_NANO_SORT) buffer Registers { uint regs[]; };

uniform uint uNodeCount;  // nodes of the level
uniform uint uOutPer;     // blocks (work groups) per node in this dispatch
uniform uint uFromGrid;   // 1: pieces are slices of the grid; 0: registers in regs[]
uniform uint uNodeAt;     // grid: the level's first node's word
uniform uint uNodeWords;  // grid: words per node
uniform uint uSliceWords; // grid: words per slice, 1 to 16
uniform uint uInAt;       // registers: the first one's index in regs[]
uniform uint uInPer;      // registers: per node
uniform uint uOutAt;      // where the blocks' registers go in regs[], or (uLast) the CRCs in stats[]
uniform uint uLast;       // 1: one block per node, the node's CRC
uniform uint uShiftBy[64]; // x^(8·piece bytes·(63 - t)) mod P, reflected: piece t to the block's end

const uint kPoly = 0xEDB88320u;

shared uint sTable[256];
shared uint sWords[64 * 17]; // slices at an odd stride: no bank conflicts
shared uint sRegs[64];

// a·b mod P, both reflected (bit 31 is x^0).
uint mulMod(uint a, uint b)
{
    uint p = 0u;
    for (int i = 31; i >= 0; --i) {
        p ^= b & (0u - ((a >> uint(i)) & 1u));
        b = (b >> 1u) ^ (kPoly & (0u - (b & 1u)));
    }
    return p;
}

// The register of this invocation's slice: the block's words staged coalesced, then table CRC from 0.
uint sliceRegister(uint node, uint block, uint t)
{
    for (uint e = t; e < 256u; e += 64u) sTable[e] = regs[e];
    uint s = uSliceWords, stride = s | 1u;
    uint pad = uOutPer * 64u * s - uNodeWords; // zero words before the node
    uint at = uNodeAt + node * uNodeWords;
    uint first = block * 64u * s;
    for (uint k = 0u; k < s; ++k) {
        uint i = k * 64u + t, v = first + i, w = 0u;
        if (v >= pad) {
            w = grid[at + v - pad];
            if (v == pad) w = ~w; // the initial all-ones register
        }
        sWords[(i / s) * stride + i % s] = w;
    }
    barrier();
    uint crc = 0u;
    for (uint k = 0u; k < s; ++k) { // a word's bytes, lowest first (little-endian memory order)
        uint word = sWords[t * stride + k];
        crc = sTable[(crc ^ word) & 0xFFu] ^ (crc >> 8u);
        crc = sTable[(crc ^ (word >> 8u)) & 0xFFu] ^ (crc >> 8u);
        crc = sTable[(crc ^ (word >> 16u)) & 0xFFu] ^ (crc >> 8u);
        crc = sTable[(crc ^ (word >> 24u)) & 0xFFu] ^ (crc >> 8u);
    }
    return crc;
}

void main()
{
    uint t = gl_LocalInvocationID.x;
    uint g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint node = g / uOutPer, block = g % uOutPer;
    if (node >= uNodeCount) return; // the whole group
    uint r;
    if (uFromGrid != 0u) {
        r = sliceRegister(node, block, t);
    } else {
        uint pad = uOutPer * 64u - uInPer; // zero registers before the node's
        uint p = block * 64u + t;
        r = p >= pad ? regs[uInAt + node * uInPer + p - pad] : 0u;
    }
    sRegs[t] = r == 0u ? 0u : mulMod(r, uShiftBy[t]);
    barrier();
    for (uint span = 32u; span > 0u; span >>= 1u) {
        if (t < span) sRegs[t] ^= sRegs[t + span];
        barrier();
    }
    if (t != 0u) return;
    if (uLast != 0u) stats[uOutAt + node] = ~sRegs[0];
    else regs[uOutAt + g] = sRegs[0];
}
