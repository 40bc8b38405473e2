#pragma once
/// @file winding_request.h
/// @brief svo::gl::WindingRequest: what computeWinding (winding_number.h) evaluates.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "svo/core/interrupt.h"
#include "svo/core/voxel_box.h"
#include "svo/gl/winding_work.h"

namespace svo::gl {

/// @brief What computeWinding evaluates: the bricks to classify voxel by
/// voxel, whether every brick centre too, and the accuracy.
struct WindingRequest {
    /// Bricks (local voxel coordinate / 8) whose voxels to classify.
    std::vector<std::array<uint32_t, 3>> bricks;
    bool perBrick = false; ///< also the winding number at every brick centre of a box of bricks
    std::optional<BrickBox> brickBox; ///< that box (clamped to the grid's); default the grid's whole box
    double beta = 1.5;     ///< far-field threshold; +infinity: every triangle exactly
    WindingWork work = WindingWork::Auto; ///< how the per-voxel evaluation walks the tree
    Checkpoint checkpoint;                ///< polled while the passes run; throws svo::Interrupted to stop
};

} // namespace svo::gl
