// Distance fields and solids on bricks as OpenVDB grids (svo/vdb_io/field_grids.h).
#include "svo/vdb_io/field_grids.h"

#include <memory>
#include <openvdb/tools/SignedFloodFill.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <unordered_map>

namespace svo::vdb {
namespace {

openvdb::Coord leafOrigin(const GridSpec& grid, const BrickCoord& b)
{
    return openvdb::Coord(int32_t(grid.anchor[0] + 8 * int64_t(b[0])), int32_t(grid.anchor[1] + 8 * int64_t(b[1])),
                          int32_t(grid.anchor[2] + 8 * int64_t(b[2])));
}

bool bitOf(const Brick& b, uint32_t bit) { return (b.words[bit >> 6] >> (bit & 63)) & 1u; }

/// Adds whole bricks (the grid's brick coordinates) as tiles of `value`:
/// where all 16³ leaves of a level-1 node (128³ voxels) are bricks of the
/// list, one tile for the node, else one leaf-sized tile per brick, so that
/// a solid's interior costs time and memory in proportion to its surface.
template <typename TreeT>
void addBrickTiles(TreeT& tree, const GridSpec& grid, const std::vector<BrickCoord>& bricks,
                   const typename TreeT::ValueType& value, bool active)
{
    using Level1 = typename TreeT::RootNodeType::ChildNodeType::ChildNodeType;
    constexpr uint32_t kFull = (Level1::DIM / 8) * (Level1::DIM / 8) * (Level1::DIM / 8);
    auto nodeOf = [&](const BrickCoord& b) { return leafOrigin(grid, b) & ~(int32_t(Level1::DIM) - 1); };
    std::unordered_map<openvdb::Coord, uint32_t> count; // the list's bricks per level-1 node
    for (const BrickCoord& b : bricks) ++count[nodeOf(b)];
    for (const auto& [origin, n] : count)
        if (n == kFull) tree.addTile(2, origin, value, active); // a tile of the level-2 node: 128³ voxels
    for (const BrickCoord& b : bricks)
        if (count[nodeOf(b)] != kFull) tree.addTile(1, leafOrigin(grid, b), value, active);
}

/// Parity: fills the runs of whole bricks inside with `value`; a run is one
/// box where all 64 columns of its brick column are inside.
template <typename TreeT>
void fillRuns(TreeT& tree, const GridSpec& grid, const std::vector<InsideRun>& runs,
              const typename TreeT::ValueType& value, bool active)
{
    for (const auto& run : runs) {
        const openvdb::Coord lo = leafOrigin(grid, run.first);
        const int32_t top = lo.z() + 8 * int32_t(run.bricks) - 1;
        if (run.columns == ~uint64_t(0)) {
            tree.fill(openvdb::CoordBBox(lo, openvdb::Coord(lo.x() + 7, lo.y() + 7, top)), value, active);
            continue;
        }
        for (uint32_t c = 0; c < 64; ++c)
            if ((run.columns >> c) & 1u) {
                const openvdb::Coord a(lo.x() + int32_t(c / 8), lo.y() + int32_t(c % 8), lo.z());
                tree.fill(openvdb::CoordBBox(a, openvdb::Coord(a.x(), a.y(), top)), value, active);
            }
    }
}

/// Adds leaves made in parallel (null: none) to a tree, in order.
template <typename TreeT>
void addLeaves(TreeT& tree, std::vector<typename TreeT::LeafNodeType*>& leaves)
{
    for (auto* leaf : leaves)
        if (leaf) tree.addLeaf(leaf);
}

} // namespace

openvdb::GridPtrVec levelSetGrids(const DistanceBricks& field, double exteriorBand, double interiorBand,
                                  double worldPerVoxel, openvdb::math::Transform::Ptr xform)
{
    const GridSpec& g = field.grid;
    const bool signedField = field.signedField, winding = field.winding;
    // Where no flood fill runs (winding, a parity field's region), a band
    // brick's inside values are kept even when none of its voxels is active:
    // a brick of the band's list wholly inside lies in no parity run.
    const bool keepInside = winding || (signedField && field.region);
    const FieldSigns& signs = field.signs;
    const float exterior = float(exteriorBand), interior = float(interiorBand);
    const float background = float(exteriorBand * worldPerVoxel);
    auto distance = openvdb::FloatGrid::create(background);
    auto closest = field.closestTriangle ? openvdb::Int32Grid::create(-1) : nullptr;
    const size_t nb = field.bricks.size();
    std::vector<openvdb::FloatTree::LeafNodeType*> leaves(nb, nullptr);
    std::vector<openvdb::Int32Tree::LeafNodeType*> closestLeaves(nb, nullptr);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nb, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const openvdb::Coord origin = leafOrigin(g, field.bricks[i]);
            const Brick& near = field.near[i];
            const bool anyInside = signedField && signs.inside[i].count();
            // Parity's flood fill signs inactive leaves from their neighbours;
            // elsewhere a leaf with no active voxel is kept when it holds inside values.
            if (!near.count() && !(keepInside && anyInside)) continue;
            auto leaf = std::make_unique<openvdb::FloatTree::LeafNodeType>(origin, background);
            std::unique_ptr<openvdb::Int32Tree::LeafNodeType> c;
            if (closest) c = std::make_unique<openvdb::Int32Tree::LeafNodeType>(origin, -1);
            bool any = false;
            size_t packed = field.offsets[i]; // the next near voxel's value
            for (uint32_t v = 0; v < 512; ++v) {
                const bool inside = signedField && bitOf(signs.inside[i], v);
                float value = background;
                if (bitOf(near, v)) {
                    const float d = field.distances[packed];
                    if (d < (inside ? interior : exterior)) {
                        value = float(double(d) * worldPerVoxel);
                        leaf->setValueOn(v);
                        if (c) c->setValueOn(v, field.closest[packed]);
                        any = true;
                    }
                    ++packed;
                }
                leaf->setValueOnly(v, inside ? -value : value);
            }
            if (!any && !(keepInside && anyInside)) continue;
            if (c && any) closestLeaves[i] = c.release();
            leaves[i] = leaf.release();
        }
    });
    addLeaves(distance->tree(), leaves);
    if (closest) addLeaves(closest->tree(), closestLeaves);
    distance->setTransform(xform);
    if (winding) {
        // Beyond the band: inactive values, negative where the winding number says inside.
        for (const auto& [b, m] : signs.partial) {
            auto* leaf = distance->tree().touchLeaf(leafOrigin(g, b));
            for (uint32_t v = 0; v < 512; ++v)
                if (bitOf(m, v)) leaf->setValueOnly(v, -background);
        }
        addBrickTiles(distance->tree(), g, signs.insideBricks, -background, false);
        distance->tree().prune();
    } else if (signedField && field.region) {
        // A region's band is cut at its sides, so a flood fill would guess
        // beyond them; the parity runs say what the whole grid's fill says.
        fillRuns(distance->tree(), g, signs.runs, -background, false);
        distance->tree().prune();
    } else if (signedField) {
        openvdb::tools::signedFloodFill(distance->tree());
    }
    if (signedField) {
        distance->setGridClass(openvdb::GRID_LEVEL_SET);
        distance->setName("surface");
    } else {
        distance->setGridClass(openvdb::GRID_UNKNOWN);
        distance->setName("distance");
    }
    openvdb::GridPtrVec out{distance};
    if (closest) {
        closest->setTransform(xform->copy());
        closest->setName("closest_triangle");
        out.push_back(closest);
    }
    return out;
}

openvdb::MaskGrid::Ptr bandGrid(const DistanceBricks& field, double band, openvdb::math::Transform::Ptr xform)
{
    // The unsigned field's grid says which voxels are nearer than the band;
    // its topology is the band's.
    const openvdb::GridBase::Ptr distance = levelSetGrids(field, band, band, 1.0, xform).front();
    auto out = openvdb::MaskGrid::create(false);
    out->tree().topologyUnion(openvdb::gridPtrCast<openvdb::FloatGrid>(distance)->tree());
    out->setTransform(xform);
    out->setName("band");
    return out;
}

openvdb::MaskGrid::Ptr solidGrid(const SolidBricks& solid, openvdb::math::Transform::Ptr xform)
{
    const GridSpec& g = solid.grid;
    const FieldSigns& signs = solid.signs;
    auto out = openvdb::MaskGrid::create(false);
    const size_t nb = solid.bricks.size();
    std::vector<openvdb::MaskTree::LeafNodeType*> leaves(nb, nullptr);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nb, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const Brick& m = signs.inside[i];
            if (!m.count()) continue;
            auto leaf = std::make_unique<openvdb::MaskTree::LeafNodeType>(leafOrigin(g, solid.bricks[i]), false);
            for (uint32_t v = 0; v < 512; ++v)
                if (bitOf(m, v)) leaf->setValueOn(v);
            leaves[i] = leaf.release();
        }
    });
    addLeaves(out->tree(), leaves);
    // Winding: bricks beyond the band, voxel by voxel or whole.
    for (const auto& [b, m] : signs.partial) {
        auto* leaf = out->tree().touchLeaf(leafOrigin(g, b));
        for (uint32_t v = 0; v < 512; ++v)
            if (bitOf(m, v)) leaf->setValueOn(v);
    }
    addBrickTiles(out->tree(), g, signs.insideBricks, true, true);
    fillRuns(out->tree(), g, signs.runs, true, true);
    out->tree().prune(); // full leaves and nodes become tiles at the largest level they fill
    out->setTransform(xform);
    out->setName("solid");
    return out;
}

} // namespace svo::vdb
