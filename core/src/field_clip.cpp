#include "svo/core/field_clip.h"

#include <algorithm>

namespace svo {
namespace {

bool inside(const BrickBox& box, const BrickCoord& b)
{
    for (int a = 0; a < 3; ++a)
        if (b[a] < box.lo[a] || b[a] >= box.hi[a]) return false;
    return true;
}

/// The runs cut to the box: along z to its range, and left out past its x and y.
void clipRuns(std::vector<InsideRun>& runs, const BrickBox& box)
{
    std::vector<InsideRun> kept;
    for (InsideRun r : runs) {
        const uint32_t lo = std::max(r.first[2], box.lo[2]), hi = std::min(r.first[2] + r.bricks, box.hi[2]);
        BrickCoord first = r.first;
        first[2] = lo;
        if (lo >= hi || !inside(box, first)) continue;
        r.first = first;
        r.bricks = hi - lo;
        kept.push_back(r);
    }
    runs = std::move(kept);
}

/// The signs beyond the band cut to the box.
void clipBeyondBand(FieldSigns& signs, const BrickBox& box)
{
    clipRuns(signs.runs, box);
    auto& whole = signs.insideBricks;
    whole.erase(std::remove_if(whole.begin(), whole.end(), [&](const BrickCoord& b) { return !inside(box, b); }),
                whole.end());
    auto& partial = signs.partial;
    partial.erase(std::remove_if(partial.begin(), partial.end(), [&](const auto& p) { return !inside(box, p.first); }),
                  partial.end());
}

} // namespace

void clipField(DistanceBricks& field, const BrickBox& box)
{
    const bool signs = field.signedField && field.signs.inside.size() == field.bricks.size();
    const bool closest = !field.closest.empty();
    // New value arrays: a brick's values may lie anywhere in the old ones
    // (the GPU packs bricks in the order its work groups finish).
    std::vector<float> distances;
    std::vector<int32_t> nearest;
    size_t kept = 0;
    for (size_t i = 0; i < field.bricks.size(); ++i) {
        if (!inside(box, field.bricks[i])) continue;
        const auto first = std::ptrdiff_t(field.offsets[i]), n = std::ptrdiff_t(field.near[i].count());
        field.bricks[kept] = field.bricks[i];
        field.near[kept] = field.near[i];
        field.offsets[kept] = uint32_t(distances.size());
        if (signs) field.signs.inside[kept] = field.signs.inside[i];
        distances.insert(distances.end(), field.distances.begin() + first, field.distances.begin() + first + n);
        if (closest) nearest.insert(nearest.end(), field.closest.begin() + first, field.closest.begin() + first + n);
        ++kept;
    }
    field.bricks.resize(kept);
    field.near.resize(kept);
    field.offsets.resize(kept);
    field.distances = std::move(distances);
    field.closest = std::move(nearest);
    if (signs) field.signs.inside.resize(kept);
    clipBeyondBand(field.signs, box);
}

void clipSolid(SolidBricks& solid, const BrickBox& box)
{
    const bool signs = solid.signs.inside.size() == solid.bricks.size();
    size_t kept = 0;
    for (size_t i = 0; i < solid.bricks.size(); ++i) {
        if (!inside(box, solid.bricks[i])) continue;
        solid.bricks[kept] = solid.bricks[i];
        if (signs) solid.signs.inside[kept] = solid.signs.inside[i];
        ++kept;
    }
    solid.bricks.resize(kept);
    if (signs) solid.signs.inside.resize(kept);
    clipBeyondBand(solid.signs, box);
}

} // namespace svo
