#include "svo/vdb_io/grid_builder.h"

#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <algorithm>
#include <memory>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "svo/core/error.h"
#include "svo/core/voxel_key.h"
#include "svo/vdb_io/vdb_file.h"

namespace svo::vdb {
namespace {

static_assert(sizeof(Brick) == openvdb::util::NodeMask<3>::WORD_COUNT * sizeof(openvdb::util::NodeMask<3>::Word));

/// Builds the tree in parallel: the bricks, in the octree's Morton order, are
/// cut into one contiguous run per thread; each run fills a tree of its own
/// through an accessor (neighbouring leaves share their path, so the descent
/// is cached), and the trees are merged by moving nodes. Inserting leaf by
/// leaf from the root was the serial bottleneck (4 ms of 9 for 56,000
/// leaves on 2 cores).
template <typename GridT, typename FillLeaf>
typename GridT::Ptr buildGrid(const Octree& o, typename GridT::ValueType background, FillLeaf&& fill)
{
    using TreeT = typename GridT::TreeType;
    using LeafT = typename TreeT::LeafNodeType;
    const std::vector<BrickRef> refs = occupiedBricks(o);
    const size_t runs = std::clamp<size_t>(refs.size() / 1024, 1, size_t(tbb::this_task_arena::max_concurrency()));
    std::vector<std::unique_ptr<TreeT>> parts(runs);
    tbb::parallel_for(size_t(0), runs, [&](size_t run) {
        auto tree = std::make_unique<TreeT>(background);
        openvdb::tree::ValueAccessor<TreeT> acc(*tree);
        for (size_t i = refs.size() * run / runs, end = refs.size() * (run + 1) / runs; i < end; ++i) {
            const auto g = o.grid.toGlobal(refs[i].origin);
            auto* leaf = new LeafT(openvdb::Coord(int32_t(g[0]), int32_t(g[1]), int32_t(g[2])), background, false);
            fill(*leaf, refs[i]);
            acc.addLeaf(leaf); // the tree takes ownership
        }
        parts[run] = std::move(tree);
    });
    auto grid = GridT::create(background);
    auto& tree = grid->tree();
    for (auto& part : parts) tree.merge(*part, openvdb::MERGE_NODES); // bricks are disjoint: nodes move
    grid->setTransform(makeTransform(o.grid));
    return grid;
}

template <typename LeafT>
void copyMask(LeafT& leaf, const Brick& b)
{
    auto& mask = leaf.getValueMask();
    for (openvdb::Index w = 0; w < 8; ++w) mask.template getWord<uint64_t>(w) = b.words[w];
}

} // namespace

void checkVdbVoxelSize(double voxelSize, const std::string& what)
{
    // The product, as ScaleMap forms it, decides; kMinVoxelSize is its cube root.
    if (!(voxelSize * voxelSize * voxelSize >= 3e-15))
        throw InvalidInput(fmt::format("{}: voxel size {:.6g} is below the smallest an OpenVDB transform takes ({:.6g}, as "
                                       "its scale map needs voxel size^3 >= 3e-15); scale the mesh up, use a coarser grid, "
                                       "or write .svo",
                                       what, voxelSize, kMinVoxelSize));
}

namespace {
openvdb::math::Transform::Ptr buildTransform(const GridSpec& grid, const std::string& what)
{
    checkVdbVoxelSize(grid.voxelSize, what);
    auto xform = openvdb::math::Transform::createLinearTransform(grid.voxelSize);
    const auto t = grid.translation();
    try {
        if (t[0] != 0 || t[1] != 0 || t[2] != 0) xform->postTranslate(openvdb::Vec3d(t[0], t[1], t[2]));
        // Copying a grid rebuilds its transform from the map's matrix
        // (Transform(MapBase::Ptr) simplifies it), as the writer does.
        openvdb::math::Transform copy(xform->baseMap()->copy());
    } catch (const openvdb::Exception& e) {
        throw InvalidInput(fmt::format("{}: the grid lies {:.3g} from the origin, {:.3g} voxels of {:.6g}: farther than an "
                                       "OpenVDB transform holds ({}); move the mesh nearer the origin, use a coarser grid, "
                                       "or write .svo",
                                       what, std::max({std::abs(t[0]), std::abs(t[1]), std::abs(t[2])}),
                                       std::max({std::abs(t[0]), std::abs(t[1]), std::abs(t[2])}) / grid.voxelSize,
                                       grid.voxelSize, e.what()));
    }
    return xform;
}
} // namespace

void checkVdbGrid(const GridSpec& grid, const std::string& what) { buildTransform(grid, what); }

openvdb::math::Transform::Ptr makeTransform(const GridSpec& grid) { return buildTransform(grid, "grid"); }

openvdb::MaskGrid::Ptr buildMaskGrid(const Octree& o)
{
    return buildGrid<openvdb::MaskGrid>(o, false, [&](auto& leaf, const BrickRef& r) { copyMask(leaf, o.bricks[r.index]); });
}

openvdb::BoolGrid::Ptr buildBoolGrid(const Octree& o)
{
    // Bool leaves keep values apart from the mask: active voxels are true.
    return buildGrid<openvdb::BoolGrid>(o, false, [&](auto& leaf, const BrickRef& r) {
        copyMask(leaf, o.bricks[r.index]);
        for (auto it = leaf.cbeginValueOn(); it; ++it) leaf.setValueOnly(it.pos(), true);
    });
}

openvdb::FloatGrid::Ptr buildFogGrid(const Octree& o)
{
    auto grid = buildGrid<openvdb::FloatGrid>(o, 0.0f, [&](auto& leaf, const BrickRef& r) {
        copyMask(leaf, o.bricks[r.index]);
        for (auto it = leaf.cbeginValueOn(); it; ++it) leaf.setValueOnly(it.pos(), 1.0f);
    });
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    return grid;
}

openvdb::GridPtrVec buildAttributeGrids(const Octree& o)
{
    openvdb::GridPtrVec grids;
    const auto offsets = brickVoxelOffsets(o);
    // Values in voxel order: the n-th set bit of a brick is its n-th value.
    auto build = [&](auto background, const auto& values, auto convert, const char* name) {
        using Value = decltype(background);
        using GridT = openvdb::Grid<typename openvdb::tree::Tree4<Value, 5, 4, 3>::Type>;
        auto grid = buildGrid<GridT>(o, background, [&](auto& leaf, const BrickRef& r) {
            copyMask(leaf, o.bricks[r.index]);
            uint64_t at = offsets[r.index];
            for (auto it = leaf.cbeginValueOn(); it; ++it) leaf.setValueOnly(it.pos(), convert(values[at++]));
        });
        grid->setName(name);
        grids.push_back(grid);
        return grid;
    };
    auto vec = [](const Vec3f& v) { return openvdb::Vec3s(v.x, v.y, v.z); };
    // Every channel computed, an empty grid where no voxel holds it.
    const uint32_t channels = o.channels();
    if (channels & kNormals) {
        auto g = build(openvdb::Vec3s(0, 0, 0), o.attributes.normals, vec, "normal");
        g->setVectorType(openvdb::VEC_COVARIANT_NORMALIZE);
    }
    if (channels & kTriangles) build(int32_t(-1), o.attributes.triangles, [](int32_t t) { return t; }, "triangle_id");
    if (channels & kColors) build(openvdb::Vec3s(0, 0, 0), o.attributes.colors, vec, "color");
    return grids;
}

openvdb::GridPtrVec octreeToGrids(const Octree& octree, const GridOptions& options,
                                  openvdb::math::Transform::ConstPtr xform)
{
    openvdb::GridPtrVec grids;
    if (options.topology == GridOptions::Topology::Bool) grids.push_back(buildBoolGrid(octree));
    else grids.push_back(buildMaskGrid(octree));
    grids.back()->setName(options.name);
    if (options.fog) {
        grids.push_back(buildFogGrid(octree));
        grids.back()->setName("density");
    }
    if (options.attributes)
        for (auto& g : buildAttributeGrids(octree)) grids.push_back(g);
    if (xform)
        for (auto& g : grids) g->setTransform(xform->copy());
    for (auto& g : grids) tagProvenance(*g, octree.madeBy);
    return grids;
}

void tagProvenance(openvdb::GridBase& grid, const Provenance& madeBy)
{
    const std::pair<const char*, const std::string*> fields[] = {
        {"svo:backend", &madeBy.backend}, {"svo:mode", &madeBy.mode}, {"svo:renderer", &madeBy.renderer}};
    for (const auto& [key, value] : fields)
        if (!value->empty()) grid.insertMeta(key, openvdb::StringMetadata(validUtf8(*value)));
}

GridBricks gridToBricks(const openvdb::GridBase& base, const std::string& name, uint64_t maxTileBricks)
{
    // Transform: uniform linear scale plus a whole-voxel translation.
    const auto& xform = base.constTransform();
    const auto map = xform.baseMap();
    const openvdb::Vec3d vs = xform.voxelSize();
    bool diagonal = xform.isLinear();
    if (diagonal) {
        const openvdb::Mat4d m = map->getAffineMap()->getMat4();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                if (r != c ? m(r, c) != 0.0 : !(m(r, c) > 0.0)) diagonal = false;
    }
    if (!diagonal)
        throw InvalidInput(fmt::format("{}: grid '{}' has a {} transform; svo needs scaling plus translation", name,
                                       base.getName(), map->type()));
    if (!(vs[0] > 0) || std::abs(vs[1] - vs[0]) > 1e-12 * vs[0] || std::abs(vs[2] - vs[0]) > 1e-12 * vs[0])
        throw InvalidInput(fmt::format("{}: grid '{}' has non-uniform voxel size ({}, {}, {})", name, base.getName(), vs[0],
                                       vs[1], vs[2]));
    GridBricks out;
    out.grid.voxelSize = vs[0];
    const openvdb::Vec3d t = xform.indexToWorld(openvdb::Vec3d(0, 0, 0));
    for (int a = 0; a < 3; ++a) {
        const double s = t[a] / vs[0];
        const double r = std::round(s);
        if (std::abs(s - r) > 1e-6)
            throw InvalidInput(fmt::format("{}: grid '{}' is translated by {} voxels along {}, not a whole number; svo's "
                                           "octrees sit on whole-voxel lattices",
                                           name, base.getName(), s, "xyz"[a]));
        if (!(std::abs(r) < 9.0e18))
            throw InvalidInput(fmt::format("{}: grid '{}' is translated by {:.3g} voxels along {}, beyond 64-bit indices",
                                           name, base.getName(), r, "xyz"[a]));
        out.grid.shift[a] = int64_t(r);
    }

    const bool typed = base.apply<GridTypes>([&](const auto& grid) {
        const auto& tree = grid.tree();
        openvdb::CoordBBox bbox;
        if (!tree.evalActiveVoxelBoundingBox(bbox)) {
            out.grid.dims = {1, 1, 1};
            return;
        }
        for (int a = 0; a < 3; ++a) {
            const int64_t lo = bbox.min()[a];
            out.grid.anchor[a] = floorTo8(lo);
            const int64_t dim = int64_t(bbox.max()[a]) - out.grid.anchor[a] + 1;
            if (dim > int64_t(kMaxGridDim))
                throw InvalidInput(fmt::format("{}: grid '{}' spans {} voxels along {}, beyond the supported {}", name,
                                               base.getName(), dim, "xyz"[a], kMaxGridDim));
            out.grid.dims[a] = uint32_t(dim);
        }
        auto keyAt = [&](const openvdb::Coord& c) {
            return packVoxelKey(uint32_t(c[0] - out.grid.anchor[0]), uint32_t(c[1] - out.grid.anchor[1]),
                                uint32_t(c[2] - out.grid.anchor[2]));
        };
        out.bricks.reserve(tree.leafCount());
        for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
            Brick b;
            const auto& mask = leaf->getValueMask();
            for (openvdb::Index w = 0; w < 8; ++w) b.words[w] = mask.template getWord<uint64_t>(w);
            if (b.count()) out.bricks.emplace_back(keyAt(leaf->origin()), b);
        }
        // Active tiles (above the leaf level) become full bricks.
        Brick full;
        std::fill(full.words, full.words + 8, ~uint64_t(0));
        // Count first: a few large tiles can stand for more bricks than memory holds.
        auto it = tree.cbeginValueOn();
        it.setMaxDepth(it.getLeafDepth() - 1);
        uint64_t tileBricks = 0;
        for (auto counter = it; counter; ++counter)
            if (counter.isTileValue()) tileBricks += counter.getBoundingBox().volume() / 512;
        if (tileBricks > maxTileBricks)
            throw InvalidInput(fmt::format("{}: grid '{}' has active tiles covering {} bricks ({:.1f} G voxels), more than "
                                           "svo expands",
                                           name, base.getName(), tileBricks, double(tileBricks) * 512 / 1e9));
        out.bricks.reserve(out.bricks.size() + tileBricks);
        for (; it; ++it) {
            if (!it.isTileValue()) continue;
            const openvdb::CoordBBox tile = it.getBoundingBox();
            ++out.tilesExpanded;
            for (int64_t x = tile.min()[0]; x <= tile.max()[0]; x += 8)
                for (int64_t y = tile.min()[1]; y <= tile.max()[1]; y += 8)
                    for (int64_t z = tile.min()[2]; z <= tile.max()[2]; z += 8)
                        out.bricks.emplace_back(keyAt(openvdb::Coord(int32_t(x), int32_t(y), int32_t(z))), full);
        }
    });
    if (!typed)
        throw InvalidInput(fmt::format("{}: grid '{}' has type {}, which svo does not read (it reads bool, mask, float, "
                                       "double, int32, int64 and vec3 grids)",
                                       name, base.getName(), base.type()));
    checkGrid(out.grid, name);
    return out;
}

} // namespace svo::vdb
