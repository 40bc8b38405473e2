#include "svo/core/voxel_attributes.h"

#include <cmath>
#include <fmt/format.h>
#include <unordered_map>

#include "svo/core/error.h"
#include "triangle_voxels.h"

namespace svo {

TriangleValues triangleValues(const TriangleMesh& mesh, bool colors)
{
    TriangleValues v;
    v.normals.reserve(mesh.triangles.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto p = mesh.corners(t);
        const Vec3d n = cross(p[1] - p[0], p[2] - p[0]);
        const double len = std::sqrt(dot(n, n));
        v.normals.push_back(len > 0 && std::isfinite(len) ? Vec3f{float(n.x / len), float(n.y / len), float(n.z / len)}
                                                          : Vec3f{0, 0, 0});
        if (colors && !mesh.colors.empty()) {
            const auto& f = mesh.triangles[t];
            const Vec3f& a = mesh.colors[f[0]];
            const Vec3f& b = mesh.colors[f[1]];
            const Vec3f& c = mesh.colors[f[2]];
            v.colors.push_back({(a.x + b.x + c.x) / 3.0f, (a.y + b.y + c.y) / 3.0f, (a.z + b.z + c.z) / 3.0f});
        }
    }
    return v;
}

int32_t toFixed(float v) { return int32_t(std::nearbyint(v * gpu::kFixedScale)); } // default mode: half to even

uint32_t availableChannels(const TriangleMesh& mesh, uint32_t channels)
{
    return mesh.colors.empty() ? channels & ~uint32_t(kColors) : channels;
}

VoxelAttributes finishAttributes(const std::vector<AttributeSums>& sums, uint32_t channels)
{
    using namespace gpu;
    for (const auto& s : sums)
        if (s[kSumCount] > kFixedMaxContributions)
            throw Unsupported(fmt::format("{} triangles cover one voxel, more than the {} the attribute sums hold; "
                                          "use a finer grid or leave out the attribute channels",
                                          s[kSumCount], kFixedMaxContributions));
    VoxelAttributes a;
    auto fixedVec = [](const AttributeSums& s, uint32_t at) {
        return Vec3f{float(int32_t(s[at])) / kFixedScale, float(int32_t(s[at + 1])) / kFixedScale,
                     float(int32_t(s[at + 2])) / kFixedScale};
    };
    for (const auto& s : sums) {
        if (channels & kTriangles) a.triangles.push_back(s[kSumTriangle] ? int32_t(~s[kSumTriangle]) : -1);
        if (channels & kNormals) {
            const Vec3f n = fixedVec(s, kSumNormal);
            const float len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
            a.normals.push_back(len > 0 ? Vec3f{n.x / len, n.y / len, n.z / len} : Vec3f{0, 0, 0});
        }
        if (channels & kColors) {
            const Vec3f c = fixedVec(s, kSumColor);
            const float k = s[kSumCount] ? 1.0f / float(s[kSumCount]) : 0.0f;
            a.colors.push_back({c.x * k, c.y * k, c.z * k});
        }
    }
    return a;
}

void attachAttributesCpu(const TriangleMesh& mesh, Octree& octree, uint32_t channels, double guard, VoxelMode mode)
{
    channels = availableChannels(mesh, channels);
    octree.attributes = {};
    if (!channels) return;
    // Voxel order: bricks in index order, bits ascending.
    std::unordered_map<uint64_t, uint64_t> slot;
    const auto offsets = brickVoxelOffsets(octree);
    for (const auto& r : occupiedBricks(octree)) {
        const Brick& b = octree.bricks[r.index];
        const uint64_t base = packVoxelKey(r.origin[0], r.origin[1], r.origin[2]);
        uint64_t at = offsets[r.index];
        for (uint32_t bit = 0; bit < 512; ++bit)
            if (b.words[bit >> 6] >> (bit & 63) & 1) slot[base | bit] = at++;
    }
    const TriangleValues tv = triangleValues(mesh, channels & kColors);
    std::vector<AttributeSums> sums(octree.voxelCount(), AttributeSums{});
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto p = mesh.corners(t);
        const Vec3d a = octree.grid.toLocal(p[0]), b = octree.grid.toLocal(p[1]), c = octree.grid.toLocal(p[2]);
        detail::voxelizeTriangle(a, b, c, octree.grid, guard, mode, [&](uint64_t key) {
            const auto it = slot.find(key);
            if (it == slot.end()) return;
            using namespace gpu;
            AttributeSums& s = sums[it->second];
            s[kSumTriangle] = std::max(s[kSumTriangle], ~uint32_t(t));
            auto add = [&s](uint32_t at, const Vec3f& v) {
                s[at] += uint32_t(toFixed(v.x)), s[at + 1] += uint32_t(toFixed(v.y));
                s[at + 2] += uint32_t(toFixed(v.z));
            };
            add(kSumNormal, tv.normals[t]);
            if (!tv.colors.empty()) add(kSumColor, tv.colors[t]);
            ++s[kSumCount];
        });
    }
    octree.attributes = finishAttributes(sums, channels);
}

} // namespace svo
