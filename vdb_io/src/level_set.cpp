// Level sets, unsigned distance fields and solids (svo/voxelizer.h): the
// triangles give a level set's band bricks (a solid's come from its surface
// voxels), the GPU gives distances there
// (svo/gl/distance_field.h) and signs, by parity crossings or by winding
// numbers (svo/gl/winding_number.h), and OpenVDB holds the result.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <openvdb/tools/SignedFloodFill.h>
#include <unordered_map>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include "svo/core/error.h"
#include "svo/core/mesh_topology.h"
#include "svo/core/parity_scan.h"
#include "svo/gl/distance_field.h"
#include "svo/gl/winding_number.h"
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
            throw Unsupported(fmt::format("{}: the grid with its band is {} voxels wide, more than svo's {}", what, dims,
                                          kMaxGridDim));
        g.dims[a] = uint32_t(dims);
    }
    checkGrid(g, what);
    return g;
}

/// The sign method a call uses, and why (for the statistics).
struct SignChoice {
    SignMethod method;
    std::string why;
};
SignChoice chooseSign(const TriangleMesh& mesh, const SignOptions& asked, std::vector<std::string>& warnings)
{
    checkWindingAccuracy(asked.windingAccuracy, "SignOptions::windingAccuracy");
    if (asked.method == SignMethod::Winding) return {SignMethod::Winding, "winding: as asked"};
    const EdgeReport edges = checkEdges(mesh);
    if (edges.closedAndOriented()) return {SignMethod::Parity, "parity: the mesh is " + edges.describe()};
    if (asked.method == SignMethod::Auto)
        return {SignMethod::Winding, "winding: the mesh is not closed (" + edges.describe() + ")"};
    // A hole lets a column of voxel centres cross the surface an odd number
    // of times, and parity then flips every sign beyond it: refused. Edges of
    // three or more triangles, or two running the same way, can still give
    // even crossings (two solids sharing an edge, a flipped face): warned.
    if (edges.boundary)
        throw Unsupported(fmt::format("{}: parity signs need a mesh without holes, and this one has {}: a column of voxels "
                                      "through a hole crosses the surface an odd number of times and every sign beyond it "
                                      "would flip; use the winding sign method (or auto, which picks it for such a mesh)",
                                      mesh.source, edges.describe()));
    warnings.push_back(fmt::format("{} is not closed ({}): parity signs may be wrong", mesh.source, edges.describe()));
    return {SignMethod::Parity, "parity: as asked (the mesh is not closed)"};
}

/// Inside and outside, for the band's bricks and beyond them.
struct Signs {
    std::vector<Brick> inside; ///< per band brick, the voxels whose centres are inside
    /// Parity: runs of whole bricks inside between band bricks of a column.
    std::vector<InsideRun> runs;
    /// Winding: whole bricks beyond the band that are inside, and bricks
    /// beyond it classified voxel by voxel (their inside voxels).
    std::vector<BrickCoord> insideBricks;
    std::vector<std::pair<BrickCoord, Brick>> partial;
    uint64_t openColumns = 0;
};

/// A brick beyond the band whose centre's winding number is nearer 1/2 than
/// this may hold both sides (the 1/2 level crosses free space only where the
/// mesh has holes); its voxels are evaluated one by one.
constexpr float kWindingMargin = 0.25f;

/// Winding-number signs: the number at every brick centre of the grid's box,
/// then voxel by voxel in the band's bricks and in the bricks whose centre is
/// within kWindingMargin of 1/2.
Signs windingSigns(gl::Context& context, const TriangleMesh& mesh, const GridSpec& g,
                   const std::vector<BrickCoord>& band, double beta, const Checkpoint& checkpoint,
                   VoxelizeStats& stats)
{
    auto t0 = Clock::now();
    const WindingTree tree = buildWindingTree(gl::localPositions(mesh, g), mesh.triangles);
    stats.stages.push_back({"winding tree", -1, msSince(t0)});
    gl::WindingRequest coarse;
    coarse.perBrick = true;
    coarse.beta = beta;
    coarse.checkpoint = checkpoint.part(0.0, 0.3);
    gl::WindingResult centres = gl::computeWinding(context, mesh, g, tree, coarse);
    for (auto& st : centres.stages) stats.stages.push_back(std::move(st));

    // `band` is sorted (grownBricks): the box's bricks in x-major order walk it once.
    Signs signs;
    gl::WindingRequest fine;
    fine.bricks = band;
    fine.beta = beta;
    fine.checkpoint = checkpoint.part(0.3, 1.0);
    const auto& d = centres.brickDims;
    size_t next = 0;
    for (uint32_t x = 0; x < d[0]; ++x)
        for (uint32_t y = 0; y < d[1]; ++y)
            for (uint32_t z = 0; z < d[2]; ++z) {
                const BrickCoord b{x, y, z};
                if (next < band.size() && band[next] == b) {
                    ++next;
                    continue;
                }
                const float w = centres.perBrick[x + size_t(d[0]) * (y + size_t(d[1]) * z)];
                if (std::abs(w - 0.5f) < kWindingMargin) fine.bricks.push_back(b);
                else if (w >= 0.5f) signs.insideBricks.push_back(b);
            }
    stats.windingBricks = fine.bricks.size() - band.size();
    gl::WindingResult voxels = gl::computeWinding(context, mesh, g, tree, fine);
    for (auto& st : voxels.stages) stats.stages.push_back(std::move(st));
    stats.gpuBytes = std::max({stats.gpuBytes, centres.gpuBytes, voxels.gpuBytes});
    signs.inside.assign(voxels.inside.begin(), voxels.inside.begin() + std::ptrdiff_t(band.size()));
    for (size_t i = band.size(); i < fine.bricks.size(); ++i)
        if (voxels.inside[i].count()) signs.partial.push_back({fine.bricks[i], voxels.inside[i]});
    return signs;
}

/// Parity signs from the crossings the distance pass marked.
Signs paritySigns(const std::vector<BrickCoord>& band, const std::vector<Brick>& crossings)
{
    ParityScan scan = scanParity(band, crossings);
    Signs signs;
    signs.inside = std::move(scan.inside);
    signs.runs = std::move(scan.runs);
    signs.openColumns = scan.openColumns;
    return signs;
}

/// computeField, with its stages and buffer bytes added to `stats`.
gl::FieldResult fieldPass(gl::Context& context, const TriangleMesh& mesh, const GridSpec& g,
                          const gl::FieldRequest& request, VoxelizeStats& stats)
{
    gl::FieldResult field = gl::computeField(context, mesh, g, request);
    if (field.lostCrossings)
        throw DeviceError(fmt::format("internal error: {} parity crossings fell outside the band's bricks",
                                      field.lostCrossings));
    for (auto& st : field.stages) stats.stages.push_back(std::move(st));
    stats.gpuBytes = std::max(stats.gpuBytes, field.gpuBytes);
    return field;
}

/// Records parity's open columns, warning with what they mean for the result.
void noteOpenColumns(VoxelizeStats& stats, uint64_t openColumns, const char* consequence)
{
    stats.openColumns = openColumns;
    if (openColumns)
        stats.warnings.push_back(fmt::format("{} voxel columns cross the surface an odd number of times: the mesh is "
                                             "open there, and {}",
                                             openColumns, consequence));
}

/// The box of a non-empty brick's set bits: lowest x, y, z, then highest.
/// Word x holds bits 8y + z, so the words give x, their OR's bytes y, and
/// the OR of those bytes z.
std::array<uint32_t, 6> occupiedBox(const Brick& m)
{
    uint32_t x0 = 8, x1 = 0;
    uint64_t all = 0;
    for (uint32_t x = 0; x < 8; ++x)
        if (m.words[x]) x0 = std::min(x0, x), x1 = x, all |= m.words[x];
    uint32_t y0 = 8, y1 = 0, zBits = 0;
    for (uint32_t y = 0; y < 8; ++y)
        if (const uint32_t byte = uint32_t(all >> (8 * y)) & 0xFFu) y0 = std::min(y0, y), y1 = y, zBits |= byte;
    const uint32_t z0 = uint32_t(__builtin_ctz(zBits)), z1 = 31u - uint32_t(__builtin_clz(zBits));
    return {x0, y0, z0, x1, y1, z1};
}

/// A bit per brick of a grid `limit` + 1 bricks wide, in x-major order:
/// set from many threads, then read in order, the set bits are the bricks
/// sorted and unique, without a sort. Used up to 2^33 bricks (1 GiB).
struct BrickBitmap {
    uint64_t ny, nz;
    std::vector<std::atomic<uint64_t>> bits;

    static uint64_t cells(const std::array<uint32_t, 3>& limit)
    {
        return uint64_t(limit[0] + 1) * (limit[1] + 1) * (limit[2] + 1);
    }
    static bool fits(const std::array<uint32_t, 3>& limit) { return cells(limit) <= (uint64_t(1) << 33); }
    explicit BrickBitmap(const std::array<uint32_t, 3>& limit)
        : ny(limit[1] + 1), nz(limit[2] + 1), bits((cells(limit) + 63) / 64)
    {
    }
    void set(const BrickCoord& b)
    {
        const uint64_t i = (b[0] * ny + b[1]) * nz + b[2];
        bits[i >> 6].fetch_or(uint64_t(1) << (i & 63), std::memory_order_relaxed);
    }
    std::vector<BrickCoord> sorted() const
    {
        std::vector<BrickCoord> all;
        for (uint64_t w = 0; w < bits.size(); ++w)
            for (uint64_t m = bits[w].load(std::memory_order_relaxed); m; m &= m - 1) {
                const uint64_t i = 64 * w + uint64_t(__builtin_ctzll(m));
                all.push_back({uint32_t(i / (ny * nz)), uint32_t(i / nz % ny), uint32_t(i % nz)});
            }
        return all;
    }
};

/// `all` sorted in x-major order and unique: for grids too large for a BrickBitmap.
std::vector<BrickCoord> sortedUnique(std::vector<BrickCoord> all)
{
    tbb::parallel_sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
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
            const std::array<uint32_t, 6> box = occupiedBox(octree.bricks[refs[n].index]);
            const std::array<uint32_t, 3> lo{box[0], box[1], box[2]}, hi{box[3], box[4], box[5]};
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
    if (!BrickBitmap::fits(limit)) {
        std::vector<BrickCoord> all;
        for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
        return sortedUnique(std::move(all));
    }
    BrickBitmap bitmap(limit);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, parts.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t n = r.begin(); n != r.end(); ++n)
            for (const BrickCoord& b : parts[n]) bitmap.set(b);
    });
    return bitmap.sorted();
}

/// The bricks holding every voxel centre within `grow` voxels of a
/// triangle (local coordinates: centres at integers): per triangle, the
/// bricks its box grown by `grow` spans that also meet the slab of centres
/// within `grow` of its plane, found a column of bricks at a time. Both
/// tests hold every centre whose distance to the triangle is at most `grow`,
/// widened by 1e-6 relative and absolute against rounding (and the slab as
/// band_distance.glsl's for needles), so no centre the distance pass keeps
/// is left out, and a slanted triangle's box costs only its slab.
/// @throw svo::Unsupported when the boxes span more than 2^32 bricks in all, what
///        the distance pass refuses too (a band far wider than the mesh's features).
std::vector<BrickCoord> bricksNearTriangles(const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                                            const GridSpec& g, double grow)
{
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (g.dims[a] + 7) / 8 - 1;
    const double reach = grow * (1 + 1e-6) + 1e-6;
    // Triangle t's centres within reach of its box, clamped to the grid
    // (and one past it) before converting; false when none is in the grid.
    const auto boxOf = [&](size_t t, std::array<int64_t, 3>& lo, std::array<int64_t, 3>& hi) {
        const auto& f = mesh.triangles[t];
        bool any = true;
        for (int k = 0; k < 3; ++k) {
            const double top = double(g.dims[k]);
            const double a = local[f[0]][k], b = local[f[1]][k], c = local[f[2]][k];
            lo[k] = int64_t(std::clamp(std::ceil(std::min({a, b, c}) - reach), 0.0, top));
            hi[k] = int64_t(std::clamp(std::floor(std::max({a, b, c}) + reach), -1.0, top - 1));
            any &= lo[k] <= hi[k];
        }
        return any;
    };
    const size_t n = mesh.triangles.size();
    const uint64_t spanned = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 4096), uint64_t(0),
        [&](const tbb::blocked_range<size_t>& r, uint64_t sum) {
            std::array<int64_t, 3> lo{}, hi{};
            for (size_t t = r.begin(); t != r.end(); ++t)
                if (boxOf(t, lo, hi))
                    sum += uint64_t(hi[0] / 8 - lo[0] / 8 + 1) * uint64_t(hi[1] / 8 - lo[1] / 8 + 1) *
                           uint64_t(hi[2] / 8 - lo[2] / 8 + 1);
            return sum;
        },
        std::plus<uint64_t>());
    if (spanned > (uint64_t(1) << 32))
        throw Unsupported(fmt::format("the distance field needs {} brick work items, more than one pass holds (2^32); use "
                                      "a coarser grid or a narrower band",
                                      spanned));
    // Calls emit(brick) for every brick near triangle t.
    const auto forEachBrick = [&](size_t t, auto&& emit) {
        std::array<int64_t, 3> lo{}, hi{};
        if (!boxOf(t, lo, hi)) return;
        const auto& f = mesh.triangles[t];
        const Vec3d& a = local[f[0]];
        const Vec3d& b = local[f[1]];
        const Vec3d& c = local[f[2]];
        // The plane: h(p) = n . (p - a), within the slab when |h| <= slab,
        // widened as band_distance.glsl's slabOf for needles, whose normal
        // is rounding noise.
        const Vec3d nrm = cross(b - a, c - a);
        const double e1 = std::sqrt(dot(b - a, b - a)), e2 = std::sqrt(dot(c - a, c - a));
        const double slab = reach * std::sqrt(dot(nrm, nrm)) + 1e-10 * e1 * e2 * (e1 + e2 + reach);
        for (int64_t bx = lo[0] / 8; bx <= hi[0] / 8; ++bx)
            for (int64_t by = lo[1] / 8; by <= hi[1] / 8; ++by) {
                // This brick column's centres in x and y, and h over them at z = 0.
                const double x0 = double(std::max(lo[0], 8 * bx)), x1 = double(std::min(hi[0], 8 * bx + 7));
                const double y0 = double(std::max(lo[1], 8 * by)), y1 = double(std::min(hi[1], 8 * by + 7));
                const double h0 = nrm.x * (0.5 * (x0 + x1) - a.x) + nrm.y * (0.5 * (y0 + y1) - a.y) - nrm.z * a.z;
                const double spread = std::abs(nrm.x) * 0.5 * (x1 - x0) + std::abs(nrm.y) * 0.5 * (y1 - y0);
                double z0 = double(lo[2]), z1 = double(hi[2]);
                if (nrm.z != 0) {
                    // n.z z + h0 within [-slab - spread, slab + spread].
                    const double below = (-slab - spread - h0) / nrm.z, above = (slab + spread - h0) / nrm.z;
                    z0 = std::max(z0, std::ceil(std::min(below, above) - 1e-6));
                    z1 = std::min(z1, std::floor(std::max(below, above) + 1e-6));
                } else if (std::abs(h0) > slab + spread) {
                    continue;
                }
                if (!(z0 <= z1)) continue;
                for (int64_t bz = int64_t(z0) / 8; bz <= int64_t(z1) / 8; ++bz)
                    emit(BrickCoord{uint32_t(bx), uint32_t(by), uint32_t(bz)});
            }
    };
    if (BrickBitmap::fits(limit)) {
        BrickBitmap bitmap(limit);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t t = r.begin(); t != r.end(); ++t) forEachBrick(t, [&](const BrickCoord& b) { bitmap.set(b); });
        });
        return bitmap.sorted();
    }
    tbb::enumerable_thread_specific<std::vector<BrickCoord>> lists;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
        auto& list = lists.local();
        for (size_t t = r.begin(); t != r.end(); ++t) forEachBrick(t, [&](const BrickCoord& b) { list.push_back(b); });
    });
    std::vector<BrickCoord> all;
    for (auto& list : lists) all.insert(all.end(), list.begin(), list.end());
    return sortedUnique(std::move(all));
}

/// grownBricks, counted and timed in `stats`.
std::vector<BrickCoord> bandBricks(const Octree& surface, uint32_t reach, VoxelizeStats& stats)
{
    const auto t0 = Clock::now();
    std::vector<BrickCoord> band = grownBricks(surface, reach);
    stats.bandBricks = band.size();
    stats.stages.push_back({"band bricks", -1, msSince(t0)});
    return band;
}

/// The last stage and the result's counts, then the statistics handed out.
void finishStats(VoxelizeStats& stats, const char* stage, Clock::time_point t0, const openvdb::GridBase& result,
                 const Checkpoint& checkpoint, const VoxelizeOptions& options)
{
    stats.stages.push_back({stage, -1, msSince(t0)});
    stats.voxels = result.activeVoxelCount();
    stats.bricks = result.baseTree().leafCount();
    checkpoint(1.0, "finish");
    if (options.stats) *options.stats = std::move(stats);
}

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

/// Adds leaves made in parallel (null: none) to a tree, in order.
template <typename TreeT>
void addLeaves(TreeT& tree, std::vector<typename TreeT::LeafNodeType*>& leaves)
{
    for (auto* leaf : leaves)
        if (leaf) tree.addLeaf(leaf);
}

} // namespace

void checkBand(double voxels, const std::string& name)
{
    if (!(voxels >= 1.0 && voxels <= 1000.0)) // NaN fails too
        throw InvalidInput(name, fmt::format("{}: a band is a number of voxels from 1 to 1000", voxels));
}

void checkWindingAccuracy(double accuracy, const std::string& name)
{
    if (!(accuracy > 0) || !std::isfinite(accuracy))
        throw InvalidInput(name, fmt::format("{}: the winding accuracy is a positive finite number (default 1.5; larger "
                                             "is slower and more exact, 1e300 evaluates every triangle)",
                                             accuracy));
}

void checkLevelSetOptions(const LevelSetOptions& ls)
{
    checkBand(ls.exteriorBand, "LevelSetOptions::exteriorBand");
    if (!ls.unsignedDistance) checkBand(ls.interiorBand, "LevelSetOptions::interiorBand");
    checkWindingAccuracy(ls.sign.windingAccuracy, "SignOptions::windingAccuracy");
}

void checkFieldMode(const VoxelizeOptions& options)
{
    if (options.mode != VoxelMode::Conservative)
        throw InvalidInput(std::vector<Error::Part>{
            Error::option("VoxelizeOptions::mode"), fmt::format(" {}: ", voxelModeName(options.mode)),
            Error::option("VoxelizeOptions::mode"),
            " applies to surface voxels; level sets, unsigned distances and solids do not depend on it (leave it "
            "conservative)"});
}

namespace detail {
double uniformScale(const openvdb::math::Transform& xform)
{
    if (!xform.isLinear() || !xform.hasUniformScale())
        throw Unsupported("level sets need a linear transform with uniform scale, so that index distances are world "
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
                                        const SignOptions& sign, openvdb::math::Transform::Ptr xform)
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
    checkLevelSetOptions(ls);
    checkFieldMode(options);
    if (options.backend == Backend::Cpu)
        throw Unsupported("level sets are computed on the GPU; choose the raster or compute backend, or auto");
    const InterruptScope interrupt(options.interrupter, "svo: computing a distance field");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    SignChoice sign{SignMethod::Parity, {}};
    if (signedField) sign = chooseSign(mesh, ls.sign, stats.warnings);
    const bool winding = signedField && sign.method == SignMethod::Winding;
    const double band = signedField ? std::max(ls.exteriorBand, ls.interiorBand) : ls.exteriorBand;
    // Every voxel within `band` of a triangle is within reach (Chebyshev) of
    // the triangle's box; the first centre above a crossing is within 1.
    const uint32_t reach = std::max<uint32_t>(1, uint32_t(std::floor(band + 0.5)));
    const GridSpec g = padded(grid, reach + 1, mesh.source);
    stats.grid = g;
    stats.epsilon = g.epsilon();
    impl_->describeBackend(stats, Backend::Compute); // compute passes only, whatever the backend asked
    stats.sign = sign.why;
    checkpoint(0.0, "band bricks");

    gl::FieldRequest request;
    {
        const auto t0 = Clock::now();
        request.bricks = bricksNearTriangles(gl::localPositions(mesh, g), mesh, g, std::max(band, 1.0));
        stats.bandBricks = request.bricks.size();
        stats.stages.push_back({"band bricks", -1, msSince(t0)});
    }
    request.band = band;
    request.closestTriangle = ls.closestTriangle;
    request.crossings = signedField && !winding;
    request.checkpoint = checkpoint.part(0.3, winding ? 0.55 : 0.85);
    gl::FieldResult field = fieldPass(impl_->gl(), mesh, g, request, stats);
    Signs signs;
    if (winding) {
        signs = windingSigns(impl_->gl(), mesh, g, request.bricks, ls.sign.windingAccuracy,
                             checkpoint.part(0.55, 0.85), stats);
    } else if (signedField) {
        const auto t0 = Clock::now();
        signs = paritySigns(request.bricks, field.crossings);
        stats.stages.push_back({"parity scan", -1, msSince(t0)});
    }
    checkpoint(0.85, "level set grid");

    const auto t0 = Clock::now();
    noteOpenColumns(stats, signs.openColumns, "signs above its last crossing count as outside");
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
            const Brick& near = field.bandMasks[i];
            const bool anyInside = signedField && signs.inside[i].count();
            // Parity's flood fill signs inactive leaves from their neighbours;
            // winding signs are known at every voxel, so a leaf with no active
            // voxel is still kept when it holds inside values.
            if (!near.count() && !(winding && anyInside)) continue;
            auto leaf = std::make_unique<openvdb::FloatTree::LeafNodeType>(origin, background);
            std::unique_ptr<openvdb::Int32Tree::LeafNodeType> c;
            if (closest) c = std::make_unique<openvdb::Int32Tree::LeafNodeType>(origin, -1);
            bool any = false;
            size_t packed = field.bandOffsets[i]; // the next near voxel's value
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
            if (!any && !(winding && anyInside)) continue;
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
    stats.startup = impl_->takeStartup(stats.warnings);
    finishStats(stats, "level set grid", t0, *distance, checkpoint, options);
    return out;
}

openvdb::MaskGrid::Ptr Voxelizer::solidChecked(const TriangleMesh& mesh, const GridSpec& grid,
                                               const VoxelizeOptions& options, const SignOptions& signOptions,
                                               openvdb::math::Transform::Ptr xform)
{
    checkFieldMode(options); // the sign options: chooseSign
    if (options.backend == Backend::Cpu)
        throw Unsupported("solids are computed on the GPU; choose the raster or compute backend, or auto");
    const InterruptScope interrupt(options.interrupter, "svo: filling a solid");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    const SignChoice sign = chooseSign(mesh, signOptions, stats.warnings);
    const bool winding = sign.method == SignMethod::Winding;
    const GridSpec g = padded(grid, 2, mesh.source);
    checkpoint(0.0, "surface voxels");
    const Octree surface = surfaceVoxels(mesh, g, options, stats);
    stats.sign = sign.why;
    checkpoint(0.3, "signs");

    // The first centre above a crossing is within 1 voxel of it.
    const std::vector<BrickCoord> band = bandBricks(surface, 1, stats);
    Signs signs;
    if (winding) {
        signs = windingSigns(impl_->gl(), mesh, g, band, signOptions.windingAccuracy, checkpoint.part(0.35, 0.8),
                             stats);
    } else {
        gl::FieldRequest request;
        request.bricks = band;
        request.checkpoint = checkpoint.part(0.35, 0.8);
        signs = paritySigns(band, fieldPass(impl_->gl(), mesh, g, request, stats).crossings);
    }
    checkpoint(0.8, "solid grid");

    const auto t0 = Clock::now();
    noteOpenColumns(stats, signs.openColumns, "the solid stops at its last crossing");
    // Surface bricks by coordinates, to OR into the inside masks.
    std::vector<std::pair<BrickCoord, uint32_t>> surfaceBricks;
    for (const auto& r : occupiedBricks(surface))
        surfaceBricks.push_back({{r.origin[0] / 8, r.origin[1] / 8, r.origin[2] / 8}, r.index});
    tbb::parallel_sort(surfaceBricks.begin(), surfaceBricks.end());
    auto out = openvdb::MaskGrid::create(false);
    const size_t nb = band.size();
    std::vector<openvdb::MaskTree::LeafNodeType*> leaves(nb, nullptr);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nb, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            Brick m = signs.inside[i];
            const auto it = std::lower_bound(surfaceBricks.begin(), surfaceBricks.end(),
                                             std::make_pair(band[i], uint32_t(0)));
            if (it != surfaceBricks.end() && it->first == band[i])
                for (int w = 0; w < 8; ++w) m.words[w] |= surface.bricks[it->second].words[w];
            if (!m.count()) continue;
            auto leaf = std::make_unique<openvdb::MaskTree::LeafNodeType>(leafOrigin(g, band[i]), false);
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
    // Parity: runs of whole bricks inside, tiles where all 64 columns are inside.
    for (const auto& run : signs.runs) {
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
    finishStats(stats, "solid grid", t0, *out, checkpoint, options);
    return out;
}

Octree Voxelizer::surfaceVoxels(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                VoxelizeStats& stats)
{
    // As meshToMask gives them, always conservative: the band is grown from,
    // and every crossing lies in, a voxel a triangle touches.
    VoxelizeOptions surfaceOptions = options;
    surfaceOptions.interrupter = nullptr;
    surfaceOptions.attributes = 0;
    surfaceOptions.mode = VoxelMode::Conservative;
    VoxelizeStats surfaceStats;
    surfaceOptions.stats = &surfaceStats;
    Octree surface = voxelizeChecked(mesh, grid, surfaceOptions, nullptr);
    // The surface call's statistics are the start of this call's: the
    // warnings gathered so far go first.
    surfaceStats.warnings.insert(surfaceStats.warnings.begin(), stats.warnings.begin(), stats.warnings.end());
    stats = std::move(surfaceStats);
    return surface;
}

} // namespace svo
