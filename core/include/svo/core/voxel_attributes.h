#pragma once
/// @file voxel_attributes.h
/// @brief Per-voxel channels (normal, triangle id, colour) and how they are summed.
///
/// Every (voxel, triangle) pair the voxelizer finds contributes the triangle's
/// values. Sums are kept in 16.16 fixed point in 32-bit integers, so they do
/// not depend on the order of the additions: the GPU pass (atomics) and the
/// CPU reference give identical sums from identical pairs.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/gpu_layout.h"
#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_mode.h"

namespace svo {

/// Sums hold at most gpu::kFixedMaxContributions (32,767) contributions per
/// voxel (a unit normal in 16.16 fixed point times that count fits 32 bits);
/// finishAttributes refuses more.

/// @brief One voxel's sums: [0] ~(smallest triangle id) (0: none), [1..3] normal,
/// [4..6] colour, [7] pair count. The slots (gpu::kSum*) and the fixed-point
/// format come from gpu_layout.h, which octree_attributes.comp sums with too.
using AttributeSums = std::array<uint32_t, gpu::kSumWords>;

/// @brief What each triangle contributes: its unit normal (from double
/// precision, 0 when degenerate) and its mean vertex colour, as floats.
struct TriangleValues {
    std::vector<Vec3f> normals, colors; ///< one per triangle; colors empty when not asked for
};
/// @brief Each triangle's contribution.
/// @param colors whether to compute colours (none where the mesh has no vertex colours)
TriangleValues triangleValues(const TriangleMesh& mesh, bool colors);

/// @brief @a v in 16.16 fixed point, rounding half to even (GLSL roundEven).
int32_t toFixed(float v);

/// @brief The asked-for channels the mesh can give: colour only with vertex colours.
/// @return the AttributeChannel bits of @a channels the mesh can give
uint32_t availableChannels(const TriangleMesh& mesh, uint32_t channels);

/// @brief Turns sums into the asked-for channels.
/// @param sums     one per voxel, in voxel order
/// @param channels AttributeChannel bits
/// @throw svo::Unsupported when a voxel has more contributions than the sums hold
VoxelAttributes finishAttributes(const std::vector<AttributeSums>& sums, uint32_t channels);

/// @brief The CPU reference of the attribute pass: pairs from the shared overlap test on cubes grown by
/// `guard` (thin mode: on the voxels' centre segments, as voxelizeCpu tests
/// them), summed for the octree's voxels (others are ignored), stored on
/// the octree. Colours are skipped when the mesh has none. Triangles run in
/// parallel; the sums (integer adds, a max) do not depend on their order.
/// @param channels AttributeChannel bits
/// @param guard    voxels the cubes are grown by
/// @throw svo::Unsupported as finishAttributes
void attachAttributesCpu(const TriangleMesh& mesh, Octree& octree, uint32_t channels, double guard,
                         VoxelMode mode = VoxelMode::Conservative);

} // namespace svo
