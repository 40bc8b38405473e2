#pragma once
// Fields cut into regions (docs/design.md §7e): past a GPU memory budget, or
// past what one shader buffer holds, a field call runs on halves of its box
// until each fits, and joins the halves' results. Private to the front door:
// level_set.cpp joins OpenVDB grids, nanovdb_calls.cpp the fields' and
// solids' bricks (svo/core/field_join.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <optional>
#include <string>
#include <utility>

#include "svo/core/error.h"
#include "svo/core/interrupt.h"
#include "svo/core/region.h"
#include "svo/voxelizer.h"

namespace svo::detail {

/// The grid's index range grown by `pad` voxels, in whole leaves: every
/// voxel a field of the grid holds (its band included) lies inside.
inline IndexBox fieldBox(const GridSpec& grid, int64_t pad)
{
    IndexBox box;
    for (int a = 0; a < 3; ++a) {
        box.lo[a] = floorTo8(grid.anchor[a] - pad);
        box.hi[a] = floorTo8(grid.anchor[a] + int64_t(grid.dims[a]) + pad + 7);
    }
    return box;
}

/// The pad of a level set's field box: its wider band, and a leaf.
inline int64_t levelSetPad(const LevelSetOptions& ls)
{
    return int64_t(std::ceil(std::max(ls.exteriorBand, ls.interiorBand))) + 8;
}

/// The unsigned field whose active voxels are a band of @a band voxels
/// (Voxelizer::band), checked as levelSet() checks its bands.
inline LevelSetOptions bandOptions(double band)
{
    checkBand(band, "band");
    return gl::bandFieldOptions(band);
}

/// The pad of a solid's field box: its 2 voxels, in whole leaves, and a leaf.
constexpr int64_t kSolidPad = 16;

/// Progress across regions: each region's run reports on its share of the
/// call, its columns' share of the box's (regions cut the box in x and y
/// only), after the regions done, so the percentage climbs once over all of
/// them instead of starting again in each.
class RegionProgress {
public:
    RegionProgress(const Checkpoint& checkpoint, const IndexBox& box) : checkpoint_(checkpoint), columns_(columns(box)) {}

    /// The checkpoint of @a region's run.
    Checkpoint of(const IndexBox& region) const
    {
        return checkpoint_.part(done_ / columns_, (done_ + columns(region)) / columns_);
    }
    void finished(const IndexBox& region) { done_ += columns(region); }

private:
    static double columns(const IndexBox& b) { return double(b.hi[0] - b.lo[0]) * double(b.hi[1] - b.lo[1]); }

    Checkpoint checkpoint_;
    double columns_, done_ = 0.0;
};

/// `run(box, checkpoint)` on `box`, or, where a GPU memory budget cannot hold
/// that, on its two halves across its wider x or y side (z columns stay
/// whole: parity counts along them), joined by `join(first, second)`; each
/// region is exactly the whole grid's there, so the join is the whole grid's result.
template <typename Run, typename Join>
auto inRegions(Run& run, Join& join, const IndexBox& box, uint32_t& tiles, RegionProgress& progress)
    -> decltype(run(box, progress.of(box)))
{
    try {
        auto out = run(box, progress.of(box));
        progress.finished(box);
        ++tiles;
        return out;
    } catch (const OutOfMemory&) {
        const int axis = box.hi[0] - box.lo[0] >= box.hi[1] - box.lo[1] ? 0 : 1;
        const int64_t leaves = (box.hi[axis] - box.lo[axis]) / 8;
        if (leaves < 2) throw; // one column of leaves: nothing smaller to try
        IndexBox first = box, second = box;
        first.hi[axis] = second.lo[axis] = box.lo[axis] + 8 * (leaves / 2);
        auto out = inRegions(run, join, first, tiles, progress);
        auto more = inRegions(run, join, second, tiles, progress);
        join(out, std::move(more));
        return out;
    }
}

/// inRegions over all of `box`, on `checkpoint`'s range; `tiles` counts the
/// regions. A region cut smaller after a try reports again from its start:
/// monotonic() holds the percentage where the try left it.
template <typename Run, typename Join>
auto allRegions(Run& run, Join& join, const IndexBox& box, const Checkpoint& checkpoint, uint32_t& tiles)
    -> decltype(run(box, checkpoint))
{
    RegionProgress progress(checkpoint.monotonic(), box);
    return inRegions(run, join, box, tiles, progress);
}

/// The warning of a call cut into @a regions because one shader buffer
/// cannot hold its field (BufferLimit): no budget asked for the cut.
inline std::string pastOneBufferWarning(uint32_t regions)
{
    return fmt::format("one GPU buffer does not hold the whole grid's field: computed in {} regions and joined",
                       regions);
}

/// `run(region, checkpoint)` on the call's region (none: the whole grid);
/// past a GPU memory budget, or past what one shader buffer holds (with a
/// warning), in regions of `box` (or of the call's region) that fit, each
/// on its share of `checkpoint`; `stats.tiles` says how many.
template <typename Run, typename Join>
auto withinBudget(Run&& run, Join&& join, const VoxelizeOptions& options, const IndexBox& box,
                  const Checkpoint& checkpoint, VoxelizeStats& stats) -> decltype(run(options.region, checkpoint))
{
    const Checkpoint progress = checkpoint.monotonic(); // the regions retry what the first try began
    bool pastOneBuffer = false;
    try {
        return run(options.region, progress);
    } catch (const BufferLimit&) {
        pastOneBuffer = true; // a driver's per-buffer limit: smaller regions fit, budget or not
    } catch (const OutOfMemory&) {
        if (!options.gpuMemory) throw; // only a budget the grid can be cut for
    }
    uint32_t tiles = 0;
    auto out = allRegions(run, join, options.region ? *options.region : box, progress, tiles);
    stats.tiles = tiles;
    if (pastOneBuffer) stats.warnings.push_back(pastOneBufferWarning(tiles));
    return out;
}

} // namespace svo::detail
