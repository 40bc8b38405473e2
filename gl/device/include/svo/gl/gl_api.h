#pragma once
// OpenGL 4.5 core declarations, through libepoxy: each entry point is a
// pointer epoxy resolves on its first call (libOpenGL and eglGetProcAddress,
// loaded then), so nothing that includes this links a GL library. GL may be
// called only in a context that a gl::Context made current, which fails
// first, with a DeviceError, where no GL can be loaded.
#include <epoxy/gl.h>

#ifndef GL_CONSERVATIVE_RASTERIZATION_NV
#define GL_CONSERVATIVE_RASTERIZATION_NV 0x9346
#endif

namespace svo::gl {

/// Throws svo::Error naming `what` if the GL error flag is set
/// (GL_OUT_OF_MEMORY is reported as the GPU running out of memory).
void checkGl(const char* what);

} // namespace svo::gl
