#include "svo/gl/vertex_array.h"

#include "svo/gl/buffer.h"

namespace svo::gl {

VertexArray::VertexArray()
{
    GLuint n = 0;
    glCreateVertexArrays(1, &n);
    h_ = Handle<detail::deleteVertexArray>(n);
}

void VertexArray::setPositions(const Buffer& vertices, GLuint location)
{
    glVertexArrayVertexBuffer(h_.get(), 0, vertices.h_.get(), 0, 3 * sizeof(float));
    glEnableVertexArrayAttrib(h_.get(), location);
    glVertexArrayAttribFormat(h_.get(), location, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(h_.get(), location, 0);
}

void VertexArray::setIndices(const Buffer& indices) { glVertexArrayElementBuffer(h_.get(), indices.h_.get()); }

} // namespace svo::gl
