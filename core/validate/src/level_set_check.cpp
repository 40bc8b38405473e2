#include "svo/validate/level_set_check.h"

#include <CGAL/Side_of_triangle_mesh.h>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <mutex>
#include <tbb/parallel_for.h>

#include "closed_surface.h"
#include "local_points.h"
#include "triangle_distances.h"

namespace svo::validate {
namespace {

using K = detail::K;
using Side = CGAL::Side_of_triangle_mesh<detail::SurfaceMesh, K>;
using Index = std::array<int32_t, 3>;

/// CGAL's view of the mesh in the grid's local frame: distances always, sides when closed.
class Reference {
public:
    Reference(const TriangleMesh& mesh, const GridSpec& grid)
        : grid_(grid), points_(detail::localPoints(mesh, grid)), distances_(mesh, points_),
          closed_(detail::closedSurface(mesh, points_))
    {
        if (closed_.closed) {
            side_ = std::make_unique<Side>(closed_.surface);
            (void)(*side_)(points_.front()); // builds its tree before parallel queries
        }
    }
    bool hasSide() const { return side_ != nullptr; }
    const std::string& why() const { return closed_.reason; }
    /// A voxel centre in local coordinates.
    K::Point_3 centre(const std::array<int64_t, 3>& global) const
    {
        return K::Point_3(double(global[0] - grid_.anchor[0]), double(global[1] - grid_.anchor[1]),
                          double(global[2] - grid_.anchor[2]));
    }
    double distance(const K::Point_3& p) const { return distances_.distance(p); }
    int64_t triangle(const K::Point_3& p) const { return distances_.nearest(p).triangle; }
    /// 1 inside, 0 outside or on the surface.
    int side(const K::Point_3& p) const { return (*side_)(p) == CGAL::ON_BOUNDED_SIDE ? 1 : 0; }

private:
    const GridSpec& grid_;
    std::vector<K::Point_3> points_;
    detail::TriangleDistances distances_;
    detail::ClosedSurface closed_;
    std::unique_ptr<Side> side_;
};

std::array<int64_t, 3> wide(const Index& i) { return {i[0], i[1], i[2]}; }

/// What one active voxel showed.
struct Active {
    double exact = 0; ///< unsigned, voxels
    double error = 0;
    int side = -1;
    bool wrongSign = false, extra = false;
};

/// Keeps the `n` cases that rank first by `before`, in that order.
template <typename Before>
void keepWorst(std::vector<LevelSetCase>& cases, size_t n, Before before)
{
    std::sort(cases.begin(), cases.end(), before);
    if (cases.size() > n) cases.resize(n);
}

} // namespace

LevelSetCheck checkLevelSet(const TriangleMesh& mesh, const GridSpec& grid, const std::vector<LevelSetVoxel>& voxels,
                            const LevelSetCheckOptions& o)
{
    for (double w : {o.exteriorBand, o.interiorBand})
        if (!(w > 0) || !std::isfinite(w))
            throw InvalidInput(fmt::format("level set check: a band of {} voxels; bands must be positive and finite", w));
    if (!(o.tolerance >= 0) || !std::isfinite(o.tolerance))
        throw InvalidInput(fmt::format("level set check: tolerance {} voxels; it must be zero or positive and finite",
                                       o.tolerance));
    const double h = o.voxelSize > 0 ? o.voxelSize : grid.voxelSize;
    if (!(h > 0) || !std::isfinite(h)) throw InvalidInput(fmt::format("level set check: voxel size {} is not positive", h));
    validateMesh(mesh);
    const double tau = o.tolerance;

    // The active voxels sorted by index, to find them from the band scan.
    std::vector<LevelSetVoxel> active = voxels;
    std::sort(active.begin(), active.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
    for (size_t i = 1; i < active.size(); ++i)
        if (active[i].index == active[i - 1].index)
            throw InvalidInput(fmt::format("level set check: voxel [{}, {}, {}] is listed twice", active[i].index[0],
                                           active[i].index[1], active[i].index[2]));
    auto isActive = [&](const Index& i) {
        return std::binary_search(active.begin(), active.end(), LevelSetVoxel{i, 0},
                                  [](const auto& a, const auto& b) { return a.index < b.index; });
    };

    const Reference ref(mesh, grid);
    LevelSetCheck r;
    r.voxels = active.size();
    r.tolerance = tau;
    r.signChecked = ref.hasSide();
    if (!r.signChecked) r.signReason = ref.why();
    const double wideBand = std::max(o.exteriorBand, o.interiorBand);
    const double narrowBand = std::min(o.exteriorBand, o.interiorBand);

    // Active voxels: distance error, side, and whether the band holds them.
    std::vector<Active> seen(active.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, active.size(), 256), [&](const auto& range) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const auto p = ref.centre(wide(active[i].index));
            const double value = double(active[i].value) / h;
            Active& a = seen[i];
            a.exact = ref.distance(p);
            a.error = std::isfinite(value) ? std::abs(std::abs(value) - a.exact) : INFINITY;
            const bool valueInside = std::signbit(value);
            a.side = ref.hasSide() ? ref.side(p) : -1;
            a.wrongSign = a.side >= 0 && valueInside != (a.side == 1);
            // The band of the reference's side; without one, of the value's.
            const bool inside = a.side >= 0 ? a.side == 1 : valueInside;
            a.extra = a.exact > (inside ? o.interiorBand : o.exteriorBand) + tau;
        }
    });
    double sumSquares = 0;
    std::vector<LevelSetCase> errors, signs, extras;
    auto caseOf = [&](const LevelSetVoxel& v, const Active& a) {
        LevelSetCase c;
        c.index = wide(v.index);
        c.value = double(v.value) / h;
        c.side = a.side;
        c.exact = a.side == 1 ? -a.exact : a.exact;
        return c;
    };
    for (size_t i = 0; i < active.size(); ++i) {
        const Active& a = seen[i];
        r.maxError = std::max(r.maxError, a.error);
        sumSquares += a.error * a.error;
        r.overTolerance += !(a.error <= tau);
        if (a.wrongSign) (a.exact > tau ? r.signDisagreements : r.signNearSurface) += 1;
        r.extra += a.extra;
        if (a.wrongSign && a.exact > tau) signs.push_back(caseOf(active[i], a));
        if (a.extra) extras.push_back(caseOf(active[i], a));
    }
    r.rmsError = active.empty() ? 0.0 : std::sqrt(sumSquares / double(active.size()));
    std::vector<size_t> order(active.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    const size_t nWorst = std::min(o.worst, order.size());
    std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(nWorst), order.end(),
                      [&](size_t x, size_t y) { return seen[x].error > seen[y].error; });
    for (size_t i = 0; i < nWorst; ++i) errors.push_back(caseOf(active[order[i]], seen[order[i]]));
    keepWorst(signs, o.worst, [](const auto& x, const auto& y) { return std::abs(x.exact) > std::abs(y.exact); });
    keepWorst(extras, o.worst, [](const auto& x, const auto& y) { return std::abs(x.exact) > std::abs(y.exact); });

    // Inactive voxels that may lie in the band: every centre within the wider
    // band of a triangle lies within it of the mesh's box, so blocks of 8^3
    // centres over that box grown by the band, each skipped when its middle is
    // too far for any of its centres to reach the band.
    const Bounds b = mesh.bounds();
    const Vec3d lo = grid.toLocal(b.min), hi = grid.toLocal(b.max);
    const int64_t reach = int64_t(std::ceil(wideBand + tau)) + 1;
    const std::array<int64_t, 3> first = {int64_t(std::floor(lo.x)) - reach, int64_t(std::floor(lo.y)) - reach,
                                          int64_t(std::floor(lo.z)) - reach};
    const std::array<int64_t, 3> last = {int64_t(std::ceil(hi.x)) + reach, int64_t(std::ceil(hi.y)) + reach,
                                         int64_t(std::ceil(hi.z)) + reach};
    std::array<int64_t, 3> blocks{};
    for (int a = 0; a < 3; ++a) blocks[size_t(a)] = (last[size_t(a)] - first[size_t(a)]) / 8 + 1;
    const uint64_t nBlocks = uint64_t(blocks[0]) * uint64_t(blocks[1]) * uint64_t(blocks[2]);
    std::mutex lock;
    std::vector<LevelSetCase> missing;
    const auto deepestFirst = [](const LevelSetCase& x, const LevelSetCase& y) {
        return std::abs(x.exact) < std::abs(y.exact) || (std::abs(x.exact) == std::abs(y.exact) && x.index < y.index);
    };
    uint64_t candidates = 0, unjudged = 0, missed = 0;
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, nBlocks, 16), [&](const auto& range) {
        uint64_t localCandidates = 0, localUnjudged = 0, localMissed = 0;
        std::vector<LevelSetCase> localMissing;
        for (uint64_t n = range.begin(); n != range.end(); ++n) {
            const std::array<int64_t, 3> bl = {int64_t(n / uint64_t(blocks[1] * blocks[2])),
                                               int64_t(n / uint64_t(blocks[2]) % uint64_t(blocks[1])),
                                               int64_t(n % uint64_t(blocks[2]))};
            std::array<int64_t, 3> from{}, to{}; // local centres, inclusive
            double halfDiagonal = 0;
            for (size_t a = 0; a < 3; ++a) {
                from[a] = first[a] + 8 * bl[a];
                to[a] = std::min(from[a] + 7, last[a]);
                halfDiagonal += 0.25 * double(to[a] - from[a]) * double(to[a] - from[a]);
            }
            const K::Point_3 middle(0.5 * double(from[0] + to[0]), 0.5 * double(from[1] + to[1]),
                                    0.5 * double(from[2] + to[2]));
            // 1e-9 covers the rounding of the middle's distance.
            if (ref.distance(middle) - std::sqrt(halfDiagonal) > wideBand + tau + 1e-9) continue;
            for (int64_t x = from[0]; x <= to[0]; ++x)
                for (int64_t y = from[1]; y <= to[1]; ++y)
                    for (int64_t z = from[2]; z <= to[2]; ++z) {
                        const std::array<int64_t, 3> global = {x + grid.anchor[0], y + grid.anchor[1],
                                                               z + grid.anchor[2]};
                        if (isActive({int32_t(global[0]), int32_t(global[1]), int32_t(global[2])})) continue;
                        ++localCandidates;
                        const K::Point_3 p{static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)};
                        const double d = ref.distance(p);
                        if (d >= wideBand - tau) continue; // in no band, or within tau of its edge
                        int side = -1;
                        double w = narrowBand;
                        if (d >= narrowBand - tau) { // the side decides the band
                            if (!ref.hasSide()) {
                                ++localUnjudged;
                                continue;
                            }
                            side = ref.side(p);
                            w = side == 1 ? o.interiorBand : o.exteriorBand;
                        }
                        if (d >= w - tau) continue;
                        ++localMissed;
                        if (side < 0 && ref.hasSide()) side = ref.side(p);
                        LevelSetCase c;
                        c.index = global;
                        c.value = std::numeric_limits<double>::quiet_NaN();
                        c.side = side;
                        c.exact = side == 1 ? -d : d;
                        localMissing.push_back(c);
                        if (localMissing.size() > 4 * o.worst + 64) keepWorst(localMissing, o.worst, deepestFirst);
                    }
        }
        const std::lock_guard<std::mutex> guard(lock);
        candidates += localCandidates;
        unjudged += localUnjudged;
        missed += localMissed;
        missing.insert(missing.end(), localMissing.begin(), localMissing.end());
    });
    r.candidates = candidates;
    r.bandUnjudged = unjudged;
    r.missing = missed;
    // Active voxels outside the scanned box are beyond every band: counted as extra above.
    keepWorst(missing, o.worst, deepestFirst);

    for (auto* list : {&errors, &signs, &missing, &extras})
        for (auto& c : *list) c.triangle = ref.triangle(ref.centre(c.index));
    r.worstError = std::move(errors);
    r.worstSign = std::move(signs);
    r.worstMissing = std::move(missing);
    r.worstExtra = std::move(extras);
    return r;
}

} // namespace svo::validate
