#pragma once
/// @file texture_3d.h
/// An immutable-storage 3D texture with a mip chain.
#include <algorithm>
#include <cstdint>

#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"

namespace svo::gl {

/// Immutable-storage 3D texture with a full mip chain of `levels` levels
/// (glTextureStorage3D), trilinearly filtered between levels, clamped to
/// a transparent black border (outside the volume is empty). Allocation failure throws.
class Texture3D {
public:
    Texture3D() = default;
    /// `what` names the texture in out-of-memory errors.
    Texture3D(const char* what, GLenum internalFormat, int levels, int width, int height, int depth);
    int levels() const { return levels_; }
    /// Level `level`'s size along `axis` (GL's rule: halved and floored, at least 1).
    int size(int level, int axis) const { return std::max(1, size_[axis] >> level); }
    void bindTexture(GLuint unit) const { glBindTextureUnit(unit, h_.get()); }
    /// Nearest filtering, as integer textures need to be complete.
    void nearest() const
    {
        glTextureParameteri(h_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(h_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    /// Binds one level as an image (imageLoad / imageStore); `format` is the image's layout qualifier format.
    void bindImage(GLuint unit, int level, GLenum access, GLenum format) const
    {
        glBindImageTexture(unit, h_.get(), level, GL_TRUE, 0, access, format);
    }
    /// Reads one level back as `format`/`type` (glGetTextureImage) into `bytes` bytes at `out`.
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
