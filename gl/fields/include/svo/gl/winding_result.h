#pragma once
/// @file winding_result.h
/// @brief svo::gl::WindingResult: what computeWinding (winding_number.h)
/// gives back: inside voxels per brick and winding numbers at brick centres.
#include <array>
#include <cstdint>
#include <vector>

#include "svo/core/octree.h"

namespace svo::gl {

/// @brief What computeWinding gives back.
struct WindingResult {
    std::vector<Brick> inside;   ///< per requested brick: voxels whose winding number is >= 1/2
    std::vector<float> perBrick; ///< x-fastest over the box of bricks, when asked
    std::array<uint32_t, 3> brickDims{};   ///< that box, in bricks
    std::array<uint32_t, 3> brickOrigin{}; ///< ... and its first brick
};

} // namespace svo::gl
