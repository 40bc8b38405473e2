#pragma once
/// @file image.h
/// @brief The pictures the octree view reads back (Image).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace svo::gl {

/// @brief An RGBA8 picture, rows from the top.
struct Image {
    int width = 0, height = 0; ///< pixels
    std::vector<uint8_t> rgba; ///< 4 bytes per pixel
    /// @brief The 4 bytes of pixel (@a x, @a y), row @a y from the top; unchecked.
    const uint8_t* pixel(int x, int y) const { return &rgba[4 * (size_t(y) * size_t(width) + size_t(x))]; }
};

} // namespace svo::gl
