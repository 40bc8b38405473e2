#pragma once
/// @file texture_3d.h
/// @brief svo::gl::Texture3D: an immutable-storage 3D texture with a mip chain.
#include <algorithm>
#include <cstdint>

#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// @brief An immutable-storage 3D texture with a mip chain (glTextureStorage3D),
/// trilinearly filtered between levels, clamped to a transparent black border
/// (outside the volume is empty).
class Texture3D {
public:
    /// @brief An empty texture with no GL name.
    Texture3D() = default;
    /// @brief Allocates a @a width by @a height by @a depth texture of
    /// @a internalFormat with @a levels mip levels.
    /// @param what names the texture in error messages
    /// @throw svo::OutOfMemory when the GPU cannot allocate it
    /// @throw svo::DeviceError on another GL error, earlier work's included
    Texture3D(const char* what, GLenum internalFormat, int levels, int width, int height, int depth);
    /// @brief The number of mip levels.
    int levels() const { return levels_; }
    /// @brief Level @a level's size along @a axis (GL's rule: halved and
    /// floored, at least 1).
    int size(int level, int axis) const { return std::max(1, size_[axis] >> level); }
    /// @brief Binds it to texture unit @a unit.
    void bindTexture(GLuint unit) const { glBindTextureUnit(unit, h_.get()); }
    /// @brief Switches to nearest filtering, as integer textures need to be complete.
    void nearest() const
    {
        glTextureParameteri(h_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(h_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    /// @brief Binds level @a level as image @a unit (imageLoad / imageStore), all layers.
    /// @param access GL_READ_ONLY, GL_WRITE_ONLY or GL_READ_WRITE
    /// @param format the image's layout qualifier format
    void bindImage(GLuint unit, int level, GLenum access, GLenum format) const
    {
        glBindImageTexture(unit, h_.get(), level, GL_TRUE, 0, access, format);
    }
    /// @brief Reads level @a level back as @a format / @a type (glGetTextureImage),
    /// waiting for the GPU.
    /// @param bytes the size of @a out; the driver writes no more
    void read(int level, GLenum format, GLenum type, uint64_t bytes, void* out) const
    {
        glGetTextureImage(h_.get(), level, format, type, GLsizei(bytes), out);
    }

private:
    Handle<detail::deleteTexture> h_;
    int levels_ = 0;
    int size_[3] = {0, 0, 0};
};

} // namespace svo::gl
