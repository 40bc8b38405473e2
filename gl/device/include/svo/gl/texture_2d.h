#pragma once
/// @file texture_2d.h
/// @brief svo::gl::Texture2D: an immutable-storage 2D texture of one level.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// @brief An immutable-storage 2D texture of one level, read by texelFetch and
/// written as an image (the viewer's pixels).
class Texture2D {
public:
    /// @brief An empty texture with no GL name.
    Texture2D() = default;
    /// @brief Allocates a @a width by @a height texture of @a internalFormat.
    /// @param what names the texture in error messages
    /// @throw svo::OutOfMemory when the GPU cannot allocate it
    /// @throw svo::DeviceError on another GL error, earlier work's included
    Texture2D(const char* what, GLenum internalFormat, int width, int height);
    /// @brief Width in texels.
    int width() const { return width_; }
    /// @brief Height in texels.
    int height() const { return height_; }
    /// @brief Binds it to texture unit @a unit.
    void bindTexture(GLuint unit) const { glBindTextureUnit(unit, h_.get()); }
    GLuint get() const { return h_.get(); } ///< the GL name, e.g. to attach it to a framebuffer
    /// @brief Binds the texture as image @a unit (imageLoad / imageStore).
    /// @param access GL_READ_ONLY, GL_WRITE_ONLY or GL_READ_WRITE
    /// @param format the image's layout qualifier format
    void bindImage(GLuint unit, GLenum access, GLenum format) const
    {
        glBindImageTexture(unit, h_.get(), 0, GL_FALSE, 0, access, format);
    }

private:
    Handle<detail::deleteTexture> h_;
    int width_ = 0, height_ = 0;
};

} // namespace svo::gl
