#include "svo/core/field_join.h"

#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo {
namespace {

bool sameGrid(const GridSpec& a, const GridSpec& b)
{
    return a.voxelSize == b.voxelSize && a.shift == b.shift && a.anchor == b.anchor && a.dims == b.dims;
}

void checkJoinable(const DistanceBricks& a, const DistanceBricks& b)
{
    if (a.signedField || b.signedField)
        throw InvalidInput("joinUnsignedFields: a signed field's regions join through their grids, not their bricks");
    if (!sameGrid(a.grid, b.grid)) throw InvalidInput("joinUnsignedFields: the fields are of different grids");
    if (a.closestTriangle != b.closestTriangle)
        throw InvalidInput("joinUnsignedFields: one field has closest triangles and the other not");
    for (const DistanceBricks* f : {&a, &b})
        if (!f->closest.empty() && f->closest.size() != f->distances.size())
            throw InvalidInput("joinUnsignedFields: a field's closest triangles do not match its distances");
}

/// Appends brick @a i of @a from to @a to, with its values.
void appendBrick(DistanceBricks& to, const DistanceBricks& from, size_t i, bool closest)
{
    const size_t first = from.offsets[i], n = from.near[i].count();
    if (to.distances.size() + n > UINT32_MAX)
        throw Unsupported("the joined field holds more than 2^32 distances; use a coarser grid or a narrower band");
    to.bricks.push_back(from.bricks[i]);
    to.near.push_back(from.near[i]);
    to.offsets.push_back(uint32_t(to.distances.size()));
    to.distances.insert(to.distances.end(), from.distances.begin() + std::ptrdiff_t(first),
                        from.distances.begin() + std::ptrdiff_t(first + n));
    if (closest) {
        if (from.closest.empty() && n)
            throw InvalidInput("joinUnsignedFields: a field's closest triangles do not match its distances");
        to.closest.insert(to.closest.end(), from.closest.begin() + std::ptrdiff_t(first),
                          from.closest.begin() + std::ptrdiff_t(first + n));
    }
}

} // namespace

void joinUnsignedFields(DistanceBricks& into, DistanceBricks&& more)
{
    checkJoinable(into, more);
    const bool closest = !into.closest.empty() || !more.closest.empty();
    DistanceBricks out;
    out.grid = into.grid;
    out.signedField = false;
    out.closestTriangle = into.closestTriangle;
    out.region = into.region || more.region;
    out.bricks.reserve(into.bricks.size() + more.bricks.size());
    size_t i = 0, j = 0;
    while (i < into.bricks.size() || j < more.bricks.size()) {
        const bool fromInto = j == more.bricks.size() || (i < into.bricks.size() && into.bricks[i] < more.bricks[j]);
        if (i < into.bricks.size() && j < more.bricks.size() && into.bricks[i] == more.bricks[j])
            throw InvalidInput(fmt::format("joinUnsignedFields: brick ({}, {}, {}) is in both regions",
                                           into.bricks[i][0], into.bricks[i][1], into.bricks[i][2]));
        if (fromInto) appendBrick(out, into, i++, closest);
        else appendBrick(out, more, j++, closest);
    }
    into = std::move(out);
    more = DistanceBricks{};
}

} // namespace svo
