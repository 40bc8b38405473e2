#include "svo/core/field_join.h"

#include <algorithm>
#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo {
namespace {

bool sameGrid(const GridSpec& a, const GridSpec& b)
{
    return a.voxelSize == b.voxelSize && a.shift == b.shift && a.anchor == b.anchor && a.dims == b.dims;
}

[[noreturn]] void inBoth(const char* what, const BrickCoord& b)
{
    throw InvalidInput(fmt::format("{}: brick ({}, {}, {}) is in both regions", what, b[0], b[1], b[2]));
}

/// Calls `take(fromB, index)` for the bricks of two sorted lists in the
/// order of their union.
template <typename Take>
void inBrickOrder(const std::vector<BrickCoord>& a, const std::vector<BrickCoord>& b, const char* what, Take&& take)
{
    size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (i < a.size() && j < b.size() && a[i] == b[j]) inBoth(what, a[i]);
        if (j == b.size() || (i < a.size() && a[i] < b[j])) take(false, i++);
        else take(true, j++);
    }
}

/// @a a and @a b's items together, sorted by their brick (`brickOf`); no
/// brick twice.
template <typename T, typename BrickOf>
std::vector<T> unionOf(std::vector<T>& a, std::vector<T>& b, BrickOf&& brickOf, const char* what)
{
    std::vector<T> out = std::move(a);
    out.insert(out.end(), std::make_move_iterator(b.begin()), std::make_move_iterator(b.end()));
    const auto less = [&](const T& x, const T& y) { return brickOf(x) < brickOf(y); };
    std::sort(out.begin(), out.end(), less);
    const auto same = std::adjacent_find(out.begin(), out.end(), [&](const T& x, const T& y) { return !less(x, y); });
    if (same != out.end()) inBoth(what, brickOf(*same));
    return out;
}

/// The signs beyond the band of two regions: parity's runs, winding's
/// inside and partly inside bricks. The band's inside voxels go brick by
/// brick with the bricks.
void joinBeyondBand(FieldSigns& out, FieldSigns& a, FieldSigns& b, const char* what)
{
    out.runs = unionOf(a.runs, b.runs, [](const InsideRun& r) { return r.first; }, what);
    out.insideBricks = unionOf(a.insideBricks, b.insideBricks, [](const BrickCoord& c) { return c; }, what);
    out.partial = unionOf(a.partial, b.partial, [](const std::pair<BrickCoord, Brick>& p) { return p.first; }, what);
    out.openColumns = a.openColumns + b.openColumns;
}

/// Whether signed signs (@a hasSigns) hold an inside mask per band brick.
void checkSigns(const FieldSigns& s, size_t bricks, bool hasSigns, const char* what)
{
    if (hasSigns ? s.inside.size() != bricks : !s.inside.empty())
        throw InvalidInput(fmt::format("{}: a field's inside voxels do not match its bricks", what));
}

constexpr const char* kFields = "joinFields";

void checkJoinable(const DistanceBricks& a, const DistanceBricks& b)
{
    if (!sameGrid(a.grid, b.grid)) throw InvalidInput("joinFields: the fields are of different grids");
    if (a.signedField != b.signedField || (a.signedField && a.winding != b.winding))
        throw InvalidInput("joinFields: the fields are of different kinds (signed or not, by winding or parity)");
    if (a.closestTriangle != b.closestTriangle)
        throw InvalidInput("joinFields: one field has closest triangles and the other not");
    for (const DistanceBricks* f : {&a, &b}) {
        if (f->near.size() != f->bricks.size() || f->offsets.size() != f->bricks.size())
            throw InvalidInput("joinFields: a field's masks or offsets do not match its bricks");
        if (!f->closest.empty() && f->closest.size() != f->distances.size())
            throw InvalidInput("joinFields: a field's closest triangles do not match its distances");
        checkSigns(f->signs, f->bricks.size(), f->signedField, kFields);
    }
}

/// Appends brick @a i of @a from to @a to, with its values and inside voxels.
void appendBrick(DistanceBricks& to, const DistanceBricks& from, size_t i, bool closest)
{
    const size_t first = from.offsets[i], n = from.near[i].count();
    if (first + n > from.distances.size())
        throw InvalidInput("joinFields: a field's distances do not match its masks");
    if (to.distances.size() + n > UINT32_MAX)
        throw Unsupported("the joined field holds more than 2^32 distances; use a coarser grid or a narrower band");
    to.bricks.push_back(from.bricks[i]);
    to.near.push_back(from.near[i]);
    to.offsets.push_back(uint32_t(to.distances.size()));
    to.distances.insert(to.distances.end(), from.distances.begin() + std::ptrdiff_t(first),
                        from.distances.begin() + std::ptrdiff_t(first + n));
    if (closest) {
        if (from.closest.empty() && n)
            throw InvalidInput("joinFields: a field's closest triangles do not match its distances");
        to.closest.insert(to.closest.end(), from.closest.begin() + std::ptrdiff_t(first),
                          from.closest.begin() + std::ptrdiff_t(first + n));
    }
    if (from.signedField) to.signs.inside.push_back(from.signs.inside[i]);
}

} // namespace

void joinFields(DistanceBricks& into, DistanceBricks&& more)
{
    checkJoinable(into, more);
    const bool closest = !into.closest.empty() || !more.closest.empty();
    DistanceBricks out;
    out.grid = into.grid;
    out.signedField = into.signedField;
    out.winding = into.winding;
    out.closestTriangle = into.closestTriangle;
    out.region = into.region || more.region;
    out.bricks.reserve(into.bricks.size() + more.bricks.size());
    inBrickOrder(into.bricks, more.bricks, kFields,
                 [&](bool fromMore, size_t i) { appendBrick(out, fromMore ? more : into, i, closest); });
    joinBeyondBand(out.signs, into.signs, more.signs, kFields);
    into = std::move(out);
    more = DistanceBricks{};
}

void joinSolids(SolidBricks& into, SolidBricks&& more)
{
    constexpr const char* what = "joinSolids";
    if (!sameGrid(into.grid, more.grid)) throw InvalidInput("joinSolids: the solids are of different grids");
    checkSigns(into.signs, into.bricks.size(), true, what);
    checkSigns(more.signs, more.bricks.size(), true, what);
    SolidBricks out;
    out.grid = into.grid;
    out.bricks.reserve(into.bricks.size() + more.bricks.size());
    out.signs.inside.reserve(out.bricks.capacity());
    inBrickOrder(into.bricks, more.bricks, what, [&](bool fromMore, size_t i) {
        const SolidBricks& from = fromMore ? more : into;
        out.bricks.push_back(from.bricks[i]);
        out.signs.inside.push_back(from.signs.inside[i]);
    });
    joinBeyondBand(out.signs, into.signs, more.signs, what);
    into = std::move(out);
    more = SolidBricks{};
}

} // namespace svo
