#pragma once
/// @file vertex_array.h
/// @brief svo::gl::VertexArray: a vertex array of float3 positions and indices.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

class Buffer;

/// @brief A vertex array with one float3 attribute and an element buffer.
class VertexArray {
public:
    /// @brief Creates the vertex array (needs a current Context).
    VertexArray();
    /// @brief Reads attribute @a location as tightly packed float3 positions
    /// from @a vertices.
    void setPositions(const Buffer& vertices, GLuint location);
    /// @brief Uses @a indices as the element buffer.
    void setIndices(const Buffer& indices);
    /// @brief Binds it for drawing.
    void bind() const { glBindVertexArray(h_.get()); }

private:
    Handle<detail::deleteVertexArray> h_;
};

} // namespace svo::gl
