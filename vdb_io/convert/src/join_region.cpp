#include "svo/vdb_io/join_region.h"

#include <openvdb/openvdb.h>

#include "svo/core/error.h"

namespace svo::vdb {
namespace {

/// Sets in @a into every tile of @a node and of the internal nodes below it
/// that is active or not background, at its own level. A node's own entries
/// are walked (its child mask's off bits), not the tree's value iterator,
/// which costs several times as much per entry (a level set's lower nodes
/// hold 4,096 entries each, nearly all of them background).
template <typename NodeT, typename TreeT>
void setTilesOf(const NodeT& node, TreeT& into, const typename TreeT::ValueType& background)
{
    for (auto tile = node.cbeginValueAll(); tile; ++tile)
        if (tile.isValueOn() || !openvdb::math::isExactlyEqual(*tile, background))
            into.addTile(NodeT::LEVEL, tile.getCoord(), *tile, tile.isValueOn());
    if constexpr (NodeT::LEVEL > 1)
        for (auto child = node.cbeginChildOn(); child; ++child) setTilesOf(*child, into, background);
}

template <typename GridT>
void joinInto(GridT& into, GridT& part)
{
    if (!openvdb::math::isExactlyEqual(into.background(), part.background()))
        throw InvalidInput("joinRegion: the grids have different backgrounds");
    // A grid read with OpenVDB's delayed loading (a tile file, a pickled
    // grid) fills its leaves on first touch, taking their inactive values
    // from the grid it was read into: the part's leaves leave that grid, so
    // read them now. The target's stay where they are (reading them at every
    // join would walk the growing grid once per part).
    part.tree().readNonresidentBuffers();
    if (into.tree().empty()) { // the first region (only background tiles so far): take its tree whole
        into.setTree(part.treePtr());
        part.newTree();
        return;
    }
    setTilesOf(part.tree().root(), into.tree(), part.background());
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
