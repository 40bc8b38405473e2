#include "svo/gl/empty_framebuffer.h"

#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo::gl {

EmptyFramebuffer::EmptyFramebuffer(int width, int height)
{
    GLuint n = 0;
    glCreateFramebuffers(1, &n);
    h_ = Handle<detail::deleteFramebuffer>(n);
    glNamedFramebufferParameteri(n, GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    glNamedFramebufferParameteri(n, GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    glNamedFramebufferParameteri(n, GL_FRAMEBUFFER_DEFAULT_SAMPLES, 0);
    if (glCheckNamedFramebufferStatus(n, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw DeviceError(fmt::format("cannot create an empty {}x{} framebuffer", width, height));
}

} // namespace svo::gl
