#include "svo/vdb_io/grid_builder.h"

#include <tbb/parallel_for.h>

#include "svo/core/voxel_key.h"

namespace svo::vdb {
namespace {

/// [begin, end) ranges of keys that share a brick.
std::vector<std::pair<size_t, size_t>> brickRuns(const std::vector<uint64_t>& keys)
{
    std::vector<std::pair<size_t, size_t>> runs;
    size_t start = 0;
    for (size_t i = 1; i <= keys.size(); ++i)
        if (i == keys.size() || brickOfKey(keys[i]) != brickOfKey(keys[start])) {
            runs.emplace_back(start, i);
            start = i;
        }
    return runs;
}

template <typename GridT, typename FillLeaf>
typename GridT::Ptr buildGrid(const Voxelization& v, typename GridT::ValueType background, FillLeaf&& fill)
{
    using LeafT = typename GridT::TreeType::LeafNodeType;
    const auto runs = brickRuns(v.keys);
    std::vector<LeafT*> leaves(runs.size(), nullptr);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, runs.size(), 64), [&](const auto& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const auto [b, e] = runs[i];
            const auto local = unpackVoxelKey(v.keys[b]);
            const auto g = v.grid.toGlobal({local[0] & ~7u, local[1] & ~7u, local[2] & ~7u});
            auto* leaf = new LeafT(openvdb::Coord(int32_t(g[0]), int32_t(g[1]), int32_t(g[2])), background, false);
            for (size_t k = b; k < e; ++k) fill(*leaf, openvdb::Index(v.keys[k] & 511));
            leaves[i] = leaf;
        }
    });
    auto grid = GridT::create(background);
    auto& tree = grid->tree();
    for (LeafT* leaf : leaves) tree.addLeaf(leaf); // the tree takes ownership
    grid->setTransform(makeTransform(v.grid));
    return grid;
}

} // namespace

openvdb::math::Transform::Ptr makeTransform(const GridSpec& grid)
{
    auto xform = openvdb::math::Transform::createLinearTransform(grid.voxelSize);
    const auto t = grid.translation();
    if (t[0] != 0 || t[1] != 0 || t[2] != 0) xform->postTranslate(openvdb::Vec3d(t[0], t[1], t[2]));
    return xform;
}

openvdb::MaskGrid::Ptr buildMaskGrid(const Voxelization& voxels)
{
    return buildGrid<openvdb::MaskGrid>(voxels, false, [](auto& leaf, openvdb::Index n) { leaf.setValueOn(n); });
}

openvdb::FloatGrid::Ptr buildFogGrid(const Voxelization& voxels)
{
    auto grid = buildGrid<openvdb::FloatGrid>(voxels, 0.0f, [](auto& leaf, openvdb::Index n) { leaf.setValueOn(n, 1.0f); });
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    return grid;
}

} // namespace svo::vdb
