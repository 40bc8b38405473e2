#include "svo/gl/texture_2d.h"

#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo::gl {

Texture2D::Texture2D(const char* what, GLenum internalFormat, int width, int height) : width_(width), height_(height)
{
    checkGl(fmt::format("the GL work before allocating the {}", what).c_str());
    GLuint n = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &n);
    h_ = Handle<detail::deleteTexture>(n);
    glTextureStorage2D(n, 1, internalFormat, width, height);
    const GLenum err = glGetError();
    if (err == GL_OUT_OF_MEMORY)
        throw OutOfMemory(fmt::format("the GPU cannot allocate the {} ({} x {} texels)", what, width, height));
    if (err != GL_NO_ERROR)
        throw DeviceError(fmt::format("OpenGL error 0x{:04x} allocating the {} ({} x {} texels)", err, what, width, height));
    glTextureParameteri(n, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(n, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGl(fmt::format("setting up the {}", what).c_str());
}

} // namespace svo::gl
