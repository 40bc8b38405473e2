#pragma once
/// @file winding_columns.h
/// @brief What carries a winding number up a voxel column without a walk of
/// the tree at every centre (the CPU's winding signs, winding_signs.h).
///
/// Off the surface the winding number w of a mesh is smooth, and it jumps by
/// exactly +-1 where a path crosses a triangle. Between two centres of one
/// z column, then, w(upper) = w(lower) + J + C: J the signed crossings of
/// the segment (the parity pass's crossings, column_crossing.h, with the
/// orientation of each triangle), C the smooth change. The gradient of the
/// smooth part is the Biot-Savart integral over the mesh's boundary (the
/// edges whose triangles do not cancel: holes and open shells; a closed
/// mesh has none, and w is piecewise constant). Its z part only sees the
/// edges' horizontal extent:
///   |dw/dz| <= (1/4 pi) sum over boundary edges e of |m_e| |e_xy| max |r_xy| / |r|^3,
/// with m_e the edge's multiplicity and r from the edge to the point; a
/// bounding-volume tree of the edges bounds a far group at once (its net
/// current and a remainder of the next order). A brick's slope bounds this
/// over its centres and the segment that enters it from the brick below;
/// near the boundary, each of its columns has its own.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "svo/core/field_bricks.h"
#include "svo/core/grid.h"
#include "svo/core/mesh.h"
#include "svo/core/vec3.h"
#include "svo/core/voxel_box.h"

namespace svo {

/// What winding numbers need to climb the columns of a list of bricks.
struct WindingColumns {
    /// Per brick (list order) a range of `jumps`: [first[i], first[i + 1]).
    std::vector<uint32_t> first;
    /// Where a column's winding number jumps: at voxel `voxel` (bit order of
    /// Brick) by `jump` from the centre below it (the sum of the crossings
    /// between the two; a crossing below the grid is at the column's voxel 0).
    struct Jump {
        uint16_t voxel;
        int16_t jump;
    };
    std::vector<Jump> jumps;
    /// Per brick, an upper bound on |dw/dz| off the surface over the brick's
    /// centres and one voxel below them, in winding number per voxel;
    /// +infinity where the mesh's boundary meets that box.
    std::vector<float> slope;
    /// Per brick near the boundary, the same bound for each of its 64 voxel
    /// columns (column x * 8 + y): at columnSlope[columnsAt[brick] + column];
    /// kWholeBrick where the brick's slope holds for every column.
    static constexpr uint32_t kWholeBrick = 0xffffffffu;
    std::vector<uint32_t> columnsAt;
    std::vector<float> columnSlope;

    /// @brief The bound for column @a column (x * 8 + y) of brick @a brick.
    float slopeAt(size_t brick, uint32_t column) const
    {
        const uint32_t at = columnsAt[brick];
        return at == kWholeBrick ? slope[brick] : columnSlope[size_t(at) + column];
    }
};

namespace winding_boundary {
class BoundaryTree;
}

/// The same for the centres of the bricks of a box of a grid's bricks
/// (brick b's centre 8 b + 3.5 in local coordinates), climbed a brick at a
/// time. The slopes are bounded when asked: most steps of a climb near the
/// boundary could not decide anything, and their bound need not be finished.
struct BrickCentreColumns {
    std::array<uint32_t, 3> origin{}; ///< the box's first brick
    std::array<uint32_t, 3> dims{};   ///< the box in bricks
    /// Per brick of the box (x-fastest): the winding number's jump from the
    /// centre of the brick below (0 for the box's lowest bricks).
    std::vector<int32_t> jump;
    /// The mesh's boundary edges; null for a closed mesh.
    std::shared_ptr<const winding_boundary::BoundaryTree> boundary;

    /// @brief A bound on |dw/dz| off the surface over the segment from the
    /// centre below @a brick (its index in the box) to its own, per voxel;
    /// +infinity where the boundary meets it or the bound passes @a limit.
    float slopeAt(uint64_t brick, double limit) const;

    /// @brief A bound on |grad w| over the box of @a brick's voxel centres
    /// ([8 b, 8 b + 7] in each axis), per voxel: the same Biot-Savart bound
    /// with the whole field for its z part. It holds off the surface, so
    /// only for a brick whose box holds no triangle (one beyond a band of at
    /// least one voxel); +infinity where the boundary meets the box.
    float gradientAt(uint64_t brick) const;
};

/// @brief The signed crossings and slopes of the brick centres of @a box,
/// by default the grid's whole box (ceil(dims / 8) bricks).
/// @throw svo::Unsupported for a box of more than 2^31 bricks.
BrickCentreColumns brickCentreColumns(const std::vector<Vec3d>& local, const TriangleMesh& mesh,
                                      const GridSpec& grid, const BrickBox* box = nullptr);

/// @brief The signed crossings and slopes of @a bricks, on the CPU with TBB.
/// @param local  the mesh's positions in @a grid's local frame (localPositions)
/// @param bricks unique brick coordinates
/// @return per brick, its jumps and slope
/// @throw std::bad_alloc.
WindingColumns windingColumns(const std::vector<Vec3d>& local, const TriangleMesh& mesh, const GridSpec& grid,
                              const std::vector<BrickCoord>& bricks);

} // namespace svo
