#include "svo/validate/level_set_peer.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <CGAL/Side_of_triangle_mesh.h>

#include "closed_surface.h"
#include "local_points.h"
#include "triangle_distances.h"

namespace svo::validate {
namespace {

using Index = std::array<int32_t, 3>;

/// One voxel active in OpenVDB's level set, and ours there if any.
struct Pair {
    Index index{};
    double theirs = 0;            ///< voxels
    double ours = 0;              ///< voxels, when `both`
    bool both = false;            ///< ours is active here too
};

/// [least, largest] of the values, {0, 0} when none.
std::array<double, 2> rangeOf(const std::vector<double>& v)
{
    if (v.empty()) return {0, 0};
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return {*lo, *hi};
}

} // namespace

OpenVdbComparison compareWithOpenVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                     const std::vector<LevelSetVoxel>& voxels, const LevelSetCheckOptions& o)
{
    for (double w : {o.exteriorBand, o.interiorBand})
        if (!(w > 0) || !std::isfinite(w))
            throw InvalidInput(fmt::format("OpenVDB comparison: a band of {} voxels; bands must be positive and finite", w));
    validateMesh(mesh);
    const double h = o.voxelSize > 0 ? o.voxelSize : grid.voxelSize;
    const double tau = o.tolerance;

    // OpenVDB's level set: float points in the grid's frame, the grid's transform.
    openvdb::initialize();
    std::vector<openvdb::Vec3s> points;
    points.reserve(mesh.positions.size());
    for (const auto& p : mesh.positions) points.emplace_back(float(p.x), float(p.y), float(p.z));
    std::vector<openvdb::Vec3I> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
    OpenVdbComparison c;
    openvdb::FloatGrid::Ptr theirs;
    try {
        const auto t0 = std::chrono::steady_clock::now();
        // The grid's own transform: its voxel size, then its whole-voxel translation.
        const auto xform = openvdb::math::Transform::createLinearTransform(grid.voxelSize);
        const auto t = grid.translation();
        xform->postTranslate(openvdb::Vec3d(t[0], t[1], t[2]));
        theirs = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
            *xform, points, triangles, {}, float(o.exteriorBand), float(o.interiorBand));
        c.openvdbSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } catch (const openvdb::Exception& e) {
        throw DeviceError(fmt::format("{}: OpenVDB's meshToSignedDistanceField failed: {}", mesh.source, e.what()));
    }

    std::vector<LevelSetVoxel> ours = voxels;
    std::sort(ours.begin(), ours.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
    std::vector<Pair> pairs;
    pairs.reserve(size_t(theirs->activeVoxelCount()));
    std::vector<char> matched(ours.size(), 0);
    for (auto it = theirs->cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue()) continue; // meshToVolume makes no active tiles
        const openvdb::Coord x = it.getCoord();
        Pair p;
        p.index = {x.x(), x.y(), x.z()};
        p.theirs = double(*it) / grid.voxelSize;
        const auto at = std::lower_bound(ours.begin(), ours.end(), LevelSetVoxel{p.index, 0},
                                         [](const auto& a, const auto& b) { return a.index < b.index; });
        if (at != ours.end() && at->index == p.index) {
            p.ours = double(at->value) / h;
            p.both = true;
            matched[size_t(at - ours.begin())] = 1;
        }
        pairs.push_back(p);
    }

    // CGAL's distance at every voxel of either level set.
    const detail::TriangleDistances exact(mesh, detail::localPoints(mesh, grid));
    auto exactAt = [&](const Index& i) {
        return exact.distance(detail::K::Point_3(double(i[0] - grid.anchor[0]), double(i[1] - grid.anchor[1]),
                                                 double(i[2] - grid.anchor[2])));
    };
    std::vector<double> pairExact(pairs.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size(), 256), [&](const auto& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) pairExact[i] = exactAt(pairs[i].index);
    });
    std::vector<size_t> unmatched;
    for (size_t i = 0; i < ours.size(); ++i)
        if (!matched[i]) unmatched.push_back(i);
    std::vector<double> onlyOursExact(unmatched.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, unmatched.size(), 256), [&](const auto& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) onlyOursExact[i] = exactAt(ours[unmatched[i]].index);
    });

    c.ours = ours.size();
    c.openvdb = pairs.size();
    c.onlyOurs = unmatched.size();
    std::vector<double> onlyTheirsExact;
    std::vector<size_t> signDiffer;
    for (size_t i = 0; i < pairs.size(); ++i) {
        const Pair& p = pairs[i];
        if (!p.both) {
            onlyTheirsExact.push_back(pairExact[i]);
            continue;
        }
        ++c.common;
        if (std::abs(p.ours) > tau && std::abs(p.theirs) > tau && std::signbit(p.ours) != std::signbit(p.theirs))
            signDiffer.push_back(i);
        c.maxDifference = std::max(c.maxDifference, std::abs(std::abs(p.ours) - std::abs(p.theirs)));
        const double eOurs = std::abs(std::abs(p.ours) - pairExact[i]);
        const double eTheirs = std::abs(std::abs(p.theirs) - pairExact[i]);
        c.maxErrorOurs = std::max(c.maxErrorOurs, eOurs);
        c.maxErrorOpenVdb = std::max(c.maxErrorOpenVdb, eTheirs);
        c.oursFarther += eOurs > eTheirs + tau;
    }
    c.onlyOpenVdb = onlyTheirsExact.size();
    c.signDisagreements = signDiffer.size();
    for (size_t i : signDiffer) c.signFarthest = std::max(c.signFarthest, pairExact[i]);
    // Who is right where the signs differ: CGAL's side, when the mesh has one.
    if (!signDiffer.empty()) {
        const detail::ClosedSurface closed = detail::closedSurface(mesh, detail::localPoints(mesh, grid));
        if (closed.closed) {
            const CGAL::Side_of_triangle_mesh<detail::SurfaceMesh, detail::K> side(closed.surface);
            c.signJudged = true;
            for (size_t i : signDiffer) {
                const Index& x = pairs[i].index;
                const bool inside = side(detail::K::Point_3(double(x[0] - grid.anchor[0]), double(x[1] - grid.anchor[1]),
                                                            double(x[2] - grid.anchor[2]))) == CGAL::ON_BOUNDED_SIDE;
                c.signOursRight += inside == std::signbit(pairs[i].ours);
            }
        }
    }
    c.onlyOursExact = rangeOf(onlyOursExact);
    c.onlyOpenVdbExact = rangeOf(onlyTheirsExact);
    return c;
}

} // namespace svo::validate
