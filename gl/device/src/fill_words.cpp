#include "svo/gl/fill_words.h"

#include <algorithm>
#include <numeric>
#include <fmt/format.h>

#include "svo/core/error.h"
#include "svo/gl/buffer.h"
#include "svo/gl/context.h"
#include "svo/gl/program.h"

namespace svo::gl {

// This layer's shaders, embedded by svo_embed_files (gl/device/CMakeLists.txt).
const ShaderFiles& deviceShaders();

void fillWords(const Context& context, const Buffer& buffer, uint32_t value, uint64_t bytes)
{
    if (bytes % 4 || bytes > buffer.bytes())
        throw InvalidInput(fmt::format("fillWords: {} bytes in a buffer of {}", bytes, buffer.bytes()));
    if (!bytes) return;
    const Context::Scope scope(context);
    GLint was = 0;
    GLint64 wasAt = 0, wasSize = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &was);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 0, &wasAt);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 0, &wasSize);
    const Program& fill = context.program(deviceShaders(), {"fill_words.comp"});
    fill.set("uValue", value);
    // Ranges the shader can address (it counts words in 32 bits) and the
    // driver binds (its storage block limit), starting at multiples of the
    // offset alignment.
    GLint align = 256;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    uint64_t range = uint64_t(1) << 30;
    if (const uint64_t limit = context.shaderBufferLimit(); limit && limit < range) range = limit;
    range -= range % std::lcm<uint64_t>(uint64_t(std::max(align, 4)), 4);
    for (uint64_t at = 0; at < bytes; at += range) {
        const uint64_t n = std::min(range, bytes - at);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, buffer.id(), GLintptr(at), GLsizeiptr(n));
        fill.set("uWords", uint32_t(n / 4));
        fill.dispatchRows((n / 4 + 255) / 256);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
    if (wasSize > 0)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, GLuint(was), GLintptr(wasAt), GLsizeiptr(wasSize));
    else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, GLuint(was));
}

} // namespace svo::gl
