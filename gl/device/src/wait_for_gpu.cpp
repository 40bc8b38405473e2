#include "svo/gl/wait_for_gpu.h"

#include "svo/gl/gl_api.h"
#include "svo/core/error.h"

namespace svo::gl {

void waitForGpu(const std::function<void()>& poll)
{
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!fence) throw DeviceError("cannot create a GL fence to wait for the GPU");
    GLbitfield flags = GL_SYNC_FLUSH_COMMANDS_BIT; // the first wait submits the commands
    for (;;) {
        const GLenum r = glClientWaitSync(fence, flags, 20'000'000); // 20 ms
        flags = 0;
        if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) break;
        if (r == GL_WAIT_FAILED) {
            glDeleteSync(fence);
            throw DeviceError("waiting for the GPU failed (glClientWaitSync)");
        }
        try {
            poll();
        } catch (...) {
            glDeleteSync(fence);
            throw;
        }
    }
    glDeleteSync(fence);
}

} // namespace svo::gl
