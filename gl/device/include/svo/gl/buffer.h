#pragma once
/// @file buffer.h
/// An immutable-storage GL buffer: allocation, binding, reads, clears and uploads.
#include <cstdint>

#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// Immutable-storage buffer (glNamedBufferStorage). Allocation failure throws.
class Buffer {
public:
    Buffer() = default;
    /// `what` names the buffer in out-of-memory errors.
    Buffer(const char* what, uint64_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    uint64_t bytes() const { return bytes_; }
    void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, h_.get()); }
    void bind(GLenum target) const { glBindBuffer(target, h_.get()); }
    /// Small reads (counters): glGetNamedBufferSubData.
    void read(uint64_t offset, uint64_t bytes, void* out) const
    {
        glGetNamedBufferSubData(h_.get(), GLintptr(offset), GLsizeiptr(bytes), out);
    }
    /// Bulk reads: a GPU copy into a host-visible staging buffer, then a
    /// mapped memcpy, in chunks of at most 64 MiB. Some drivers serve
    /// glGetNamedBufferSubData on device memory through a slow path.
    void readBulk(uint64_t offset, uint64_t bytes, void* out) const;
    void clearUint(uint32_t value) const
    {
        glClearNamedBufferData(h_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    }
    /// Clears only the first `bytes` (a multiple of 4): scratch buffers are
    /// often larger than one call needs.
    void clearUint(uint32_t value, uint64_t bytes) const
    {
        glClearNamedBufferSubData(h_.get(), GL_R32UI, 0, GLsizeiptr(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    }
    /// Uploads into a buffer made with GL_DYNAMIC_STORAGE_BIT (the default).
    void write(uint64_t offset, uint64_t bytes, const void* data) const
    {
        if (bytes) glNamedBufferSubData(h_.get(), GLintptr(offset), GLsizeiptr(bytes), data);
    }

private:
    friend class VertexArray;
    Handle<detail::deleteBuffer> h_;
    uint64_t bytes_ = 0;
};

} // namespace svo::gl
