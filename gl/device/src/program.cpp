#include "svo/gl/program.h"

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>
#include <fmt/format.h>

#include "svo/gl/shader_source.h"
#include "svo/core/error.h"

namespace svo::gl {

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

} // namespace svo::gl
