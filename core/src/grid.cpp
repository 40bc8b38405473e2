#include "svo/core/grid.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "svo/core/error.h"

namespace svo {

Vec3d GridSpec::toIndex(const Vec3d& w) const
{
    // Subtract first: near the translation the difference is exact, so a mesh
    // moved by whole voxels maps to the very same index coordinates.
    const auto t = translation();
    return {(w.x - t[0]) / voxelSize, (w.y - t[1]) / voxelSize, (w.z - t[2]) / voxelSize};
}

Vec3d GridSpec::toLocal(const Vec3d& w) const
{
    const Vec3d i = toIndex(w);
    return {i.x - double(anchor[0]), i.y - double(anchor[1]), i.z - double(anchor[2])};
}

uint32_t GridSpec::maxDim() const { return std::max({dims[0], dims[1], dims[2]}); }

double GridSpec::epsilon() const { return 32.0 * std::ldexp(1.0, -24) * std::max<double>(maxDim(), 1.0); }

void checkResolution(double n, const std::string& name)
{
    if (n > double(kMaxGridDim) - 16 && std::isfinite(n))
        throw InvalidInput(name, fmt::format("{} is beyond the largest supported grid: a whole number from 1 to {}", n,
                                             kMaxGridDim - 16));
    if (!(n >= 1 && n <= double(kMaxGridDim) - 16) || n != std::floor(n))
        throw InvalidInput(name, fmt::format("must be a whole number from 1 to {}, got {}", kMaxGridDim - 16, n));
}

void checkVoxelSize(double h, const std::string& name)
{
    if (!(h > 0) || !std::isfinite(h))
        throw InvalidInput(name, fmt::format("must be a positive finite number, got {}", h));
}

GridSpec makeGrid(const TriangleMesh& mesh, const GridRequest& req)
{
    const Bounds b = mesh.bounds();
    if (b.empty()) throw InvalidInput(fmt::format("{}: the mesh has no triangles", mesh.source));
    GridSpec g;
    if (req.resolution > 0 && req.voxelSize > 0) throw InvalidInput("the grid request gives both a resolution and a voxel size; give one");
    if (req.resolution > 0) {
        checkResolution(double(req.resolution), "the resolution");
        const Vec3d e = b.extent();
        const double longest = std::max({e.x, e.y, e.z});
        if (!(longest > 0))
            throw InvalidInput(fmt::format("{}: the mesh has zero extent, so a resolution cannot define a voxel size; "
                                           "give a voxel size instead",
                                           mesh.source));
        g.voxelSize = longest / double(req.resolution);
    } else if (req.voxelSize != 0) {
        checkVoxelSize(req.voxelSize, "the voxel size");
        g.voxelSize = req.voxelSize;
    } else {
        throw InvalidInput(fmt::format("the grid needs a resolution N >= 1 or a finite voxel size h > 0; got "
                                       "resolution {} and voxel size {}",
                                       req.resolution, req.voxelSize));
    }
    if (!std::isfinite(g.voxelSize) || !(g.voxelSize > 0))
        throw InvalidInput(fmt::format("{}: the voxel size {} is not usable", mesh.source, g.voxelSize));

    // Shift the lattice by whole voxels when indices would approach int32 limits.
    const double limit = std::ldexp(1.0, 30);
    for (int a = 0; a < 3; ++a) {
        const double lo = b.min[a] / g.voxelSize, hi = b.max[a] / g.voxelSize;
        if (!std::isfinite(lo) || !std::isfinite(hi))
            throw InvalidInput(fmt::format("{}: the voxel size {} is too small for coordinates of magnitude {}", mesh.source,
                                           g.voxelSize, std::max(std::abs(b.min[a]), std::abs(b.max[a]))));
        if (std::abs(lo) > limit || std::abs(hi) > limit) {
            const double mid = std::round(0.5 * (lo + hi));
            if (std::abs(mid) > 9.0e18)
                throw InvalidInput(fmt::format("{}: coordinates of magnitude {} at voxel size {} exceed 64-bit indices",
                                               mesh.source, std::abs(b.max[a]), g.voxelSize));
            g.shift[a] = static_cast<int64_t>(mid);
        }
    }
    return makeGridOnLattice(mesh, g.voxelSize, g.shift);
}

GridSpec makeGridOnLattice(const TriangleMesh& mesh, double voxelSize, const std::array<int64_t, 3>& shift)
{
    const Bounds b = mesh.bounds();
    if (b.empty()) throw InvalidInput(fmt::format("{}: the mesh has no triangles", mesh.source));
    if (!std::isfinite(voxelSize) || !(voxelSize > 0))
        throw InvalidInput(fmt::format("{}: the voxel size {} is not usable", mesh.source, voxelSize));
    GridSpec g;
    g.voxelSize = voxelSize;
    g.shift = shift;
    // Anchor: a multiple of 8 at least one voxel below the lowest vertex, so that
    // every touched voxel (including those reached by the guard band) has a
    // local coordinate >= 0, and bricks align with OpenVDB leaves.
    const Vec3d lo = g.toIndex(b.min), hi = g.toIndex(b.max);
    for (int a = 0; a < 3; ++a) {
        if (!(std::abs(lo[a]) < 9.0e18) || !(std::abs(hi[a]) < 9.0e18) || hi[a] - lo[a] > double(kMaxGridDim))
            throw InvalidInput(fmt::format("{}: the grid would be {:.3g} voxels along axis {}, beyond the supported {}; "
                                           "use a larger voxel size",
                                           mesh.source, hi[a] - lo[a], "xyz"[a], kMaxGridDim));
        g.anchor[a] = floorTo8(static_cast<int64_t>(std::floor(lo[a])) - 1);
        const double top = hi[a] - double(g.anchor[a]);
        const double dim = std::floor(top) + 3; // the last touched voxel is <= top + 1
        if (dim > double(kMaxGridDim))
            throw InvalidInput(fmt::format("{}: the grid would be {} voxels along axis {}, beyond the supported {}; "
                                           "use a larger voxel size",
                                           mesh.source, dim, "xyz"[a], kMaxGridDim));
        g.dims[a] = static_cast<uint32_t>(dim);
        const int64_t lastGlobal = g.anchor[a] + int64_t(g.dims[a]);
        if (g.anchor[a] < INT32_MIN + 8 || lastGlobal > INT32_MAX - 8)
            throw InvalidInput(fmt::format("{}: voxel indices along {} would exceed OpenVDB's 32-bit coordinates",
                                           mesh.source, "xyz"[a]));
    }
    return g;
}

void checkGrid(const GridSpec& g, const std::string& what)
{
    if (!(g.voxelSize > 0) || !std::isfinite(g.voxelSize))
        throw InvalidInput(fmt::format("{}: voxel size {} is not positive and finite", what, g.voxelSize));
    for (int a = 0; a < 3; ++a) {
        if (g.dims[a] > kMaxGridDim || g.anchor[a] % 8 != 0)
            throw InvalidInput(fmt::format("{}: grid axis {} has {} voxels from anchor {} (at most {}, anchor a multiple of 8)",
                                           what, "xyz"[a], g.dims[a], g.anchor[a], kMaxGridDim));
        if (g.anchor[a] < INT32_MIN + 8 || g.anchor[a] + int64_t(g.dims[a]) > INT32_MAX - 8)
            throw InvalidInput(fmt::format("{}: voxel indices along {} exceed OpenVDB's 32-bit coordinates", what, "xyz"[a]));
        if (std::abs(double(g.shift[a])) > 9.0e18)
            throw InvalidInput(fmt::format("{}: the lattice shift along {} is out of range", what, "xyz"[a]));
    }
}

std::vector<Vec3f> localPositionsFloat(const TriangleMesh& mesh, const GridSpec& grid)
{
    std::vector<Vec3f> out(mesh.positions.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const Vec3d l = grid.toLocal(mesh.positions[i]);
            out[i] = {float(l.x), float(l.y), float(l.z)};
        }
    });
    return out;
}

} // namespace svo
