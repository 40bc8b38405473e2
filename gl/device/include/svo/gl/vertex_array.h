#pragma once
/// @file vertex_array.h
/// A vertex array of float3 positions and indices.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

class Buffer;

/// A vertex array with one float3 attribute and an element buffer.
class VertexArray {
public:
    VertexArray();
    void setPositions(const Buffer& vertices, GLuint location);
    void setIndices(const Buffer& indices);
    void bind() const { glBindVertexArray(h_.get()); }

private:
    Handle<detail::deleteVertexArray> h_;
};

} // namespace svo::gl
