// Signed column crossings and boundary slopes for the CPU's winding signs
// (svo/core/winding_columns.h).
#include "svo/core/winding_columns.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tuple>

#include "brick_index.h"
#include "svo/core/error.h"
#include "svo/core/mesh_topology.h"
#include "svo/core/region.h"
#include "column_crossings.h"

namespace svo {
namespace {

constexpr double kInvFourPi = 0.0795774715459476679;

struct Crossing {
    uint32_t brick;
    uint16_t voxel;
    int16_t jump;
};

/// Every crossing of a listed brick's column, from the parity pass's test
/// (the same columns, heights and ties): the winding number rises by 1
/// through a triangle facing down (-z) and falls through one facing up.
std::vector<Crossing> crossingsOf(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                                  const BrickIndex& index)
{
    tbb::enumerable_thread_specific<std::vector<Crossing>> found;
    const double dimZ = double(grid.dims[2]);
    const uint32_t columns[2] = {grid.dims[0], grid.dims[1]};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
        auto& out = found.local();
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            const Vec3d &A = local[f[0]], &B = local[f[1]], &C = local[f[2]];
            forEachColumnCrossing(A, B, C, 0.0, 1.0, columns, [&](uint32_t x, uint32_t y, double zc, bool facingUp) {
                const double k = std::ceil(zc);
                if (k >= dimZ) return;
                const auto kz = uint32_t(std::max(k, 0.0));
                const uint32_t i = index.find({x >> 3, y >> 3, kz >> 3});
                if (i == BrickIndex::kNone) return; // between no two centres the caller climbs
                const auto bit = uint16_t(((x & 7) << 6) | ((y & 7) << 3) | (kz & 7));
                out.push_back({i, bit, int16_t(facingUp ? -1 : 1)});
            });
        }
    });
    std::vector<Crossing> all;
    for (auto& part : found) all.insert(all.end(), part.begin(), part.end());
    tbb::parallel_sort(all.begin(), all.end(), [](const Crossing& a, const Crossing& b) {
        return std::tie(a.brick, a.voxel) < std::tie(b.brick, b.voxel);
    });
    return all;
}

} // namespace

namespace winding_boundary {

/// A boundary edge from a to b, m times (the sum of its triangles'
/// orientations: +1 for each a -> b, -1 for each b -> a).
struct Edge {
    Vec3d a, b;
    int64_t m;
};

/// The edges of the mesh whose triangles' orientations do not cancel
/// (weldedEdges: a mesh stored as separate triangles has the same boundary
/// as its welded self), in @a local's frame.
std::vector<Edge> boundaryEdges(const std::vector<Vec3d>& local, const TriangleMesh& mesh)
{
    std::vector<Edge> out;
    for (const WeldedEdge& e : weldedEdges(mesh))
        if (e.net != 0) out.push_back({local[e.lo], local[e.hi], e.net});
    return out;
}

struct Box {
    Vec3d lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    void add(const Vec3d& p)
    {
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    }
};

/// The gaps between two boxes along x, y and z (0 where they overlap).
Vec3d gaps(const Box& u, const Box& v)
{
    Vec3d g;
    for (int a = 0; a < 3; ++a) g[a] = std::max({0.0, u.lo[a] - v.hi[a], v.lo[a] - u.hi[a]});
    return g;
}

/// A bound on |r_xy| / |r|^3 over r = p - x, p and x in boxes with these
/// gaps: largest at the smallest vertical gap and at the horizontal gap
/// rho, or at rho = gap / sqrt 2 when rho may be that small. Infinity when
/// the boxes meet.
double zKernel(const Vec3d& g)
{
    const double rho = std::sqrt(g.x * g.x + g.y * g.y);
    if (rho == 0 && g.z == 0) return INFINITY;
    const double r2 = rho * rho + g.z * g.z;
    if (rho * rho * 2 >= g.z * g.z) return rho / (r2 * std::sqrt(r2));
    return 0.3849001794597505 / (g.z * g.z); // (1/sqrt 2) / (3/2)^(3/2)
}

/// A bound on 1 / |r|^2 (|r x dl| / |r|^3 per unit of dl) over r = p - x,
/// p and x in boxes with these gaps. Infinity when the boxes meet.
double fullKernel(const Vec3d& g)
{
    const double r2 = dot(g, g);
    return r2 == 0 ? INFINITY : 1.0 / r2;
}

/// Which part of the boundary's field a bound is of: its z component (a
/// column's climb), or the whole of it (a move in any direction).
enum class Part { Z, Whole };

double kernel(Part part, const Vec3d& g) { return part == Part::Z ? zKernel(g) : fullKernel(g); }

/// A bounding-volume tree over the boundary edges that bounds |dw/dz| over
/// a box: the field's z component is (1/4 pi) sum_e m_e int_e (dl x r)_z / |r|^3,
/// r = p - x (Biot-Savart), and (dl x r)_z is at most |dl_xy| |r_xy|. A node
/// far from the box bounds its edges at once, the lesser of
///  - direct: sum |m| |e_xy| times zKernel of the node's box, and
///  - moment: |N_xy| zKernel of its centre plus W R 2 / (d - R)^3, with N
///    the sum of m (b - a) (0 for whole loops), W the sum of |m| |e|, R the
///    radius of its ball about c and d the box's distance from c: the field
///    at p is N x K(p - c) plus, for each dl, K's change from c to x, at
///    most R sup |grad K| = R 2 / |r|^3 (K(r) = r / |r|^3).
/// Otherwise its children are bounded, or a leaf's edges one by one. The
/// whole field's bound is the same with |e| for |e_xy|, |N| for |N_xy| and
/// 1 / |r|^2 for the z kernel (|dl x r| <= |dl| |r|).
class BoundaryTree {
public:
    explicit BoundaryTree(std::vector<Edge> edges) : edges_(std::move(edges))
    {
        if (!edges_.empty()) build(0, uint32_t(edges_.size()));
    }

    bool empty() const { return edges_.empty(); }

    /// The bound on |dw/dz| (times 4 pi) over the box from the nodes far
    /// enough to bound at once; the edges of the others go to @a near. Past
    /// @a limit the search stops, with infinity.
    double farBound(const Box& box, std::vector<const Edge*>& near, double limit = INFINITY, Part part = Part::Z) const
    {
        double sum = 0;
        return nodeBound(0, box, near, sum, limit, part) ? sum : INFINITY;
    }

    /// The whole bound over the box (times 4 pi): the far nodes' and each
    /// near edge's; past @a limit, infinity.
    double bound(const Box& box, double limit, Part part) const
    {
        thread_local std::vector<const Edge*> near;
        near.clear();
        double sum = farBound(box, near, limit, part);
        for (size_t k = 0; k < near.size() && sum <= limit; ++k) sum += edgeBound(*near[k], box, part);
        return sum <= limit ? sum : INFINITY;
    }

    /// An edge's part of the bound over a box (times 4 pi); infinity where it meets the box.
    static double edgeBound(const Edge& e, const Box& box, Part part = Part::Z)
    {
        const Vec3d d = e.b - e.a;
        const double length = double(std::abs(e.m)) * std::sqrt(d.x * d.x + d.y * d.y + (part == Part::Z ? 0.0 : d.z * d.z));
        if (length == 0) return 0; // along z (or of no length): no field about z
        Box edge;
        edge.add(e.a), edge.add(e.b);
        return length * kernel(part, gaps(box, edge));
    }

private:
    static constexpr uint32_t kLeaf = 4;
    /// A node's part of the bound below this (times 4 pi) is taken as it is.
    static constexpr double kEnough = 1e-2;

    struct Node {
        Box box;
        Vec3d c, n; // centre, sum of m (b - a)
        double r = 0, weight = 0, weightXY = 0;
        uint32_t first = 0, count = 0; // edges
        uint32_t left = 0, right = 0;  // children (0: a leaf)
    };

    uint32_t build(uint32_t first, uint32_t count)
    {
        const auto index = uint32_t(nodes_.size());
        nodes_.emplace_back();
        Node node;
        node.first = first, node.count = count;
        for (uint32_t i = first; i < first + count; ++i) {
            const Edge& e = edges_[i];
            node.box.add(e.a), node.box.add(e.b);
            const Vec3d d = e.b - e.a;
            node.n = node.n + double(e.m) * d;
            node.weight += double(std::abs(e.m)) * std::sqrt(dot(d, d));
            node.weightXY += double(std::abs(e.m)) * std::sqrt(d.x * d.x + d.y * d.y);
        }
        node.c = 0.5 * (node.box.lo + node.box.hi);
        for (uint32_t i = first; i < first + count; ++i)
            for (const Vec3d& p : {edges_[i].a, edges_[i].b}) node.r = std::max(node.r, std::sqrt(dot(p - node.c, p - node.c)));
        if (count > kLeaf) {
            int axis = 0;
            for (int a = 1; a < 3; ++a)
                if (node.box.hi[a] - node.box.lo[a] > node.box.hi[axis] - node.box.lo[axis]) axis = a;
            const uint32_t half = count / 2;
            std::nth_element(edges_.begin() + first, edges_.begin() + first + half, edges_.begin() + first + count,
                             [axis](const Edge& u, const Edge& v) { return u.a[axis] + u.b[axis] < v.a[axis] + v.b[axis]; });
            node.left = build(first, half);
            node.right = build(first + half, count - half);
        }
        nodes_[index] = node;
        return index;
    }

    /// Adds node i's part to `sum`; false once it passes `limit`.
    bool nodeBound(uint32_t i, const Box& box, std::vector<const Edge*>& near, double& sum, double limit,
                   Part part) const
    {
        const Node& node = nodes_[i];
        const double weight = part == Part::Z ? node.weightXY : node.weight;
        if (weight == 0) return true; // only edges along z
        double best = weight * kernel(part, gaps(box, node.box));
        Box centre;
        centre.add(node.c);
        const Vec3d g = gaps(box, centre);
        const double d = std::sqrt(dot(g, g));
        if (d > node.r) {
            const double n = std::sqrt(node.n.x * node.n.x + node.n.y * node.n.y + (part == Part::Z ? 0.0 : node.n.z * node.n.z));
            const double far = d - node.r;
            best = std::min(best, n * kernel(part, g) + node.weight * node.r * 2.0 / (far * far * far));
        }
        if (best < kEnough) {
            sum += best;
            return sum <= limit;
        }
        if (node.left == 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k) near.push_back(&edges_[k]);
            return true;
        }
        return nodeBound(node.left, box, near, sum, limit, part) && nodeBound(node.right, box, near, sum, limit, part);
    }

    std::vector<Edge> edges_;
    std::vector<Node> nodes_;
};

} // namespace winding_boundary

namespace {

using winding_boundary::BoundaryTree;
using winding_boundary::Box;
using winding_boundary::Edge;

/// The bounds of the columns of a square of the brick's footprint, from
/// x0, y0 and `size` wide: the near edges (near[from..]) bounded over each
/// quarter, those small there added to its far part, the rest carried down.
void columnBounds(double x0, double y0, double z0, uint32_t size, double far, std::vector<const Edge*>& near,
                  size_t from, std::array<float, 64>& out);

/// A bound (times 4 pi) in winding number per voxel, rounded up to a float.
float roundUp(double bound)
{
    const double b = bound * kInvFourPi * (1 + 1e-9);
    float s = float(b);
    if (double(s) < b) s = std::nextafter(s, INFINITY);
    return s;
}

void columnBounds(double x0, double y0, double z0, uint32_t size, double far, std::vector<const Edge*>& near,
                  size_t from, std::array<float, 64>& out)
{
    // An edge's part below this (times 4 pi) is added to the square's far part.
    constexpr double kSmall = 1e-3;
    const size_t end = near.size();
    for (uint32_t q = 0; q < 4; ++q) {
        const uint32_t half = size / 2;
        const double qx = x0 + (q & 1) * half, qy = y0 + (q >> 1) * half;
        Box box;
        box.add({qx, qy, z0 - 1}), box.add({qx + half - 1, qy + half - 1, z0 + 7});
        double part = far;
        for (size_t k = from; k < end; ++k) {
            const double b = BoundaryTree::edgeBound(*near[k], box);
            if (half > 1 && b < kSmall) part += b;
            else if (half > 1) near.push_back(near[k]);
            else part += b;
        }
        if (half > 1) columnBounds(qx, qy, z0, half, part, near, end, out);
        else out[(uint32_t(qx) & 7) * 8 + (uint32_t(qy) & 7)] = roundUp(part);
        near.resize(end);
    }
}

} // namespace

WindingColumns windingColumns(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                              const std::vector<BrickCoord>& bricks)
{
    std::array<uint32_t, 3> limit{};
    for (int a = 0; a < 3; ++a) limit[a] = (grid.dims[a] + 7) / 8;
    WindingColumns out;
    out.slope.assign(bricks.size(), 0.0f);
    std::vector<uint32_t> overflow;

    // Jumps: the crossings of each voxel summed (int16; a brick whose sum
    // would overflow is left to the walk by an infinite slope).
    const std::vector<Crossing> crossings = crossingsOf(local, mesh, grid, BrickIndex(bricks, limit));
    out.first.assign(bricks.size() + 1, 0);
    for (size_t n = 0; n < crossings.size();) {
        size_t m = n;
        int32_t sum = 0;
        for (; m < crossings.size() && crossings[m].brick == crossings[n].brick && crossings[m].voxel == crossings[n].voxel; ++m)
            sum += crossings[m].jump;
        if (std::abs(sum) > std::numeric_limits<int16_t>::max()) overflow.push_back(crossings[n].brick);
        else if (sum != 0) {
            out.jumps.push_back({crossings[n].voxel, int16_t(sum)});
            ++out.first[crossings[n].brick + 1];
        }
        n = m;
    }
    for (size_t i = 0; i < bricks.size(); ++i) out.first[i + 1] += out.first[i];

    out.columnsAt.assign(bricks.size(), WindingColumns::kWholeBrick);
    const BoundaryTree boundary(winding_boundary::boundaryEdges(local, mesh));
    if (!boundary.empty()) {
        // Bricks in chunks, each chunk's column slopes kept in its order.
        constexpr size_t kChunk = 256;
        std::vector<std::vector<std::pair<uint32_t, std::array<float, 64>>>> perChunk((bricks.size() + kChunk - 1) / kChunk);
        tbb::parallel_for(size_t(0), perChunk.size(), [&](size_t chunk) {
            std::vector<const Edge*> near;
            for (size_t i = chunk * kChunk; i < std::min(bricks.size(), (chunk + 1) * kChunk); ++i) {
                const auto& b = bricks[i];
                const double x0 = 8.0 * b[0], y0 = 8.0 * b[1], z0 = 8.0 * b[2];
                Box box;
                box.add({x0, y0, z0 - 1}), box.add({x0 + 7, y0 + 7, z0 + 7});
                near.clear();
                const double far = boundary.farBound(box, near);
                if (near.empty()) {
                    out.slope[i] = roundUp(far);
                    continue;
                }
                std::array<float, 64> columns;
                columnBounds(x0, y0, z0, 8, far, near, 0, columns);
                out.slope[i] = *std::max_element(columns.begin(), columns.end());
                perChunk[chunk].push_back({uint32_t(i), columns});
            }
        });
        for (const auto& chunk : perChunk)
            for (const auto& [i, columns] : chunk) {
                out.columnsAt[i] = uint32_t(out.columnSlope.size());
                out.columnSlope.insert(out.columnSlope.end(), columns.begin(), columns.end());
            }
    }
    // A brick whose jumps overflowed is walked whole.
    for (uint32_t i : overflow) out.slope[i] = INFINITY, out.columnsAt[i] = WindingColumns::kWholeBrick;
    return out;
}

BrickCentreColumns brickCentreColumns(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                                      const BrickBox* box)
{
    BrickCentreColumns out;
    const BrickBox within = box ? withinGrid(grid, *box) : bricksMeeting(grid, std::nullopt);
    for (int a = 0; a < 3; ++a) out.origin[a] = within.lo[a], out.dims[a] = within.hi[a] - within.lo[a];
    const auto& d = out.dims;
    const uint64_t n = uint64_t(d[0]) * d[1] * d[2];
    if (n > (uint64_t(1) << 31))
        throw Unsupported(fmt::format("the grid's box holds {} bricks, more than the winding pass evaluates (2^31); use a "
                                      "coarser grid",
                                      n));
    out.jump.assign(n, 0);
    const auto at = [&](uint64_t x, uint64_t y, uint64_t z) { return x + d[0] * (y + d[1] * z); };
    // Crossings of the columns through the box's brick centres, as crossingsOf's.
    const uint32_t from[2] = {out.origin[0], out.origin[1]}, to[2] = {out.origin[0] + d[0], out.origin[1] + d[1]};
    const auto& o = out.origin;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            const Vec3d &A = local[f[0]], &B = local[f[1]], &C = local[f[2]];
            forEachColumnCrossing(A, B, C, 3.5, 8.0, from, to, [&](uint32_t x, uint32_t y, double zc, bool facingUp) {
                const double k = std::ceil((zc - 3.5) / 8) - double(o[2]); // the first brick centre of the box above
                if (k <= 0 || k >= double(d[2])) return; // below the box's lowest (its walk counts it) or above all
                __atomic_fetch_add(&out.jump[at(x - o[0], y - o[1], uint64_t(k))], facingUp ? -1 : 1, __ATOMIC_RELAXED);
            });
        }
    });
    auto boundary = std::make_shared<const BoundaryTree>(winding_boundary::boundaryEdges(local, mesh));
    if (!boundary->empty()) out.boundary = std::move(boundary);
    return out;
}

namespace {

/// The origin, in voxels (8 b), of brick @a brick of a box of @a dims bricks
/// (x-fastest) from brick @a origin.
std::array<double, 3> brickOrigin(uint64_t brick, const std::array<uint32_t, 3>& origin,
                                  const std::array<uint32_t, 3>& dims)
{
    const uint64_t x = brick % dims[0], y = brick / dims[0] % dims[1], z = brick / (uint64_t(dims[0]) * dims[1]);
    return {8.0 * double(origin[0] + x), 8.0 * double(origin[1] + y), 8.0 * double(origin[2] + z)};
}

} // namespace

float BrickCentreColumns::slopeAt(uint64_t brick, double limit) const
{
    if (!boundary) return 0.0f;
    const auto o = brickOrigin(brick, origin, dims);
    Box segment; // from the centre below to this brick's
    segment.add({o[0] + 3.5, o[1] + 3.5, o[2] - 4.5}), segment.add({o[0] + 3.5, o[1] + 3.5, o[2] + 3.5});
    const double sum = boundary->bound(segment, limit / kInvFourPi, winding_boundary::Part::Z);
    return std::isfinite(sum) ? roundUp(sum) : INFINITY;
}

float BrickCentreColumns::gradientAt(uint64_t brick) const
{
    if (!boundary) return 0.0f;
    const auto o = brickOrigin(brick, origin, dims);
    Box box; // the brick's centres
    box.add({o[0], o[1], o[2]}), box.add({o[0] + 7, o[1] + 7, o[2] + 7});
    const double sum = boundary->bound(box, INFINITY, winding_boundary::Part::Whole);
    return std::isfinite(sum) ? roundUp(sum) : INFINITY;
}

} // namespace svo
