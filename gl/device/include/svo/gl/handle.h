#pragma once
/// @file handle.h
/// @brief Movable ownership of one GL name (Handle), and the deleters it is
/// instantiated with. The small owners of GL objects built on it (buffer.h,
/// texture_2d.h, texture_3d.h, vertex_array.h, empty_framebuffer.h,
/// timer_query.h, program.h) each hold one name, delete it on destruction,
/// move but never copy, and expose operations rather than the name itself.
/// All use 4.5 direct state access.
#include <utility>

#include "svo/gl/gl_api.h"

namespace svo::gl {

/// @brief Movable ownership of one GL name; @c Deleter frees it.
template <void (*Deleter)(GLuint)>
class Handle {
public:
    /// @brief Owns no name.
    Handle() = default;
    /// @brief Takes ownership of @a name (0: none).
    explicit Handle(GLuint name) : name_(name) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
    Handle& operator=(Handle&& o) noexcept
    {
        if (this != &o) { reset(); name_ = std::exchange(o.name_, 0); }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    /// @brief The GL name; 0 when none is owned.
    GLuint get() const { return name_; }
    /// @brief Frees the name now (if any) and owns none.
    void reset()
    {
        if (name_) Deleter(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

/// The deleters Handle is instantiated with, one per kind of GL object.
namespace detail {
inline void deleteBuffer(GLuint n) { glDeleteBuffers(1, &n); }
inline void deleteVertexArray(GLuint n) { glDeleteVertexArrays(1, &n); }
inline void deleteFramebuffer(GLuint n) { glDeleteFramebuffers(1, &n); }
inline void deleteQuery(GLuint n) { glDeleteQueries(1, &n); }
inline void deleteProgram(GLuint n) { glDeleteProgram(n); }
inline void deleteShader(GLuint n) { glDeleteShader(n); }
inline void deleteTexture(GLuint n) { glDeleteTextures(1, &n); }
} // namespace detail

} // namespace svo::gl
