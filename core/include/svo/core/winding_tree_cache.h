#pragma once
/// @file winding_tree_cache.h
/// @brief The last winding tree built, kept for the next call over the same
/// triangles. A level set or solid computed in regions (a GPU memory
/// budget's, or a cluster's tiles, each a call of its own on the worker's
/// Voxelizer) would otherwise build the whole mesh's tree once per region.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "svo/core/vec3.h"
#include "svo/core/winding_tree.h"

namespace svo {

class WindingTreeCache {
public:
    /// @brief buildWindingTree(@a positions, @a triangles) (default piece
    /// edge), or the tree kept from the last call when both are the same,
    /// bit for bit: the key is the whole input compared, not a hash, so a
    /// changed mesh never gets an old tree.
    /// @param positions the triangles' corners (the frame the tree is built in)
    /// @param triangles three indices into @a positions each
    /// @param built     set to whether the tree was built now
    /// @return the tree, valid until the next call or clear()
    /// @throw as buildWindingTree
    const WindingTree& treeFor(const std::vector<Vec3d>& positions,
                               const std::vector<std::array<uint32_t, 3>>& triangles, bool* built = nullptr);
    /// @brief Frees the tree and the copy of its input.
    void clear();

private:
    std::vector<Vec3d> positions_;
    std::vector<std::array<uint32_t, 3>> triangles_;
    std::unique_ptr<WindingTree> tree_;
};

} // namespace svo
