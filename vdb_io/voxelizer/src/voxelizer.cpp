#include "svo/voxelizer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <utility>

#include "svo/core/error.h"
#include "svo/core/interrupt.h"
#include "svo/gl/voxelize_pipeline.h"
#include "voxelizer_state.h"

namespace svo {
namespace {

using detail::Clock;
using detail::InterruptScope;
using detail::msSince;

/// A uniform scale h with a translation of exactly h * shift (whole voxels):
/// the lattices svo's GridSpec, .svo files and makeTransform describe.
bool wholeVoxelLattice(const openvdb::Mat4d& m, double& voxelSize, std::array<int64_t, 3>& shift)
{
    const double h = m(0, 0);
    if (!(h > 0) || !std::isfinite(h)) return false;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (m(r, c) != (r == c ? h : 0.0)) return false;
    for (int a = 0; a < 3; ++a) {
        const double t = m(3, a), s = std::round(t / h);
        if (!(std::abs(s) < 9.0e15) || h * s != t) return false; // must reproduce t exactly
        shift[a] = int64_t(s);
    }
    voxelSize = h;
    return true;
}

/// The triangles (quads split along 0-2) and the positions in double, as
/// given; indices checked, the first bad one named.
template <typename PointT>
TriangleMesh worldMesh(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                       const std::vector<openvdb::Vec4I>& quads)
{
    TriangleMesh m;
    m.source = "input mesh";
    const uint64_t n = points.size();
    auto checked = [&](uint64_t face, const char* kind, uint32_t i) {
        if (i >= n)
            throw InvalidInput(fmt::format("{} {} refers to vertex {}, but the mesh has {} points", kind, face, i, n));
        return i;
    };
    // Triangles in parallel; a bad index is looked for again in order, so the message names the first.
    m.triangles.resize(triangles.size());
    std::atomic<bool> anyBad{false};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = triangles[t];
            if (f[0] >= n || f[1] >= n || f[2] >= n) anyBad.store(true, std::memory_order_relaxed);
            m.triangles[t] = {f[0], f[1], f[2]};
        }
    });
    if (anyBad)
        for (size_t t = 0; t < triangles.size(); ++t)
            for (int c = 0; c < 3; ++c) checked(t, "triangle", triangles[t][c]);
    m.triangles.reserve(triangles.size() + 2 * quads.size());
    for (size_t q = 0; q < quads.size(); ++q) {
        const auto& f = quads[q];
        const uint32_t a = checked(q, "quad", f[0]), b = checked(q, "quad", f[1]), c = checked(q, "quad", f[2]);
        m.triangles.push_back({a, b, c});
        if (f[3] != openvdb::util::INVALID_IDX) m.triangles.push_back({a, c, checked(q, "quad", f[3])});
    }
    m.positions.resize(n);
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, n, 4096), [&](const tbb::blocked_range<uint64_t>& r) {
        for (uint64_t i = r.begin(); i != r.end(); ++i)
            m.positions[i] = {double(points[i][0]), double(points[i][1]), double(points[i][2])};
    });
    return m;
}

template <typename PointT>
IndexSpaceMesh prepare(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                       const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform)
{
    if (!xform.isLinear())
        throw InvalidInput(fmt::format("the transform is a {} map, which is not linear; svo voxelizes in the index space "
                                       "of linear (affine) transforms only",
                                       xform.baseMap()->type()));
    IndexSpaceMesh out;
    out.mesh = worldMesh(points, triangles, quads);
    TriangleMesh& m = out.mesh;
    const uint64_t n = points.size();

    const openvdb::Mat4d mat = xform.baseMap()->getAffineMap()->getMat4();
    double h = 1.0;
    std::array<int64_t, 3> shift{};
    // On the transform's lattice the world coordinates stay: GridSpec::toIndex maps them.
    if (!wholeVoxelLattice(mat, h, shift)) {
        // Index space directly: subtract the translation first, where it is
        // exact for a mesh near it, then apply the inverse of the linear part.
        const openvdb::Vec3d t = mat.getTranslation();
        const openvdb::Mat3d inv = mat.getMat3().inverse();
        if (!std::isfinite(inv.det()) || inv.det() == 0.0)
            throw InvalidInput("the transform's linear part is singular; it has no index space to voxelize in");
        tbb::parallel_for(tbb::blocked_range<uint64_t>(0, n, 4096), [&](const tbb::blocked_range<uint64_t>& r) {
            for (uint64_t i = r.begin(); i != r.end(); ++i) {
                const openvdb::Vec3d p =
                    openvdb::Vec3d(double(points[i][0]), double(points[i][1]), double(points[i][2])) - t;
                const openvdb::Vec3d idx = p * inv; // OpenVDB's row-vector convention: world = index * M + t
                m.positions[i] = {idx[0], idx[1], idx[2]};
            }
        });
    }
    validateMesh(m);
    out.grid = makeGridOnLattice(m, h, shift);
    return out;
}

/// The end every call shares: the last checkpoint, the statistics handed over.
Octree finish(Octree octree, VoxelizeStats& stats, const VoxelizeOptions& options, const Checkpoint& checkpoint)
{
    checkpoint(1.0, "finish");
    if (options.stats) *options.stats = std::move(stats);
    return octree;
}

template <typename PointT>
openvdb::MaskGrid::Ptr toMask(Voxelizer& v, const std::vector<PointT>& points,
                              const std::vector<openvdb::Vec3I>& triangles, const std::vector<openvdb::Vec4I>& quads,
                              const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    GridOptions g;
    g.attributes = false;
    const Octree o = v.meshToOctree(points, triangles, quads, xform, options);
    return openvdb::gridPtrCast<openvdb::MaskGrid>(octreeToGrids(o, g, xform.copy()).front());
}

} // namespace

TriangleMesh toTriangleMesh(const std::vector<openvdb::Vec3d>& points, const std::vector<openvdb::Vec3I>& triangles,
                            const std::vector<openvdb::Vec4I>& quads)
{
    TriangleMesh m = worldMesh(points, triangles, quads);
    validateMesh(m);
    return m;
}

TriangleMesh toTriangleMesh(const std::vector<openvdb::Vec3s>& points, const std::vector<openvdb::Vec3I>& triangles,
                            const std::vector<openvdb::Vec4I>& quads)
{
    TriangleMesh m = worldMesh(points, triangles, quads);
    validateMesh(m);
    return m;
}

IndexSpaceMesh prepareMesh(const std::vector<openvdb::Vec3d>& points, const std::vector<openvdb::Vec3I>& triangles,
                           const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform)
{
    return prepare(points, triangles, quads, xform);
}

IndexSpaceMesh prepareMesh(const std::vector<openvdb::Vec3s>& points, const std::vector<openvdb::Vec3I>& triangles,
                           const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform)
{
    return prepare(points, triangles, quads, xform);
}

Voxelizer::Voxelizer(const DeviceOptions& device) : device_(device) {}
Voxelizer::~Voxelizer() = default;
Voxelizer::Voxelizer(Voxelizer&&) noexcept = default;
Voxelizer& Voxelizer::operator=(Voxelizer&&) noexcept = default;

Octree Voxelizer::voxelize(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                           std::vector<uint64_t>* voxelList)
{
    validateMesh(mesh);
    checkGrid(grid, mesh.source);
    return voxelizeChecked(mesh, grid, options, voxelList);
}

Octree Voxelizer::voxelizeChecked(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                  std::vector<uint64_t>* voxelList)
{
    const InterruptScope interrupt(options.interrupter, "svo: voxelizing a mesh");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    Octree octree = gl::voxelizeMesh(device_, mesh, grid, options, checkpoint, stats, voxelList);
    octree.madeBy = {stats.backend, stats.mode, stats.renderer}; // a mesh's voxels: the record files carry
    return finish(std::move(octree), stats, options, checkpoint);
}

Octree Voxelizer::bricksToOctree(const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> bricks,
                                 const VoxelizeOptions& options)
{
    checkGrid(grid, "brick input");
    const InterruptScope interrupt(options.interrupter, "svo: building an octree");
    const Checkpoint checkpoint = interrupt.checkpoint();
    VoxelizeStats stats;
    Octree octree = gl::bricksToOctree(device_, grid, std::move(bricks), options.backend, checkpoint, stats);
    return finish(std::move(octree), stats, options, checkpoint);
}

Octree Voxelizer::gridToOctree(const openvdb::GridBase& grid, const VoxelizeOptions& options)
{
    vdb::GridBricks gb = vdb::gridToBricks(grid, grid.getName().empty() ? std::string("grid") : grid.getName());
    return bricksToOctree(gb.grid, std::move(gb.bricks), options);
}

openvdb::MaskGrid::Ptr Voxelizer::meshToMask(const std::vector<openvdb::Vec3s>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    return toMask(*this, points, triangles, {}, xform, options);
}

openvdb::MaskGrid::Ptr Voxelizer::meshToMask(const std::vector<openvdb::Vec3d>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    return toMask(*this, points, triangles, {}, xform, options);
}

openvdb::MaskGrid::Ptr Voxelizer::meshToMask(const std::vector<openvdb::Vec3s>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const std::vector<openvdb::Vec4I>& quads,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    return toMask(*this, points, triangles, quads, xform, options);
}

openvdb::MaskGrid::Ptr Voxelizer::meshToMask(const std::vector<openvdb::Vec3d>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const std::vector<openvdb::Vec4I>& quads,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    return toMask(*this, points, triangles, quads, xform, options);
}

Backend Voxelizer::backendFor(const VoxelizeOptions& options) { return gl::resolveBackend(device_, options, false); }

std::string Voxelizer::deviceDescription() { return device_.describe(); }

void Voxelizer::startDevice() { device_.start(); }

void Voxelizer::releaseScratch() { device_.releaseScratch(); }

// ---- The templates on OpenVDB point types: each maps the mesh with prepareMesh.


template <typename PointT>
Octree Voxelizer::meshToOctree(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                               const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform,
                               const VoxelizeOptions& options)
{
    const IndexSpaceMesh p = prepareMesh(points, triangles, quads, xform);
    return voxelizeChecked(p.mesh, p.grid, options, nullptr); // prepareMesh checked both
}

template <typename PointT>
openvdb::GridPtrVec Voxelizer::meshToGrids(const std::vector<PointT>& points,
                                           const std::vector<openvdb::Vec3I>& triangles,
                                           const openvdb::math::Transform& xform, const VoxelizeOptions& options,
                                           const GridOptions& grids)
{
    return octreeToGrids(meshToOctree(points, triangles, {}, xform, options), grids, xform.copy());
}

template <typename PointT>
openvdb::BoolGrid::Ptr Voxelizer::meshToBool(const std::vector<PointT>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    GridOptions g;
    g.topology = GridOptions::Topology::Bool;
    g.attributes = false;
    return openvdb::gridPtrCast<openvdb::BoolGrid>(meshToGrids(points, triangles, xform, options, g).front());
}

template <typename PointT>
openvdb::FloatGrid::Ptr Voxelizer::meshToFog(const std::vector<PointT>& points,
                                             const std::vector<openvdb::Vec3I>& triangles,
                                             const openvdb::math::Transform& xform, const VoxelizeOptions& options)
{
    GridOptions g;
    g.fog = true;
    g.attributes = false;
    return openvdb::gridPtrCast<openvdb::FloatGrid>(meshToGrids(points, triangles, xform, options, g).at(1));
}


template <typename PointT>
openvdb::FloatGrid::Ptr Voxelizer::meshToLevelSet(const std::vector<PointT>& points,
                                                  const std::vector<openvdb::Vec3I>& triangles,
                                                  const openvdb::math::Transform& xform, float exteriorBand,
                                                  float interiorBand, const VoxelizeOptions& options)
{
    const double scale = detail::uniformScale(xform);
    const IndexSpaceMesh p = prepareMesh(points, triangles, {}, xform);
    LevelSetOptions ls;
    ls.exteriorBand = exteriorBand;
    ls.interiorBand = interiorBand;
    return openvdb::gridPtrCast<openvdb::FloatGrid>(
        levelSetChecked(p.mesh, p.grid, ls, options, xform.copy(), scale).front());
}

template <typename PointT>
openvdb::FloatGrid::Ptr Voxelizer::meshToUnsignedDistanceField(const std::vector<PointT>& points,
                                                               const std::vector<openvdb::Vec3I>& triangles,
                                                               const openvdb::math::Transform& xform, float band,
                                                               const VoxelizeOptions& options)
{
    const double scale = detail::uniformScale(xform);
    const IndexSpaceMesh p = prepareMesh(points, triangles, {}, xform);
    LevelSetOptions ls;
    ls.exteriorBand = ls.interiorBand = band;
    ls.unsignedDistance = true;
    return openvdb::gridPtrCast<openvdb::FloatGrid>(
        levelSetChecked(p.mesh, p.grid, ls, options, xform.copy(), scale).front());
}

template <typename PointT>
openvdb::MaskGrid::Ptr Voxelizer::meshToSolid(const std::vector<PointT>& points,
                                              const std::vector<openvdb::Vec3I>& triangles,
                                              const openvdb::math::Transform& xform, const VoxelizeOptions& options,
                                              const SignOptions& sign)
{
    const IndexSpaceMesh p = prepareMesh(points, triangles, {}, xform);
    return solidChecked(p.mesh, p.grid, options, sign, xform.copy());
}


// The templates' two instantiations: single and double precision points.
#define SVO_INSTANTIATE(PointT)                                                                                      \
    template openvdb::BoolGrid::Ptr Voxelizer::meshToBool(const std::vector<PointT>&,                               \
                                                          const std::vector<openvdb::Vec3I>&,                        \
                                                          const openvdb::math::Transform&, const VoxelizeOptions&);  \
    template openvdb::FloatGrid::Ptr Voxelizer::meshToFog(const std::vector<PointT>&,                               \
                                                          const std::vector<openvdb::Vec3I>&,                        \
                                                          const openvdb::math::Transform&, const VoxelizeOptions&);  \
    template openvdb::GridPtrVec Voxelizer::meshToGrids(const std::vector<PointT>&, const std::vector<openvdb::Vec3I>&, \
                                                        const openvdb::math::Transform&, const VoxelizeOptions&,     \
                                                        const GridOptions&);                                          \
    template Octree Voxelizer::meshToOctree(const std::vector<PointT>&, const std::vector<openvdb::Vec3I>&,         \
                                            const std::vector<openvdb::Vec4I>&, const openvdb::math::Transform&,     \
                                            const VoxelizeOptions&);                                                  \
    template openvdb::FloatGrid::Ptr Voxelizer::meshToLevelSet(const std::vector<PointT>&,                          \
                                                               const std::vector<openvdb::Vec3I>&,                   \
                                                               const openvdb::math::Transform&, float, float,        \
                                                               const VoxelizeOptions&);                               \
    template openvdb::FloatGrid::Ptr Voxelizer::meshToUnsignedDistanceField(                                         \
        const std::vector<PointT>&, const std::vector<openvdb::Vec3I>&, const openvdb::math::Transform&, float,     \
        const VoxelizeOptions&);                                                                                      \
    template openvdb::MaskGrid::Ptr Voxelizer::meshToSolid(const std::vector<PointT>&,                              \
                                                           const std::vector<openvdb::Vec3I>&,                       \
                                                           const openvdb::math::Transform&, const VoxelizeOptions&,  \
                                                           const SignOptions&);
SVO_INSTANTIATE(openvdb::Vec3s)
SVO_INSTANTIATE(openvdb::Vec3d)
#undef SVO_INSTANTIATE

} // namespace svo
