#include "svo/gl/texture_3d.h"

#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo::gl {

Texture3D::Texture3D(const char* what, GLenum internalFormat, int levels, int width, int height, int depth)
    : levels_(levels), size_{width, height, depth}
{
    checkGl(fmt::format("the GL work before allocating the {}", what).c_str());
    GLuint n = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &n);
    h_ = Handle<detail::deleteTexture>(n);
    glTextureStorage3D(n, levels, internalFormat, width, height, depth);
    const GLenum err = glGetError();
    if (err == GL_OUT_OF_MEMORY)
        throw OutOfMemory(fmt::format("the GPU cannot allocate the {} ({} x {} x {} texels)", what, width, height, depth));
    if (err != GL_NO_ERROR)
        throw DeviceError(fmt::format("OpenGL error 0x{:04x} allocating the {} ({} x {} x {} texels, {} levels)", err, what,
                                width, height, depth, levels));
    glTextureParameteri(n, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(n, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    const float border[4] = {0, 0, 0, 0};
    glTextureParameterfv(n, GL_TEXTURE_BORDER_COLOR, border);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(n, wrap, GL_CLAMP_TO_BORDER);
    checkGl(fmt::format("setting up the {}", what).c_str());
}

} // namespace svo::gl
