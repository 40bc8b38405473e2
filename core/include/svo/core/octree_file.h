#pragma once
/// @file octree_file.h
/// @brief The .svo file: one octree, versioned and checksummed.
///
/// Layout, little-endian (x86-64 and every target svo builds for):
///
///   offset  size        field
///   0       128         OctreeFileHeader (below)
///   128     4 (L+2)     levelStart[L+2], uint32      L = brickLevel
///   ...     8 N         nodes[N], OctreeNode        N = nodeCount
///   ...     64 B        bricks[B], Brick            B = brickCount
///   ...     12 V        normals[V], 3 x float       if channels has kNormals (V = voxels)
///   ...     4 V         triangle ids[V], int32      if channels has kTriangles
///   ...     12 V        colours[V], 3 x float       if channels has kColors
///
/// The checksum is 64-bit FNV-1a over the whole file with the checksum field
/// zeroed. Octrees are written in canonicalOrder(), so one voxel set on one
/// grid always gives the same bytes.
#include <cstddef>
#include <cstdint>
#include <string>

#include "svo/core/octree.h"

namespace svo {

/// @brief The first 128 bytes of a .svo file.
struct OctreeFileHeader {
    char magic[8];        ///< "SVOCTREE"
    uint32_t version;     ///< kOctreeFileVersion
    uint32_t headerBytes; ///< sizeof(OctreeFileHeader)
    uint64_t fileBytes;   ///< size of the whole file
    double voxelSize;     ///< GridSpec::voxelSize
    int64_t shift[3];     ///< GridSpec::shift
    int64_t anchor[3];    ///< GridSpec::anchor
    uint32_t dims[3];     ///< GridSpec::dims
    uint32_t brickLevel;  ///< Octree::brickLevel
    uint64_t nodeCount;   ///< Octree::nodes.size()
    uint64_t brickCount;  ///< Octree::bricks.size()
    uint32_t channels;    ///< AttributeChannel bits of the per-voxel arrays that follow the bricks
    uint32_t reserved;    ///< 0
    uint64_t checksum;    ///< FNV-1a of the file with this field zeroed
};
static_assert(sizeof(OctreeFileHeader) == 128);
static_assert(offsetof(OctreeFileHeader, voxelSize) == 24 && offsetof(OctreeFileHeader, dims) == 80);
static_assert(offsetof(OctreeFileHeader, nodeCount) == 96 && offsetof(OctreeFileHeader, channels) == 112);
static_assert(offsetof(OctreeFileHeader, checksum) == 120);

/// @brief The version this svo writes and reads; 2 added the attribute channels.
constexpr uint32_t kOctreeFileVersion = 2;

/// @brief Writes @a octree, in canonicalOrder(), atomically (temporary file,
/// then rename).
/// @throw svo::IoError naming @a path when it cannot be written
void writeOctreeFile(const std::string& path, const Octree& octree);

/// @brief Reads a .svo file, checking magic, version, sizes, checksum, grid
/// (checkGrid) and structure (checkOctree).
/// @throw svo::IoError naming the file and the first problem
Octree readOctreeFile(const std::string& path);

/// @brief Reads a .svo file's bytes from memory, with readOctreeFile's checks.
/// @param name labels errors, as the path does for readOctreeFile
/// @throw svo::IoError naming @a name and the first problem
Octree parseOctree(const void* data, size_t bytes, const std::string& name);

} // namespace svo
