#pragma once
/// @file octree_passes.h (internal)
/// The GPU passes of svo/gl/octree_builder.h, for use on buffers already on
/// the GPU (the raster backend's voxel list).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "svo/gl/buffer.h"
#include "svo/gl/program.h"
#include "voxelize_layout.h"
#include "svo/core/octree.h"
#include "svo/gl/context.h"

namespace svo::gl {

/// The build's counters and indirect dispatch arguments: the same field list
/// (voxelize_layout.h) declares octree_common.glsl's std430 block.
using BuildState = gpu::BuildState;

/// Where the build reads its entries from.
struct OctreeInput {
    const Buffer* entries = nullptr;     ///< uvec2 voxel keys (or brick-origin keys)
    const Buffer* listCounter = nullptr; ///< entry count on the GPU (voxel list), or null
    uint64_t entryCapacity = 0;          ///< entries readable in `entries`
    uint32_t entryCount = 0;             ///< used when listCounter is null
    const Buffer* masks = nullptr;       ///< 16 uints per entry: whole bricks; null: one voxel per entry
};

/// The build passes, with their programs from the context's cache. Use inside a Context::Scope.
class OctreeBuilder {
public:
    explicit OctreeBuilder(const Context& context);

    /// GPU buffers of one build (the context's scratch buffers) and the
    /// counters read back after it.
    struct Build {
        const Buffer *state = nullptr, *nodes = nullptr, *bricks = nullptr;
        const Buffer *bitmap = nullptr, *blocks = nullptr; ///< the bitmap build's, else null
        uint64_t nodeCapacity = 0, brickCapacity = 0;
        bool exactCounts = false; ///< the bitmap build counts every node and brick even past its capacity
        BuildState counts{};
        bool overflowed() const { return counts.nodeCount > nodeCapacity || counts.brickCount > brickCapacity; }
        uint64_t bytes() const
        {
            return state->bytes() + nodes->bytes() + bricks->bytes() + (bitmap ? bitmap->bytes() : 0) +
                   (blocks ? blocks->bytes() : 0);
        }
    };

    /// Allocates the buffers and issues every pass without waiting. Up to
    /// brick level SVO_BUILD_BITMAP_MAX_LEVEL the build marks occupancy
    /// bitmaps and ranks each level's nodes in Morton order (four passes, and
    /// exact node and brick counts even when the capacities are too small);
    /// past it every entry descends from the root, three passes a level. `poll`,
    /// when set, runs between levels (software drivers run the passes as they
    /// are issued, so this is where an interrupter is heard there).
    Build record(const GridSpec& grid, const OctreeInput& input, uint64_t nodeCapacity, uint64_t brickCapacity,
                 const std::function<void()>& poll = {}) const;
    /// Waits for the GPU and reads the counters into build.counts.
    static void readCounts(Build& build);
    /// Reads the finished octree (after readCounts, without overflow).
    static Octree readOctree(const Build& build, const GridSpec& grid);

    /// Upper bound on nodes for at most `bricks` occupied bricks.
    static uint64_t nodeBound(uint32_t brickLevel, uint64_t bricks);
    /// Whether a grid of this brick level is built from bitmaps.
    static bool bitmapBuild(uint32_t brickLevel);
    /// GPU bytes of the bitmap build's own buffers (0 past its levels).
    static uint64_t bitmapBytes(uint32_t brickLevel);

private:
    /// First bitmap block of each level, SVO_BUILD_BITMAP_MAX_LEVEL + 2 entries.
    static std::vector<uint32_t> levelBlocks(uint32_t brickLevel);
    void recordBitmap(Build& b, uint32_t brickLevel, const std::function<void()>& poll) const;
    void recordDescent(Build& b, uint32_t brickLevel, const std::function<void()>& poll) const;

    const Context& context_;
    const Program &prepare_, &fill_; // the others come from the context's cache when a build needs them
};

} // namespace svo::gl
