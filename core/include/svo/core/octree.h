#pragma once
/// @file octree.h
/// The linear sparse voxel octree: its memory layout, a CPU reference build,
/// traversal, and the structural checks every producer must pass.
///
/// Layout (docs/octree.md has the diagram):
///   - `nodes` is one array, level by level: the root is nodes[0]. An internal
///     node (level < brickLevel) whose `childMask` is non-zero points to a block
///     of 8 contiguous nodes at the next level, child c = x + 2y + 4z.
///   - Nodes at level `brickLevel` stand for 8^3 bricks. An occupied one has
///     childMask 1 and `child` indexes `bricks`.
///   - A brick is 8 x uint64 in OpenVDB LeafNode<T,3> bit order, so a brick
///     becomes a leaf's value mask, and a leaf mask a brick, by a copy.
///   - No positions are stored: traversal gives every brick's origin.
///   - The root covers the smallest power-of-two cube of bricks holding the
///     grid's local range [0, dims), so brickLevel = ceil(log2(max brick dim)).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "svo/core/enum_names.h"
#include <vector>

#include "svo/core/gpu_layout.h"
#include "svo/core/grid.h"
#include "svo/core/vec3.h"

namespace svo {

struct OctreeNode {
    uint32_t child = 0;     ///< first of 8 children (internal) or brick index (brick level)
    uint32_t childMask = 0; ///< bit c: child c occupied (internal); 1 if occupied (brick level)
};
static_assert(sizeof(OctreeNode) == 8 && alignof(OctreeNode) == 4);
static_assert(offsetof(OctreeNode, childMask) == 4);
static_assert(sizeof(OctreeNode) == gpu::kNodeWords * 4); // the shaders' view (gpu_layout.h)

struct Brick {
    uint64_t words[8] = {}; ///< bit (x&7)<<6 | (y&7)<<3 | (z&7), as OpenVDB's NodeMask<3>
    bool operator==(const Brick& o) const;
    uint32_t count() const;
};
static_assert(sizeof(Brick) == 64 && sizeof(Brick) == gpu::kBrickWords * 4);

/// A child pointer that could not be allocated (GPU capacity overflow). Never
/// present in a finished octree. The shaders write it (gpu_layout.h).
constexpr uint32_t kNoChild = gpu::kNoChild;

/// Optional per-voxel channels. Each is empty (not asked for, or the input
/// lacks it) or holds one value per voxel, in voxel order: bricks in index
/// order, and within a brick by bit index (brickVoxelOffsets gives where each
/// brick starts).
struct VoxelAttributes {
    std::vector<Vec3f> normals;     ///< unit average of the covering triangles' normals (0 where they cancel or all are degenerate)
    std::vector<int32_t> triangles; ///< smallest index of a covering triangle
    std::vector<Vec3f> colors;      ///< average of the covering triangles' mean vertex colours
    bool empty() const { return normals.empty() && triangles.empty() && colors.empty(); }
    bool operator==(const VoxelAttributes& o) const;
};

/// Bit flags naming channels (CLI --attributes, .svo header).
enum AttributeChannel : uint32_t { kNormals = 1, kTriangles = 2, kColors = 4 };
/// The channels' names, as --attributes and Python's attributes= take them.
inline constexpr EnumName<AttributeChannel> kAttributeChannelNames[] = {
    {kNormals, "normal"}, {kTriangles, "triangle"}, {kColors, "color"}};
constexpr const auto& enumNames(AttributeChannel) { return kAttributeChannelNames; }

/// What ran to make a result, kept with it so that the files written from it
/// say so (svo:backend, svo:mode, svo:renderer, svo:sign grid metadata). Empty
/// fields for results read from files or assembled by hand.
struct Provenance {
    std::string backend;  ///< "raster", "compute" or "cpu"
    std::string mode;     ///< "conservative" or "thin"; empty where nothing was voxelized
    std::string renderer; ///< the GL renderer, or "cpu"
};

struct Octree {
    GridSpec grid;
    uint32_t brickLevel = 0; ///< levels 0 (root) .. brickLevel (bricks)
    std::vector<OctreeNode> nodes;
    /// levelStart[l] is the first node of level l; levelStart[brickLevel + 1] == nodes.size().
    std::vector<uint32_t> levelStart;
    std::vector<Brick> bricks;
    VoxelAttributes attributes;
    Provenance madeBy; ///< set by svo::Voxelizer; not part of the voxels (sameOctree ignores it)

    uint64_t voxelCount() const;
    uint32_t channels() const;
    uint64_t bytes() const;
};

/// Where each brick's voxels start in voxel order; one more entry than bricks.
std::vector<uint64_t> brickVoxelOffsets(const Octree& octree);

/// Levels above the bricks that a grid needs: ceil(log2(max(ceil(dims/8)))).
uint32_t brickLevelFor(const GridSpec& grid);

/// Reference build from voxel keys (voxel_key.h; any order, duplicates fine).
/// Children blocks and bricks are laid out in breadth-first Morton order, the
/// canonical order that canonicalOrder() gives any octree.
Octree buildOctree(const GridSpec& grid, const std::vector<uint64_t>& keys);

/// Reference build from whole bricks keyed by brick origin (key with low 9 bits 0).
/// Bricks with equal keys are OR-ed; empty bricks are dropped.
Octree buildOctreeFromBricks(const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> bricks);

/// The same octree relaid out breadth-first with children in order, bricks in
/// the order their nodes appear. Two octrees of one voxel set and one grid are
/// equal after this, whatever order their builder allocated in.
Octree canonicalOrder(const Octree& octree);

bool sameOctree(const Octree& a, const Octree& b); ///< grid, levels, nodes, bricks and attributes equal

/// One occupied brick: local origin (multiples of 8) and index into bricks.
struct BrickRef {
    std::array<uint32_t, 3> origin;
    uint32_t index;
};
/// Every occupied brick, in traversal (Morton) order.
std::vector<BrickRef> occupiedBricks(const Octree& octree);

/// The voxel keys of an octree, sorted (brick-major) and unique.
std::vector<uint64_t> octreeKeys(const Octree& octree);

/// Structural problems, empty when the octree is sound: level ranges, child
/// pointers in range and 8-aligned inside the next level, every node and brick
/// referenced exactly once (no orphans), each mask equal to the OR of its
/// children's occupancy, no empty brick, no brick outside the grid's range,
/// attribute channels empty or one value per voxel.
/// At most `limit` messages.
std::vector<std::string> checkOctree(const Octree& octree, size_t limit = 20);

struct OctreeStats {
    std::vector<uint64_t> nodesPerLevel;         ///< allocated node slots
    std::vector<uint64_t> occupiedPerLevel;      ///< of which occupied
    uint64_t bricks = 0, voxels = 0, bytes = 0;
    double bytesPerVoxel() const { return voxels ? double(bytes) / double(voxels) : 0.0; }
    double fillRatio() const { return bricks ? double(voxels) / (512.0 * double(bricks)) : 0.0; }
};
OctreeStats octreeStats(const Octree& octree);

} // namespace svo
