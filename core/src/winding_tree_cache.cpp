// The last winding tree, kept (svo/core/winding_tree_cache.h).
#include "svo/core/winding_tree_cache.h"

#include <cstring>

namespace svo {
namespace {

/// Bit for bit, so that -0 and +0 (equal as numbers) are different keys.
template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

} // namespace

const WindingTree& WindingTreeCache::treeFor(const std::vector<Vec3d>& positions,
                                             const std::vector<std::array<uint32_t, 3>>& triangles, bool* built)
{
    const bool same = tree_ && sameBits(positions, positions_) && sameBits(triangles, triangles_);
    if (built) *built = !same;
    if (same) return *tree_;
    clear(); // a failed build leaves nothing kept
    auto tree = std::make_unique<WindingTree>(buildWindingTree(positions, triangles));
    positions_ = positions;
    triangles_ = triangles;
    tree_ = std::move(tree);
    return *tree_;
}

void WindingTreeCache::clear()
{
    tree_.reset();
    positions_ = {};
    triangles_ = {};
}

} // namespace svo
