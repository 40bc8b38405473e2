#pragma once
/// @file octree.h
/// @brief The linear sparse voxel octree: its memory layout, a CPU reference build,
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

/// @brief One node: a child block or a brick, and which children are occupied.
struct OctreeNode {
    uint32_t child = 0;     ///< first of 8 children (internal) or brick index (brick level)
    uint32_t childMask = 0; ///< bit c: child c occupied (internal); 1 if occupied (brick level)
};
static_assert(sizeof(OctreeNode) == 8 && alignof(OctreeNode) == 4);
static_assert(offsetof(OctreeNode, childMask) == 4);
static_assert(sizeof(OctreeNode) == gpu::kNodeWords * 4); // the shaders' view (gpu_layout.h)

/// @brief An 8^3 block of voxel bits, laid out as an OpenVDB leaf's value mask.
struct Brick {
    uint64_t words[8] = {}; ///< bit (x&7)<<6 | (y&7)<<3 | (z&7), as OpenVDB's NodeMask<3>
    /// @brief Whether the two hold the same voxels.
    bool operator==(const Brick& o) const;
    /// @brief The number of voxels set.
    uint32_t count() const;
};
static_assert(sizeof(Brick) == 64 && sizeof(Brick) == gpu::kBrickWords * 4);

/// @brief A child pointer that could not be allocated (GPU capacity overflow). Never
/// present in a finished octree. The shaders write it (gpu_layout.h).
constexpr uint32_t kNoChild = gpu::kNoChild;

/// @brief Optional per-voxel channels. Each is empty (not asked for, the input
/// lacks it, or no voxel holds it) or holds one value per voxel, in voxel
/// order: bricks in index order, and within a brick by bit index
/// (brickVoxelOffsets gives where each brick starts).
struct VoxelAttributes {
    std::vector<Vec3f> normals;     ///< unit average of the covering triangles' normals (0 where they cancel or all are degenerate)
    std::vector<int32_t> triangles; ///< smallest index of a covering triangle
    std::vector<Vec3f> colors;      ///< average of the covering triangles' mean vertex colours
    /// AttributeChannel bits of the channels computed, kept where no voxel
    /// holds a value (an empty region's result), so that its files have the
    /// same grids as any other region's.
    uint32_t computed = 0;
    /// @brief Whether no voxel holds a channel value.
    bool empty() const { return normals.empty() && triangles.empty() && colors.empty(); }
    /// @brief The AttributeChannel bits of the channels computed or holding values.
    uint32_t channels() const;
    /// @brief Whether the channels and every value are equal.
    bool operator==(const VoxelAttributes& o) const;
};

/// @brief Bit flags naming channels (CLI --attributes, .svo header).
enum AttributeChannel : uint32_t { kNormals = 1, kTriangles = 2, kColors = 4 };
/// The channels' names, as --attributes and Python's attributes= take them.
inline constexpr EnumName<AttributeChannel> kAttributeChannelNames[] = {
    {kNormals, "normal"}, {kTriangles, "triangle"}, {kColors, "color"}};
constexpr const auto& enumNames(AttributeChannel) { return kAttributeChannelNames; }

/// @brief What ran to make a result, kept with it so that the files written from it
/// say so (svo:backend, svo:mode, svo:renderer, svo:sign grid metadata). Empty
/// fields for results read from files or assembled by hand.
struct Provenance {
    std::string backend;  ///< "raster", "compute" or "cpu"
    std::string mode;     ///< "conservative" or "thin"; empty where nothing was voxelized
    std::string renderer; ///< the GL renderer, or "cpu"
};

/// @brief The octree: nodes level by level, bricks, and optional channels
/// (see the file comment for the layout).
struct Octree {
    GridSpec grid;                 ///< the grid whose local coordinates the octree covers
    uint32_t brickLevel = 0; ///< levels 0 (root) .. brickLevel (bricks)
    std::vector<OctreeNode> nodes; ///< level by level; the root is nodes[0]
    /// levelStart[l] is the first node of level l; levelStart[brickLevel + 1] == nodes.size().
    std::vector<uint32_t> levelStart;
    std::vector<Brick> bricks;     ///< indexed by the brick-level nodes' `child`
    VoxelAttributes attributes;    ///< per-voxel channels, in voxel order
    Provenance madeBy; ///< set by svo::Voxelizer; not part of the voxels (sameOctree ignores it)

    /// @brief The voxels set in all bricks.
    uint64_t voxelCount() const;
    /// @brief The AttributeChannel bits of the channels held (VoxelAttributes::channels).
    uint32_t channels() const;
    /// @brief The bytes of nodes, bricks and channels in memory.
    uint64_t bytes() const;
};

/// @brief Where each brick's voxels start in voxel order.
/// @return one more entry than bricks: the last is the voxel count
std::vector<uint64_t> brickVoxelOffsets(const Octree& octree);

/// @brief Levels above the bricks that a grid needs: ceil(log2(max(ceil(dims/8)))).
uint32_t brickLevelFor(const GridSpec& grid);

/// @brief The CPU reference build from voxel keys. Children blocks and bricks
/// are laid out in breadth-first Morton order, the canonical order that
/// canonicalOrder() gives any octree.
/// @param keys local voxel keys (voxel_key.h), in any order, duplicates fine
/// @throw svo::InvalidInput for a key outside the grid
/// @throw svo::Unsupported for an octree beyond 32-bit node or brick indices
Octree buildOctree(const GridSpec& grid, const std::vector<uint64_t>& keys);

/// @brief The CPU reference build from whole bricks. Bricks with equal keys
/// are OR-ed; empty bricks are dropped.
/// @param bricks (brick-origin key, mask) pairs: keys with their low 9 bits 0
/// @throw as buildOctree
Octree buildOctreeFromBricks(const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> bricks);

/// @brief The same octree relaid out breadth-first with children in order, bricks in
/// the order their nodes appear. Two octrees of one voxel set and one grid are
/// equal after this, whatever order their builder allocated in.
Octree canonicalOrder(const Octree& octree);

/// @brief Whether grid, levels, nodes, bricks and attributes are equal
/// (Octree::madeBy is not compared).
bool sameOctree(const Octree& a, const Octree& b);

/// @brief One occupied brick: local origin and index into bricks.
struct BrickRef {
    std::array<uint32_t, 3> origin; ///< local, multiples of 8
    uint32_t index;                 ///< into Octree::bricks
};
/// @brief Every occupied brick, in traversal (Morton) order.
std::vector<BrickRef> occupiedBricks(const Octree& octree);

/// @brief Every occupied brick as an 8³ leaf of index space, in traversal
/// (Morton) order: what a sparse grid's builder takes.
struct OctreeLeaves {
    std::vector<std::array<int32_t, 3>> origins; ///< global index coordinates, multiples of 8
    std::vector<Brick> masks;                    ///< the brick's voxels, one bit each
};
/// @brief The octree's occupied bricks as leaves (occupiedBricks, made global).
OctreeLeaves octreeLeaves(const Octree& octree);

/// @brief The voxel keys of an octree, sorted (brick-major) and unique.
std::vector<uint64_t> octreeKeys(const Octree& octree);

/// @brief The structural checks every producer must pass: level ranges, child
/// pointers in range and 8-aligned inside the next level, every node and brick
/// referenced exactly once (no orphans), each mask equal to the OR of its
/// children's occupancy, no empty brick, no brick outside the grid's range,
/// attribute channels empty or one value per voxel. Throws nothing but
/// std::bad_alloc.
/// @param limit the most messages to return
/// @return one message per problem; empty when the octree is sound
std::vector<std::string> checkOctree(const Octree& octree, size_t limit = 20);

/// @brief An octree's size, level by level.
struct OctreeStats {
    std::vector<uint64_t> nodesPerLevel;         ///< allocated node slots
    std::vector<uint64_t> occupiedPerLevel;      ///< of which occupied
    uint64_t bricks = 0, voxels = 0, bytes = 0;  ///< bytes: Octree::bytes()
    /// @brief Bytes per voxel; 0 for no voxels.
    double bytesPerVoxel() const { return voxels ? double(bytes) / double(voxels) : 0.0; }
    /// @brief The share of the bricks' 512 voxels that are set; 0 for no bricks.
    double fillRatio() const { return bricks ? double(voxels) / (512.0 * double(bricks)) : 0.0; }
};
/// @brief Counts an octree's nodes, bricks, voxels and bytes.
OctreeStats octreeStats(const Octree& octree);

} // namespace svo
