#pragma once
// The index of a brick in a list, by its coordinates: the CPU field passes'
// counterpart of the GPU's brick table (internal to core).
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/parallel_sort.h>

namespace svo {

class BrickIndex {
public:
    static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

    /// @param limit the grid's box in bricks (brick coordinates < limit)
    BrickIndex(const std::vector<std::array<uint32_t, 3>>& bricks, const std::array<uint32_t, 3>& limit)
        : limit_(limit)
    {
        const uint64_t cells = uint64_t(limit[0]) * limit[1] * limit[2];
        // A dense table up to 2^25 cells (128 MiB) finds a brick in one load;
        // beyond, a sorted list and a binary search.
        if (cells <= (uint64_t(1) << 25)) {
            dense_.assign(cells, kNone);
            for (uint32_t i = 0; i < bricks.size(); ++i) dense_[cell(bricks[i])] = i;
        } else {
            sorted_.reserve(bricks.size());
            for (uint32_t i = 0; i < bricks.size(); ++i) sorted_.push_back({bricks[i], i});
            tbb::parallel_sort(sorted_.begin(), sorted_.end());
        }
    }

    /// The brick's index in the list, or kNone.
    uint32_t find(const std::array<uint32_t, 3>& b) const
    {
        if (b[0] >= limit_[0] || b[1] >= limit_[1] || b[2] >= limit_[2]) return kNone;
        if (!dense_.empty()) return dense_[cell(b)];
        const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(b, uint32_t(0)));
        return it != sorted_.end() && it->first == b ? it->second : kNone;
    }

private:
    uint64_t cell(const std::array<uint32_t, 3>& b) const { return (uint64_t(b[0]) * limit_[1] + b[1]) * limit_[2] + b[2]; }

    std::array<uint32_t, 3> limit_;
    std::vector<uint32_t> dense_;
    std::vector<std::pair<std::array<uint32_t, 3>, uint32_t>> sorted_;
};

} // namespace svo
