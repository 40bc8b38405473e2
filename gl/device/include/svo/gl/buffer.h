#pragma once
/// @file buffer.h
/// @brief svo::gl::Buffer: an immutable-storage GL buffer: allocation,
/// binding, reads, clears and uploads.
#include <cstdint>

#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// @brief An immutable-storage buffer (glNamedBufferStorage). Calls need a
/// current Context; only the constructor and the reads check for errors.
class Buffer {
public:
    /// @brief An empty buffer with no GL name.
    Buffer() = default;
    /// @brief Allocates @a bytes (4 when 0), filled from @a data when not null.
    /// @param what  names the buffer in error messages
    /// @param flags glNamedBufferStorage flags; GL_DYNAMIC_STORAGE_BIT lets write() upload
    /// @throw svo::OutOfMemory when the GPU cannot allocate it, or a GL error
    ///        left by earlier work is GL_OUT_OF_MEMORY
    /// @throw svo::DeviceError on another GL error, earlier work's included
    Buffer(const char* what, uint64_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    /// @brief The size asked for at construction.
    uint64_t bytes() const { return bytes_; }
    /// @brief Binds the buffer to indexed binding @a index of @a target
    /// (GL_SHADER_STORAGE_BUFFER, GL_ATOMIC_COUNTER_BUFFER, ...).
    void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, h_.get()); }
    /// @brief The GL name, for a caller's own GL calls (or CUDA-GL interop) in this buffer's context.
    GLuint id() const { return h_.get(); }
    /// @brief Binds the buffer to @a target (GL_DISPATCH_INDIRECT_BUFFER, ...).
    void bind(GLenum target) const { glBindBuffer(target, h_.get()); }
    /// @brief Copies @a bytes from byte @a offset into @a out, waiting for the
    /// GPU: for small reads (counters), through glGetNamedBufferSubData; from
    /// a large buffer through readBulk() instead, since some drivers read a
    /// few bytes of a large buffer as slowly as the whole of it
    /// (docs/design.md, "Fresh memory and readbacks").
    /// @throw svo::OutOfMemory or svo::DeviceError as readBulk(), from a
    ///        large buffer only
    void read(uint64_t offset, uint64_t bytes, void* out) const;
    /// @brief Copies @a bytes from byte @a offset into @a out, for bulk reads:
    /// a GPU copy into a host-visible staging buffer, then a mapped memcpy, in
    /// chunks of at most 64 MiB. Some drivers serve glGetNamedBufferSubData
    /// on device memory through a slow path.
    /// @throw svo::OutOfMemory or svo::DeviceError when the staging buffer
    ///        cannot be allocated (see the constructor) or mapped
    void readBulk(uint64_t offset, uint64_t bytes, void* out) const;
    /// @brief Sets every 32-bit word of the buffer to @a value.
    void clearUint(uint32_t value) const
    {
        glClearNamedBufferData(h_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    }
    /// @brief Sets the first @a bytes (a multiple of 4) to @a value as 32-bit
    /// words: scratch buffers are often larger than one call needs.
    void clearUint(uint32_t value, uint64_t bytes) const
    {
        glClearNamedBufferSubData(h_.get(), GL_R32UI, 0, GLsizeiptr(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    }
    /// @brief Uploads @a bytes from @a data to byte @a offset; the buffer must
    /// have been made with GL_DYNAMIC_STORAGE_BIT (the default). Nothing for 0 bytes.
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
