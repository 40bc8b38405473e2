#include "svo/gl/gl_api.h"

#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo::gl {

void checkGl(const char* what)
{
    GLenum first = glGetError();
    if (first == GL_NO_ERROR) return;
    while (glGetError() != GL_NO_ERROR) {
    }
    if (first == GL_OUT_OF_MEMORY) throw OutOfMemory(fmt::format("the GPU ran out of memory during {}", what));
    throw DeviceError(fmt::format("OpenGL error 0x{:04x} during {}", first, what));
}

} // namespace svo::gl
