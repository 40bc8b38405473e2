// Level sets, unsigned distance fields and solids (svo/voxelizer.h): the
// surface voxels give the band's bricks, the GPU gives distances and parity
// crossings there (svo/gl/distance_field.h), and OpenVDB holds the result.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <openvdb/tools/SignedFloodFill.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "svo/core/error.h"
#include "svo/core/mesh_topology.h"
#include "svo/core/parity_scan.h"
#include "svo/gl/distance_field.h"
#include "svo/vdb_io/grid_builder.h"
#include "voxelizer_state.h"

namespace svo {
namespace {

using detail::Clock;
using detail::InterruptScope;
using detail::msSince;
using BrickCoord = std::array<uint32_t, 3>;

/// The grid grown by `pad` voxels on every side (the anchor kept a multiple
/// of 8), so that a band around the mesh lies inside its local range.
GridSpec padded(const GridSpec& grid, uint32_t pad, const std::string& what)
{
    GridSpec g = grid;
    for (int a = 0; a < 3; ++a) {
        g.anchor[a] = floorTo8(grid.anchor[a] - int64_t(pad));
        const uint64_t dims = uint64_t(grid.anchor[a] - g.anchor[a]) + grid.dims[a] + pad;
        if (dims > kMaxGridDim)
            throw Error(fmt::format("{}: the grid with its band is {} voxels wide, more than svo's {}", what, dims,
                                    kMaxGridDim));
        g.dims[a] = uint32_t(dims);
    }
    checkGrid(g, what);
    return g;
}

/// Which sign method a call uses, and why (for the statistics).
std::string chooseSign(const TriangleMesh& mesh, SignMethod asked, std::vector<std::string>& warnings)
{
    const EdgeReport edges = checkEdges(mesh);
    if (edges.closedAndOriented()) return "parity: the mesh is " + edges.describe();
    if (asked == SignMethod::Auto)
        throw Error(fmt::format("{}: not closed ({}), so inside and outside are not defined by parity; svo has no "
                                "sign method for open meshes yet. Use --udf (unsigned distances), or --sign parity "
                                "to use parity anyway",
                                mesh.source, edges.describe()));
    warnings.push_back(fmt::format("{} is not closed ({}): parity signs may be wrong", mesh.source, edges.describe()));
    return "parity: as asked (the mesh is not closed)";
}

/// The bricks holding every voxel within `reach` voxels (Chebyshev) of an
/// occupied voxel of the octree: each brick's occupied box grown by reach.
std::vector<BrickCoord> grownBricks(const Octree& octree, uint32_t reach)
{
    const auto refs = occupiedBricks(octree);
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (octree.grid.dims[a] + 7) / 8 - 1;
    std::vector<std::vector<BrickCoord>> parts(refs.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, refs.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t n = r.begin(); n != r.end(); ++n) {
            const Brick& m = octree.bricks[refs[n].index];
            std::array<uint32_t, 3> lo{7, 7, 7}, hi{0, 0, 0};
            for (uint32_t bit = 0; bit < 512; ++bit)
                if ((m.words[bit >> 6] >> (bit & 63)) & 1u) {
                    const uint32_t v[3] = {bit >> 6, (bit >> 3) & 7, bit & 7};
                    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
                }
            std::array<uint32_t, 3> b0{}, b1{};
            for (int a = 0; a < 3; ++a) {
                const int64_t o = refs[n].origin[a];
                b0[a] = uint32_t(std::max<int64_t>(o + lo[a] - reach, 0) / 8);
                b1[a] = std::min(uint32_t((o + hi[a] + reach) / 8), limit[a]);
            }
            for (uint32_t x = b0[0]; x <= b1[0]; ++x)
                for (uint32_t y = b0[1]; y <= b1[1]; ++y)
                    for (uint32_t z = b0[2]; z <= b1[2]; ++z) parts[n].push_back({x, y, z});
        }
    });
    std::vector<BrickCoord> all;
    for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
    tbb::parallel_sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
}

openvdb::Coord leafOrigin(const GridSpec& grid, const BrickCoord& b)
{
    return openvdb::Coord(int32_t(grid.anchor[0] + 8 * int64_t(b[0])), int32_t(grid.anchor[1] + 8 * int64_t(b[1])),
                          int32_t(grid.anchor[2] + 8 * int64_t(b[2])));
}

bool bitOf(const Brick& b, uint32_t bit) { return (b.words[bit >> 6] >> (bit & 63)) & 1u; }

/// Adds leaves made in parallel (null: none) to a tree, in order.
template <typename TreeT>
void addLeaves(TreeT& tree, std::vector<typename TreeT::LeafNodeType*>& leaves)
{
    for (auto* leaf : leaves)
        if (leaf) tree.addLeaf(leaf);
}

} // namespace

namespace detail {
double uniformScale(const openvdb::math::Transform& xform)
{
    if (!xform.isLinear() || !xform.hasUniformScale())
        throw Error("level sets need a linear transform with uniform scale, so that index distances are world "
                    "distances");
    return xform.voxelSize()[0];
}
} // namespace detail

openvdb::GridPtrVec Voxelizer::levelSet(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                                        const VoxelizeOptions& options, openvdb::math::Transform::Ptr xform)
{
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    if (!xform) xform = vdb::makeTransform(grid);
    const double scale = detail::uniformScale(*xform);
    return levelSetChecked(mesh, grid, ls, options, xform, scale);
}

openvdb::MaskGrid::Ptr Voxelizer::solid(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                        SignMethod sign, openvdb::math::Transform::Ptr xform)
{
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    return solidChecked(mesh, grid, options, sign, xform ? xform : vdb::makeTransform(grid));
}

openvdb::GridPtrVec Voxelizer::levelSetChecked(const TriangleMesh& mesh, const GridSpec& grid,
                                               const LevelSetOptions& ls, const VoxelizeOptions& options,
                                               openvdb::math::Transform::Ptr xform, double worldPerVoxel)
{
    const bool signedField = !ls.unsignedDistance;
    for (double w : {ls.exteriorBand, signedField ? ls.interiorBand : 1.0})
        if (!(w >= 1.0) || !std::isfinite(w) || w > 1000.0)
            throw Error(fmt::format("a band of {} voxels: level set bands are 1 to 1000 voxels wide", w));
    if (options.backend == Backend::Cpu)
        throw Error("level sets are computed on the GPU; choose the raster or compute backend, or auto");
    const InterruptScope interrupt(options.interrupter, "svo: computing a distance field");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    if (signedField) stats.sign = chooseSign(mesh, ls.sign, stats.warnings);
    const double band = signedField ? std::max(ls.exteriorBand, ls.interiorBand) : ls.exteriorBand;
    // Every voxel within `band` of a triangle is within reach (Chebyshev) of
    // a surface voxel; the first centre above a crossing is within 1.
    const uint32_t reach = std::max<uint32_t>(1, uint32_t(std::floor(band + 0.5)));
    const GridSpec g = padded(grid, reach + 1, mesh.source);

    // The surface, as meshToMask gives it.
    VoxelizeOptions surfaceOptions = options;
    surfaceOptions.interrupter = nullptr;
    surfaceOptions.attributes = 0;
    surfaceOptions.mode = VoxelMode::Conservative; // the band is grown from every voxel a triangle touches
    surfaceOptions.stats = &stats;
    const std::string sign = stats.sign;
    const auto warnings = stats.warnings;
    checkpoint(0.0, "surface voxels");
    const Octree surface = voxelizeChecked(mesh, g, surfaceOptions, nullptr);
    stats.sign = sign;
    stats.warnings.insert(stats.warnings.begin(), warnings.begin(), warnings.end());
    checkpoint(0.3, "band bricks");

    auto t0 = Clock::now();
    gl::FieldRequest request;
    request.bricks = grownBricks(surface, reach);
    request.band = band;
    request.closestTriangle = ls.closestTriangle;
    request.crossings = signedField;
    request.checkpoint = checkpoint.part(0.35, 0.85);
    stats.bandBricks = request.bricks.size();
    stats.stages.push_back({"band bricks", -1, msSince(t0)});
    gl::FieldResult field = gl::computeField(impl_->gl(), mesh, g, request);
    if (field.lostCrossings)
        throw Error(fmt::format("internal error: {} parity crossings fell outside the band's bricks",
                                field.lostCrossings));
    for (auto& s : field.stages) stats.stages.push_back(std::move(s));
    stats.gpuBytes = std::max(stats.gpuBytes, field.gpuBytes);
    checkpoint(0.85, "level set grid");

    t0 = Clock::now();
    ParityScan parity;
    if (signedField) parity = scanParity(request.bricks, field.crossings);
    stats.openColumns = parity.openColumns;
    if (parity.openColumns)
        stats.warnings.push_back(fmt::format("{} voxel columns cross the surface an odd number of times: the mesh is "
                                             "open there, and signs above its last crossing count as outside",
                                             parity.openColumns));
    const float exterior = float(ls.exteriorBand), interior = float(ls.interiorBand);
    const float background = float(ls.exteriorBand * worldPerVoxel);
    auto distance = openvdb::FloatGrid::create(background);
    auto closest = ls.closestTriangle ? openvdb::Int32Grid::create(-1) : nullptr;
    const size_t nb = request.bricks.size();
    std::vector<openvdb::FloatTree::LeafNodeType*> leaves(nb, nullptr);
    std::vector<openvdb::Int32Tree::LeafNodeType*> closestLeaves(nb, nullptr);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nb, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const openvdb::Coord origin = leafOrigin(g, request.bricks[i]);
            auto leaf = std::make_unique<openvdb::FloatTree::LeafNodeType>(origin, background);
            bool any = false;
            for (uint32_t v = 0; v < 512; ++v) {
                const float d = field.distances[i * 512 + v];
                const bool inside = signedField && bitOf(parity.inside[i], v);
                const bool active = d < (inside ? interior : exterior);
                const float value = active ? float(double(d) * worldPerVoxel) : background;
                leaf->setValueOnly(v, inside ? -value : value);
                if (active) leaf->setValueOn(v), any = true;
            }
            if (!any) continue;
            if (closest) {
                auto c = std::make_unique<openvdb::Int32Tree::LeafNodeType>(origin, -1);
                for (auto it = leaf->cbeginValueOn(); it; ++it) c->setValueOn(it.pos(), field.closest[i * 512 + it.pos()]);
                closestLeaves[i] = c.release();
            }
            leaves[i] = leaf.release();
        }
    });
    addLeaves(distance->tree(), leaves);
    if (closest) addLeaves(closest->tree(), closestLeaves);
    distance->setTransform(xform);
    if (signedField) {
        openvdb::tools::signedFloodFill(distance->tree());
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
    stats.stages.push_back({"level set grid", -1, msSince(t0)});
    stats.voxels = distance->activeVoxelCount();
    stats.bricks = distance->tree().leafCount();
    checkpoint(1.0, "finish");
    if (options.stats) *options.stats = std::move(stats);
    return out;
}

openvdb::MaskGrid::Ptr Voxelizer::solidChecked(const TriangleMesh& mesh, const GridSpec& grid,
                                               const VoxelizeOptions& options, SignMethod sign,
                                               openvdb::math::Transform::Ptr xform)
{
    if (options.backend == Backend::Cpu)
        throw Error("solids are computed on the GPU; choose the raster or compute backend, or auto");
    const InterruptScope interrupt(options.interrupter, "svo: filling a solid");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    const std::string how = chooseSign(mesh, sign, stats.warnings);
    const auto warnings = stats.warnings;
    const GridSpec g = padded(grid, 2, mesh.source);

    VoxelizeOptions surfaceOptions = options;
    surfaceOptions.interrupter = nullptr;
    surfaceOptions.attributes = 0;
    surfaceOptions.mode = VoxelMode::Conservative; // every crossing lies in a touched voxel
    surfaceOptions.stats = &stats;
    checkpoint(0.0, "surface voxels");
    const Octree surface = voxelizeChecked(mesh, g, surfaceOptions, nullptr);
    stats.sign = how;
    stats.warnings.insert(stats.warnings.begin(), warnings.begin(), warnings.end());
    checkpoint(0.4, "parity crossings");

    auto t0 = Clock::now();
    gl::FieldRequest request;
    request.bricks = grownBricks(surface, 1); // the first centre above a crossing is within 1 voxel of it
    request.checkpoint = checkpoint.part(0.45, 0.8);
    stats.bandBricks = request.bricks.size();
    stats.stages.push_back({"band bricks", -1, msSince(t0)});
    gl::FieldResult field = gl::computeField(impl_->gl(), mesh, g, request);
    if (field.lostCrossings)
        throw Error(fmt::format("internal error: {} parity crossings fell outside the band's bricks",
                                field.lostCrossings));
    for (auto& s : field.stages) stats.stages.push_back(std::move(s));
    stats.gpuBytes = std::max(stats.gpuBytes, field.gpuBytes);
    checkpoint(0.8, "solid grid");

    t0 = Clock::now();
    const ParityScan parity = scanParity(request.bricks, field.crossings);
    stats.openColumns = parity.openColumns;
    if (parity.openColumns)
        stats.warnings.push_back(fmt::format("{} voxel columns cross the surface an odd number of times: the mesh is "
                                             "open there, and the solid stops at its last crossing",
                                             parity.openColumns));
    // Surface bricks by coordinates, to OR into the inside masks.
    std::vector<std::pair<BrickCoord, uint32_t>> surfaceBricks;
    for (const auto& r : occupiedBricks(surface))
        surfaceBricks.push_back({{r.origin[0] / 8, r.origin[1] / 8, r.origin[2] / 8}, r.index});
    tbb::parallel_sort(surfaceBricks.begin(), surfaceBricks.end());
    auto out = openvdb::MaskGrid::create(false);
    const size_t nb = request.bricks.size();
    std::vector<openvdb::MaskTree::LeafNodeType*> leaves(nb, nullptr);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nb, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            Brick m = parity.inside[i];
            const auto it = std::lower_bound(surfaceBricks.begin(), surfaceBricks.end(),
                                             std::make_pair(request.bricks[i], uint32_t(0)));
            if (it != surfaceBricks.end() && it->first == request.bricks[i])
                for (int w = 0; w < 8; ++w) m.words[w] |= surface.bricks[it->second].words[w];
            if (!m.count()) continue;
            auto leaf = std::make_unique<openvdb::MaskTree::LeafNodeType>(leafOrigin(g, request.bricks[i]), false);
            for (uint32_t v = 0; v < 512; ++v)
                if (bitOf(m, v)) leaf->setValueOn(v);
            leaves[i] = leaf.release();
        }
    });
    addLeaves(out->tree(), leaves);
    // Runs of whole bricks inside: tiles where all 64 columns are inside.
    for (const auto& run : parity.runs) {
        const openvdb::Coord lo = leafOrigin(g, run.first);
        const int32_t top = lo.z() + 8 * int32_t(run.bricks) - 1;
        if (run.columns == ~uint64_t(0)) {
            out->tree().fill(openvdb::CoordBBox(lo, openvdb::Coord(lo.x() + 7, lo.y() + 7, top)), true, true);
            continue;
        }
        for (uint32_t c = 0; c < 64; ++c)
            if ((run.columns >> c) & 1u) {
                const openvdb::Coord a(lo.x() + int32_t(c / 8), lo.y() + int32_t(c % 8), lo.z());
                out->tree().fill(openvdb::CoordBBox(a, openvdb::Coord(a.x(), a.y(), top)), true, true);
            }
    }
    out->tree().prune(); // full leaves and nodes become tiles at the largest level they fill
    out->setTransform(xform);
    out->setName("solid");
    stats.stages.push_back({"solid grid", -1, msSince(t0)});
    stats.voxels = out->activeVoxelCount();
    stats.bricks = out->tree().leafCount();
    checkpoint(1.0, "finish");
    if (options.stats) *options.stats = std::move(stats);
    return out;
}

} // namespace svo
