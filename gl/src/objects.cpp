#include "objects.h"

#include <algorithm>
#include <cstring>
#include <fmt/format.h>
#include <vector>

#include "shaders.h"
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

Buffer::Buffer(const char* what, uint64_t bytes, const void* data, GLbitfield flags) : bytes_(bytes)
{
    // An error left by earlier work is reported as that work's, not dropped.
    checkGl(fmt::format("the GL work before allocating the {}", what).c_str());
    GLuint n = 0;
    glCreateBuffers(1, &n);
    h_ = Handle<detail::deleteBuffer>(n);
    glNamedBufferStorage(n, GLsizeiptr(bytes ? bytes : 4), data, flags);
    const GLenum err = glGetError();
    if (err == GL_OUT_OF_MEMORY)
        throw OutOfMemory(fmt::format("the GPU cannot allocate {:.1f} MiB for the {}", double(bytes) / (1 << 20), what));
    if (err != GL_NO_ERROR) throw DeviceError(fmt::format("OpenGL error 0x{:04x} allocating the {}", err, what));
}

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

void Buffer::readBulk(uint64_t offset, uint64_t bytes, void* out) const
{
    if (!bytes) return;
    const uint64_t chunk = std::min<uint64_t>(bytes, uint64_t(64) << 20);
    const Buffer staging("readback staging buffer", chunk, nullptr, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
    auto* dst = static_cast<unsigned char*>(out);
    for (uint64_t done = 0; done < bytes; done += chunk) {
        const uint64_t n = std::min(chunk, bytes - done);
        glCopyNamedBufferSubData(h_.get(), staging.h_.get(), GLintptr(offset + done), 0, GLsizeiptr(n));
        const void* src = glMapNamedBufferRange(staging.h_.get(), 0, GLsizeiptr(n), GL_MAP_READ_BIT);
        if (!src) throw DeviceError(fmt::format("cannot map the readback staging buffer ({} bytes)", n));
        std::memcpy(dst + done, src, n);
        glUnmapNamedBuffer(staging.h_.get());
    }
}

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

VertexArray::VertexArray()
{
    GLuint n = 0;
    glCreateVertexArrays(1, &n);
    h_ = Handle<detail::deleteVertexArray>(n);
}

void VertexArray::setPositions(const Buffer& vertices, GLuint location)
{
    glVertexArrayVertexBuffer(h_.get(), 0, vertices.h_.get(), 0, 3 * sizeof(float));
    glEnableVertexArrayAttrib(h_.get(), location);
    glVertexArrayAttribFormat(h_.get(), location, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(h_.get(), location, 0);
}

void VertexArray::setIndices(const Buffer& indices) { glVertexArrayElementBuffer(h_.get(), indices.h_.get()); }

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

TimerQuery::TimerQuery()
{
    GLuint n[2] = {0, 0};
    glCreateQueries(GL_TIMESTAMP, 2, n);
    begin_ = Handle<detail::deleteQuery>(n[0]);
    end_ = Handle<detail::deleteQuery>(n[1]);
}

double TimerQuery::milliseconds() const
{
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(begin_.get(), GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(end_.get(), GL_QUERY_RESULT, &t1);
    return t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0;
}

namespace {
GLenum stageOf(const std::string& file)
{
    if (file.size() > 5 && file.compare(file.size() - 5, 5, ".vert") == 0) return GL_VERTEX_SHADER;
    if (file.size() > 5 && file.compare(file.size() - 5, 5, ".geom") == 0) return GL_GEOMETRY_SHADER;
    if (file.size() > 5 && file.compare(file.size() - 5, 5, ".frag") == 0) return GL_FRAGMENT_SHADER;
    if (file.size() > 5 && file.compare(file.size() - 5, 5, ".comp") == 0) return GL_COMPUTE_SHADER;
    throw DeviceError("unknown shader stage for " + file);
}
} // namespace

ProgramSource programSource(std::initializer_list<const char*> files, const ShaderFiles& extra)
{
    ProgramSource source;
    for (const char* file : files) {
        source.name += (source.name.empty() ? "" : ", ") + std::string(file);
        source.stages.emplace_back(file, shaderSource(file, extra));
    }
    return source;
}

Program::Program(std::initializer_list<const char*> files) : Program(programSource(files)) {}

Program::Program(const ShaderFiles& extra, std::initializer_list<const char*> files)
    : Program(programSource(files, extra))
{
}

Program::Program(const ProgramSource& source, bool retrievable) : files_(source.name)
{
    h_ = Handle<detail::deleteProgram>(glCreateProgram());
    std::vector<Handle<detail::deleteShader>> shaders;
    for (const auto& [file, src] : source.stages) {
        Handle<detail::deleteShader> s(glCreateShader(stageOf(file)));
        const char* text = src.text.c_str();
        glShaderSource(s.get(), 1, &text, nullptr);
        glCompileShader(s.get());
        GLint ok = 0;
        glGetShaderiv(s.get(), GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint len = 0;
            glGetShaderiv(s.get(), GL_INFO_LOG_LENGTH, &len);
            std::string log(size_t(std::max(len, 1)), '\0');
            glGetShaderInfoLog(s.get(), len, nullptr, log.data());
            throw DeviceError(fmt::format("shader {} does not compile on this driver: {}", file,
                                          nameFilesInLog(log.c_str(), src)));
        }
        glAttachShader(h_.get(), s.get());
        shaders.push_back(std::move(s));
    }
    if (retrievable) glProgramParameteri(h_.get(), GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    glLinkProgram(h_.get());
    GLint ok = 0;
    glGetProgramiv(h_.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(h_.get(), GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetProgramInfoLog(h_.get(), len, nullptr, log.data());
        throw DeviceError(fmt::format("shader program {} does not link: {}", files_, log.c_str()));
    }
    for (auto& s : shaders) glDetachShader(h_.get(), s.get());
    findUniforms();
    checkGl("shader program creation");
}

std::optional<Program> Program::fromBinary(const ProgramSource& source, GLenum format, const std::vector<uint8_t>& binary)
{
    // An error left by earlier work is reported as that work's, not taken for a refusal.
    checkGl(fmt::format("the GL work before loading program {}", source.name).c_str());
    Program p;
    p.files_ = source.name;
    p.h_ = Handle<detail::deleteProgram>(glCreateProgram());
    glProgramBinary(p.h_.get(), format, binary.data(), GLsizei(binary.size()));
    // A format the driver does not offer (any more) is GL_INVALID_ENUM; a
    // binary it cannot use leaves the link status false. Both are refusals.
    const GLenum err = glGetError();
    if (err == GL_INVALID_ENUM) return std::nullopt;
    if (err == GL_OUT_OF_MEMORY) throw OutOfMemory(fmt::format("the GPU ran out of memory loading program {}", source.name));
    if (err != GL_NO_ERROR)
        throw DeviceError(fmt::format("OpenGL error 0x{:04x} loading program {} from its binary", err, source.name));
    GLint ok = 0;
    glGetProgramiv(p.h_.get(), GL_LINK_STATUS, &ok);
    if (!ok) return std::nullopt;
    p.findUniforms();
    checkGl("shader program loading");
    return p;
}

std::vector<uint8_t> Program::binary(GLenum& format) const
{
    GLint length = 0;
    glGetProgramiv(h_.get(), GL_PROGRAM_BINARY_LENGTH, &length);
    checkGl("querying a program binary's length");
    format = 0;
    if (length <= 0) return {};
    std::vector<uint8_t> out(static_cast<size_t>(length));
    GLsizei written = 0;
    glGetProgramBinary(h_.get(), length, &written, &format, out.data());
    checkGl("reading a program binary");
    out.resize(size_t(std::max(written, 0)));
    return out;
}

void Program::findUniforms()
{
    // Uniforms in blocks and atomic counters have no location and are skipped.
    GLint count = 0, maxName = 0;
    glGetProgramInterfaceiv(h_.get(), GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    glGetProgramInterfaceiv(h_.get(), GL_UNIFORM, GL_MAX_NAME_LENGTH, &maxName);
    std::string name;
    for (GLint i = 0; i < count; ++i) {
        name.assign(size_t(std::max(maxName, 1)), '\0');
        GLsizei len = 0;
        glGetProgramResourceName(h_.get(), GL_UNIFORM, GLuint(i), GLsizei(name.size()), &len, name.data());
        name.resize(size_t(len));
        const GLenum property = GL_LOCATION;
        GLint loc = -1;
        glGetProgramResourceiv(h_.get(), GL_UNIFORM, GLuint(i), 1, &property, 1, nullptr, &loc);
        if (loc < 0) continue;
        // An array is listed as "name[0]"; glGetUniformLocation takes either spelling.
        if (name.size() > 3 && name.compare(name.size() - 3, 3, "[0]") == 0)
            locations_[name.substr(0, name.size() - 3)] = loc;
        locations_[name] = loc;
    }
}

GLint Program::location(const char* name) const
{
    const auto it = locations_.find(std::string_view(name));
    if (it == locations_.end())
        throw DeviceError(fmt::format("shader program {} has no active uniform {}: misspelt, or unused by the shaders "
                                      "and so removed by the linker",
                                      files_, name));
    return it->second;
}

void dispatchLooping(const Program& program, uint64_t count, uint32_t groups, uint64_t loopLimit,
                     uint64_t iterationsPerUnit, const char* first, const char* end)
{
    if (!count || !groups) return;
    const uint64_t perGroup = loopLimit ? std::max<uint64_t>(loopLimit / std::max<uint64_t>(iterationsPerUnit, 1), 1)
                                        : count;
    const uint64_t perDispatch = std::min<uint64_t>(uint64_t(groups) * perGroup, count);
    for (uint64_t from = 0; from < count; from += perDispatch) {
        program.set(first, uint32_t(from));
        program.set(end, uint32_t(std::min(count, from + perDispatch)));
        program.dispatch(groups);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

} // namespace svo::gl
