#version 450 core
// Pass 7, when NanoGridHeader::checksum asks for it: each node's CRC-32 for
// NanoVDB's full checksum (zlib's CRC-32: reflected polynomial 0xEDB88320,
// all bits set before and after), an invocation per node of one level, over
// words [uFrom, uTo) of it in this dispatch (a driver's loop limit cuts a
// large node into several), the running value kept in the statistics buffer
// (whose statistics the host has read by then). The host hashes the headers
// and the list of node CRCs (nano_grid_builder.cpp).
layout(local_size_x = 64) in;
#include "nano_common.glsl"

uniform uint uNodeAt;    // the level's first node's word in the grid
uniform uint uNodeWords; // words per node
uniform uint uNodeCount; // nodes of the level
uniform uint uSumAt;     // the level's first CRC in stats[]
uniform uint uFrom;      // this dispatch's words of each node: [uFrom, uTo)
uniform uint uTo;
uniform uint uFirst;     // 1: the node's first words (start from all bits set)
uniform uint uLast;      // 1: the node's last words (invert the result)

shared uint sTable[256];

void main()
{
    uint t = gl_LocalInvocationID.x;
    for (uint e = t; e < 256u; e += 64u) {
        uint c = e;
        for (uint k = 0u; k < 8u; ++k) c = (c & 1u) != 0u ? 0xEDB88320u ^ (c >> 1u) : c >> 1u;
        sTable[e] = c;
    }
    barrier();
    uint i = groupIndex() * 64u + t;
    if (i >= uNodeCount) return;
    uint crc = uFirst != 0u ? 0xFFFFFFFFu : stats[uSumAt + i];
    uint at = uNodeAt + i * uNodeWords;
    for (uint w = uFrom; w < uTo; ++w) { // a word's bytes, lowest first (little-endian memory order)
        uint word = grid[at + w];
        crc = sTable[(crc ^ word) & 0xFFu] ^ (crc >> 8u);
        crc = sTable[(crc ^ (word >> 8u)) & 0xFFu] ^ (crc >> 8u);
        crc = sTable[(crc ^ (word >> 16u)) & 0xFFu] ^ (crc >> 8u);
        crc = sTable[(crc ^ (word >> 24u)) & 0xFFu] ^ (crc >> 8u);
    }
    stats[uSumAt + i] = uLast != 0u ? ~crc : crc;
}
