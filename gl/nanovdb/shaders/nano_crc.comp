#version 450 core
// Pass 7, when NanoGridHeader::checksum asks for it: each node's CRC-32 for
// NanoVDB's full checksum (zlib's CRC-32: reflected polynomial 0xEDB88320,
// all bits set before and after), for the nodes of one level.
//
// CRC-32 is linear over GF(2): with R(s) the register after stream s from 0,
// R(A||B) = R(A)·x^(8|B|) mod P xor R(B), zero bytes before a stream leave
// R unchanged, and starting from all bits set equals inverting the stream's
// first four bytes. So each node is seen front-padded with zeros to whole
// blocks of uPieces pieces, and a work group takes 64 / uPieces blocks in
// grid order (small nodes share a group): each invocation one piece, whose
// register it shifts to its block's end (uShiftBy[piece]) before the block
// xors its pieces'. The first dispatch's pieces are slices of uSliceWords
// grid words (the group's words read into shared memory coalesced, CRC'd
// with the table the host put at regs[0, 256)); further dispatches fold the
// blocks' registers (regs[]) 64 at a time, until one block is the node: then
// ~R is its CRC, written to stats[]. The host plans the cuts and hashes the
// headers and the list of node CRCs (nano_grid_builder.cpp). An invocation's
// loops take under 120 iterations in all, whatever the node's size.
layout(local_size_x = 64) in;
#include "gpu_layout.h"
#include "nano_layout.h"

layout(std430, binding = SVO_BIND_NANO_GRID) readonly buffer Grid { uint grid[]; };
layout(std430, binding = SVO_BIND_NANO_STATS) buffer Stats { uint stats[]; };
// The CRC table (256 words), then the blocks' registers; the sort keys' slot, free by this pass.
layout(std430, binding = SVO_BIND_NANO_SORT) buffer Registers { uint regs[]; };

uniform uint uNodeCount;   // nodes of the level
uniform uint uPieces;      // pieces per block, a power of two up to 64
uniform uint uOutPer;      // blocks per node in this dispatch
uniform uint uFromGrid;    // 1: pieces are slices of the grid; 0: registers in regs[]
uniform uint uNodeAt;      // grid: the level's first node's word
uniform uint uNodeWords;   // grid: words per node
uniform uint uSliceWords;  // grid: words per slice, odd, at most 33
uniform uint uInAt;        // registers: the first one's index in regs[]
uniform uint uInPer;       // registers: per node
uniform uint uOutAt;       // where the blocks' registers go in regs[], or (uLast) the CRCs in stats[]
uniform uint uLast;        // 1: one block per node, the node's CRC
uniform uint uShiftBy[64]; // x^(8·piece bytes·(uPieces - 1 - piece)) mod P, reflected: a piece to its block's end

const uint kPoly = 0xEDB88320u;

shared uint sTable[256];
shared uint sWords[64 * 33]; // the group's grid words
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

// The register of one slice (block @a blk's piece @a piece of node @a node,
// if @a live): the group's grid words (blocks b0 to bEnd - 1) staged
// coalesced, then the table CRC from 0.
uint sliceRegister(uint b0, uint bEnd, bool live, uint node, uint blk, uint piece)
{
    uint t = gl_LocalInvocationID.x;
    for (uint e = t; e < 256u; e += 64u) sTable[e] = regs[e];
    uint s = uSliceWords, span = uPieces * s;
    uint pad = uOutPer * span - uNodeWords; // zero words before each node
    // The group's grid words: from its first block's first real word to its last block's end.
    uint first = b0 / uOutPer * uNodeWords + max((b0 % uOutPer) * span, pad) - pad;
    uint end = (bEnd - 1u) / uOutPer * uNodeWords + max(((bEnd - 1u) % uOutPer + 1u) * span, pad) - pad;
    for (uint k = 0u; k < s; ++k) {
        uint i = k * 64u + t;
        if (first + i < end) sWords[i] = grid[uNodeAt + first + i];
    }
    barrier();
    uint crc = 0u;
    if (!live) return crc;
    uint v = (blk * uPieces + piece) * s; // the slice's first word in the padded node
    uint at = node * uNodeWords - first;  // the node's first word in sWords, mod 2^32
    for (uint k = 0u; k < s; ++k, ++v) { // a word's bytes, lowest first (little-endian memory order)
        uint word = 0u;
        if (v >= pad) {
            word = sWords[at + v - pad];
            if (v == pad) word = ~word; // the initial all-ones register
        }
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
    uint blocks = uNodeCount * uOutPer, perGroup = 64u / uPieces;
    uint b0 = g * perGroup;
    if (b0 >= blocks) return; // the whole group
    uint bEnd = min(b0 + perGroup, blocks);
    uint b = b0 + t / uPieces, piece = t % uPieces;
    uint node = b / uOutPer, blk = b % uOutPer;
    bool live = b < bEnd;
    uint r = 0u;
    if (uFromGrid != 0u) {
        r = sliceRegister(b0, bEnd, live, node, blk, piece);
    } else if (live) {
        uint pad = uOutPer * 64u - uInPer; // zero registers before the node's
        uint p = blk * 64u + piece;
        if (p >= pad) r = regs[uInAt + node * uInPer + p - pad];
    }
    uint shift = uShiftBy[piece];
    sRegs[t] = r == 0u || shift == 0x80000000u ? r : mulMod(r, shift); // 0x80000000: x^0
    barrier();
    // Each block xors its pieces: by eights, then the eights (two barriers; llvmpipe's cost much).
    uint eight = min(uPieces, 8u);
    if (piece % eight == 0u)
        for (uint k = 1u; k < eight; ++k) sRegs[t] ^= sRegs[t + k];
    barrier();
    if (piece == 0u)
        for (uint k = 8u; k < uPieces; k += 8u) sRegs[t] ^= sRegs[t + k];
    if (piece != 0u || !live) return;
    if (uLast != 0u) stats[uOutAt + node] = ~sRegs[t];
    else regs[uOutAt + b] = sRegs[t];
}
