#include "svo/core/voxel_attributes.h"

#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <unordered_map>

#include "svo/core/error.h"
#include "svo/core/local_positions.h"
#include "svo/core/voxel_key.h"
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
    a.computed = channels;
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

namespace {

/// Where each voxel's sums live: its brick's first slot plus the voxel's rank
/// among the brick's bits. One hash entry per brick, not per voxel.
class VoxelSlots {
public:
    explicit VoxelSlots(const Octree& octree) : octree_(octree), offsets_(brickVoxelOffsets(octree))
    {
        const auto refs = occupiedBricks(octree);
        brickOf_.reserve(refs.size());
        for (const auto& r : refs) brickOf_.emplace(packVoxelKey(r.origin[0], r.origin[1], r.origin[2]), r.index);
    }

    /// The slot of @a key, or kNone when the octree lacks the voxel.
    uint64_t find(uint64_t key) const
    {
        const auto it = brickOf_.find(brickOfKey(key));
        if (it == brickOf_.end()) return kNone;
        const uint64_t* words = octree_.bricks[it->second].words;
        const uint32_t bit = uint32_t(key & 511u), word = bit >> 6;
        const uint64_t below = (uint64_t(1) << (bit & 63)) - 1;
        if (!(words[word] >> (bit & 63) & 1)) return kNone;
        uint64_t rank = uint64_t(__builtin_popcountll(words[word] & below));
        for (uint32_t w = 0; w < word; ++w) rank += uint64_t(__builtin_popcountll(words[w]));
        return offsets_[it->second] + rank;
    }

    static constexpr uint64_t kNone = ~uint64_t(0);

private:
    const Octree& octree_;
    std::vector<uint64_t> offsets_;
    std::unordered_map<uint64_t, uint32_t> brickOf_;
};

// Sums from many threads: integer adds and a max commute, so the result does
// not depend on the order (C++20's atomic_ref is this; the GCC/Clang builtins
// stand in for it under C++17).
void atomicAdd(uint32_t& word, uint32_t v) { __atomic_fetch_add(&word, v, __ATOMIC_RELAXED); }
void atomicMax(uint32_t& word, uint32_t v)
{
    uint32_t seen = __atomic_load_n(&word, __ATOMIC_RELAXED);
    while (seen < v && !__atomic_compare_exchange_n(&word, &seen, v, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
}

void addTriangle(AttributeSums& s, uint32_t t, const TriangleValues& tv)
{
    using namespace gpu;
    atomicMax(s[kSumTriangle], ~t);
    auto add = [&s](uint32_t at, const Vec3f& v) {
        atomicAdd(s[at], uint32_t(toFixed(v.x)));
        atomicAdd(s[at + 1], uint32_t(toFixed(v.y)));
        atomicAdd(s[at + 2], uint32_t(toFixed(v.z)));
    };
    add(kSumNormal, tv.normals[t]);
    if (!tv.colors.empty()) add(kSumColor, tv.colors[t]);
    atomicAdd(s[kSumCount], 1u);
}

} // namespace

void attachAttributesCpu(const TriangleMesh& mesh, Octree& octree, uint32_t channels, double guard, VoxelMode mode)
{
    channels = availableChannels(mesh, channels);
    octree.attributes = {};
    if (!channels) return;
    const VoxelSlots slots(octree);
    const TriangleValues tv = triangleValues(mesh, channels & kColors);
    const std::vector<Vec3d> local = localPositions(mesh, octree.grid);
    std::vector<AttributeSums> sums(octree.voxelCount(), AttributeSums{});
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 64), [&](const auto& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
            const auto& f = mesh.triangles[t];
            detail::voxelizeTriangle(local[f[0]], local[f[1]], local[f[2]], octree.grid, guard, mode,
                                     [&](uint64_t key) {
                                         const uint64_t at = slots.find(key);
                                         if (at != VoxelSlots::kNone) addTriangle(sums[at], uint32_t(t), tv);
                                     });
        }
    });
    octree.attributes = finishAttributes(sums, channels);
}

} // namespace svo
