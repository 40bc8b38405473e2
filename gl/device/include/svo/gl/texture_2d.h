#pragma once
/// @file texture_2d.h
/// An immutable-storage 2D texture of one level.
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// Immutable-storage 2D texture of one level, read by texelFetch and written
/// as an image (the viewer's pixels). Allocation failure throws.
class Texture2D {
public:
    Texture2D() = default;
    /// `what` names the texture in out-of-memory errors.
    Texture2D(const char* what, GLenum internalFormat, int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }
    void bindTexture(GLuint unit) const { glBindTextureUnit(unit, h_.get()); }
    GLuint get() const { return h_.get(); } ///< the GL name, e.g. to attach it to a framebuffer
    /// Binds the texture as an image (imageLoad / imageStore); `format` is the image's layout qualifier format.
    void bindImage(GLuint unit, GLenum access, GLenum format) const
    {
        glBindImageTexture(unit, h_.get(), 0, GL_FALSE, 0, access, format);
    }

private:
    Handle<detail::deleteTexture> h_;
    int width_ = 0, height_ = 0;
};

} // namespace svo::gl
