#include "svo/core/region.h"

#include <algorithm>
#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo {

void checkRegion(const IndexBox& r, const std::string& name)
{
    for (int a = 0; a < 3; ++a) {
        if (r.lo[a] >= r.hi[a] || r.lo[a] % 8 != 0 || r.hi[a] % 8 != 0)
            throw InvalidInput(name, fmt::format("({}, {}, {}) to ({}, {}, {}): a region is [lo, hi) with lo < hi on "
                                                 "each axis and every bound a multiple of 8 (whole leaves)",
                                                 r.lo[0], r.lo[1], r.lo[2], r.hi[0], r.hi[1], r.hi[2]));
    }
}

IndexBox regionFrom(const std::array<int64_t, 6>& b, const std::string& name)
{
    const IndexBox r{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    checkRegion(r, name);
    return r;
}

VoxelBox localBox(const GridSpec& grid, const IndexBox& r)
{
    VoxelBox box;
    for (int a = 0; a < 3; ++a) {
        const int64_t lo = std::clamp<int64_t>(r.lo[a] - grid.anchor[a], 0, grid.dims[a]);
        const int64_t hi = std::clamp<int64_t>(r.hi[a] - grid.anchor[a], lo, grid.dims[a]);
        box.lo[a] = uint32_t(lo);
        box.hi[a] = uint32_t(hi);
    }
    return box;
}

VoxelBox wholeBox(const GridSpec& grid) { return VoxelBox{{0, 0, 0}, grid.dims}; }

BrickBox bricksMeeting(const GridSpec& grid, const std::optional<IndexBox>& region)
{
    const VoxelBox box = region ? localBox(grid, *region) : wholeBox(grid);
    BrickBox bricks;
    for (int a = 0; a < 3; ++a) {
        bricks.lo[a] = box.lo[a] / 8;
        bricks.hi[a] = std::max(bricks.lo[a], (box.hi[a] + 7) / 8);
    }
    return withinGrid(grid, bricks);
}

BrickBox withinGrid(const GridSpec& grid, const BrickBox& box)
{
    BrickBox out;
    for (int a = 0; a < 3; ++a) {
        out.hi[a] = std::min(box.hi[a], (grid.dims[a] + 7) / 8);
        out.lo[a] = std::min(box.lo[a], out.hi[a]);
    }
    return out;
}

} // namespace svo
