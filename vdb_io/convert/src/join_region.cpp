#include "svo/vdb_io/join_region.h"

#include <openvdb/openvdb.h>

#include "svo/core/error.h"

namespace svo::vdb {
namespace {

template <typename GridT>
void joinInto(GridT& into, GridT& part)
{
    using TreeT = typename GridT::TreeType;
    if (!openvdb::math::isExactlyEqual(into.background(), part.background()))
        throw InvalidInput("joinRegion: the grids have different backgrounds");
    // A grid read with OpenVDB's delayed loading (a pickled one, from a Dask
    // worker) fills its leaves on first touch, taking their inactive values
    // from the grid it was read into: read them now, while that grid lives.
    into.tree().readNonresidentBuffers();
    part.tree().readNonresidentBuffers();
    const auto background = part.background();
    auto tile = part.tree().cbeginValueAll();
    tile.setMaxDepth(TreeT::ValueAllCIter::LEAF_DEPTH - 1); // tiles only: leaves move whole below
    for (; tile; ++tile) {
        if (!tile.isValueOn() && openvdb::math::isExactlyEqual(*tile, background)) continue;
        into.tree().addTile(tile.getLevel(), tile.getCoord(), *tile, tile.isValueOn());
    }
    into.tree().merge(part.tree(), openvdb::MERGE_NODES);
}

template <typename GridT>
bool joinAs(openvdb::GridBase& into, openvdb::GridBase& part)
{
    auto* a = dynamic_cast<GridT*>(&into);
    if (!a) return false;
    joinInto(*a, dynamic_cast<GridT&>(part));
    return true;
}

} // namespace

void joinRegion(openvdb::GridBase& into, openvdb::GridBase& part)
{
    if (into.type() != part.type())
        throw InvalidInput("joinRegion: a " + part.type() + " grid cannot join a " + into.type() + " grid");
    if (!joinAs<openvdb::BoolGrid>(into, part) && !joinAs<openvdb::MaskGrid>(into, part) &&
        !joinAs<openvdb::FloatGrid>(into, part) && !joinAs<openvdb::Int32Grid>(into, part) &&
        !joinAs<openvdb::Vec3SGrid>(into, part))
        throw InvalidInput("joinRegion: grids of type " + into.type() + " are not joined");
}

} // namespace svo::vdb
