#pragma once
// OpenGL 4.5 core declarations. Entry points come straight from GLVND's
// libOpenGL, which dispatches to the context made current through EGL.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#ifndef GL_CONSERVATIVE_RASTERIZATION_NV
#define GL_CONSERVATIVE_RASTERIZATION_NV 0x9346
#endif

namespace svo::gl {

/// Throws svo::Error naming `what` if the GL error flag is set
/// (GL_OUT_OF_MEMORY is reported as the GPU running out of memory).
void checkGl(const char* what);

} // namespace svo::gl
