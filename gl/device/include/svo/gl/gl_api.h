#pragma once
/// @file gl_api.h
/// @brief OpenGL 4.5 core declarations, through libepoxy, and checkGl().
///
/// Each entry point is a pointer epoxy resolves on its first call (libOpenGL
/// and eglGetProcAddress, loaded then), so nothing that includes this links a
/// GL library. GL may be called only in a context that a gl::Context made
/// current, which fails first, with a DeviceError, where no GL can be loaded.
#include <epoxy/gl.h>

#ifndef GL_CONSERVATIVE_RASTERIZATION_NV
#define GL_CONSERVATIVE_RASTERIZATION_NV 0x9346
#endif

namespace svo::gl {

/// @brief Throws if the GL error flag is set; does nothing otherwise.
/// @param what the work just done, for the message ("during <what>")
/// @throw svo::OutOfMemory for GL_OUT_OF_MEMORY
/// @throw svo::DeviceError for any other GL error
void checkGl(const char* what);

} // namespace svo::gl
