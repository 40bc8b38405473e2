#include "svo/core/parity_scan.h"

#include <algorithm>
#include <tuple>
#include <fmt/format.h>
#include <numeric>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "svo/core/error.h"

namespace svo {
namespace {

/// Bit z of the result is the XOR of bits 0..z of b: the parity at each voxel
/// of one column from the marks below and at it.
uint8_t prefixXor(uint8_t b)
{
    b ^= uint8_t(b << 1);
    b ^= uint8_t(b << 2);
    b ^= uint8_t(b << 4);
    return b;
}

} // namespace

ParityScan scanParity(const std::vector<std::array<uint32_t, 3>>& bricks, const std::vector<Brick>& crossings)
{
    if (bricks.size() != crossings.size())
        throw InvalidInput(fmt::format("scanParity: {} bricks but {} crossing masks", bricks.size(), crossings.size()));
    ParityScan out;
    out.inside.resize(bricks.size());
    // Bricks of one brick column together, going up in z (callers usually
    // pass them sorted so already).
    const auto less = [&](uint32_t a, uint32_t b) {
        const auto &p = bricks[a], &q = bricks[b];
        return std::tie(p[0], p[1], p[2]) < std::tie(q[0], q[1], q[2]);
    };
    std::vector<uint32_t> order(bricks.size());
    std::iota(order.begin(), order.end(), 0u);
    if (!std::is_sorted(order.begin(), order.end(), less)) tbb::parallel_sort(order.begin(), order.end(), less);
    const auto sameColumn = [&](size_t n) {
        return n > 0 && bricks[order[n - 1]][0] == bricks[order[n]][0] && bricks[order[n - 1]][1] == bricks[order[n]][1];
    };
    std::vector<size_t> columnStart;
    for (size_t n = 0; n < order.size(); ++n)
        if (!sameColumn(n)) columnStart.push_back(n);
    columnStart.push_back(order.size());

    // Columns are independent: scanned in parallel parts, whose runs are
    // then joined in order, so the result is the serial scan's.
    struct Part {
        std::vector<InsideRun> runs;
        uint64_t openColumns = 0;
    };
    const size_t columns = columnStart.size() - 1;
    std::vector<Part> parts(std::min<size_t>(columns, 1024));
    tbb::parallel_for(size_t(0), parts.size(), [&](size_t k) {
        Part& part = parts[k];
        for (size_t c = k * columns / parts.size(); c < (k + 1) * columns / parts.size(); ++c) {
            uint64_t parity = 0; // per voxel column (bit x * 8 + y): inside below the current brick
            for (size_t n = columnStart[c]; n < columnStart[c + 1]; ++n) {
                const uint32_t i = order[n];
                const auto& b = bricks[i];
                if (n > columnStart[c] && parity && bricks[order[n - 1]][2] + 1 < b[2]) {
                    const auto& below = bricks[order[n - 1]];
                    part.runs.push_back({{b[0], b[1], below[2] + 1}, b[2] - below[2] - 1, parity});
                }
                // Columns are bytes of the brick: word x, byte y, bit z.
                for (uint32_t x = 0; x < 8; ++x) {
                    uint64_t word = 0;
                    for (uint32_t y = 0; y < 8; ++y) {
                        const uint8_t marks = uint8_t(crossings[i].words[x] >> (8 * y));
                        const uint32_t bit = x * 8 + y;
                        const bool in = (parity >> bit) & 1u;
                        const uint8_t inside = uint8_t(prefixXor(marks) ^ (in ? 0xFFu : 0u));
                        word |= uint64_t(inside) << (8 * y);
                        if (__builtin_popcount(marks) & 1) parity ^= uint64_t(1) << bit;
                    }
                    out.inside[i].words[x] = word;
                }
            }
            part.openColumns += uint64_t(__builtin_popcountll(parity));
        }
    });
    for (Part& part : parts) {
        out.runs.insert(out.runs.end(), part.runs.begin(), part.runs.end());
        out.openColumns += part.openColumns;
    }
    return out;
}

} // namespace svo
