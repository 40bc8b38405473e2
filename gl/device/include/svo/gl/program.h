#pragma once
/// @file program.h
/// @brief svo::gl::Program: a linked GL program, compiled from its expanded
/// stages (program_source.h) or loaded from a driver's binary.
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "svo/gl/buffer.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/handle.h"
#include "svo/gl/program_source.h"
#include "svo/gl/shader_files.h"

namespace svo::gl {

/// @brief A linked program from embedded shader files (see shader_source.h),
/// compiled or loaded from a binary the driver gave earlier. Calls need a
/// current Context.
class Program {
public:
    /// @brief Compiles and links stage files by name, e.g. {"raster.vert",
    /// "raster.geom", "raster.frag"}.
    /// @throw svo::DeviceError for an unknown file or include cycle, or with
    ///        the compiler log, its lines naming files, when a stage does not
    ///        compile or the program does not link; svo::OutOfMemory or
    ///        svo::DeviceError for a GL error (checkGl)
    Program(std::initializer_list<const char*> files);
    /// @brief The same, looking files up in @a extra before the embedded ones.
    /// @throw as above
    Program(const ShaderFiles& extra, std::initializer_list<const char*> files);
    /// @brief Compiles and links @a source.
    /// @param retrievable asks the driver to keep the linked binary for binary()
    /// @throw as above, but for the file lookup
    explicit Program(const ProgramSource& source, bool retrievable = false);

    /// @brief A program from a binary that binary() returned.
    /// @return the program, or nothing when the driver refuses the binary
    ///         (another driver or GPU, a damaged binary, a format it no longer
    ///         offers): the caller compiles instead
    /// @throw svo::OutOfMemory or svo::DeviceError for a GL error left by
    ///        earlier work, or one other than the refusal
    static std::optional<Program> fromBinary(const ProgramSource& source, GLenum format,
                                             const std::vector<uint8_t>& binary);
    /// @brief The linked binary (glGetProgramBinary).
    /// @param format receives the binary's format
    /// @return the binary; empty when the driver keeps none
    /// @throw svo::OutOfMemory or svo::DeviceError on a GL error
    std::vector<uint8_t> binary(GLenum& format) const;

    /// @brief Makes it the current program (glUseProgram).
    void use() const { glUseProgram(h_.get()); }
    /// @brief Sets uniform @a name; the overloads follow GLSL's types (float,
    /// int, uint, vec2, ivec3, uint[], uvec3, vec3, vec4).
    /// @throw svo::DeviceError for a name that is not an active uniform:
    ///        misspelt, or unused by the shaders and so removed by the linker
    void set(const char* name, float v) const { glProgramUniform1f(h_.get(), location(name), v); }
    void set(const char* name, int v) const { glProgramUniform1i(h_.get(), location(name), v); }
    void set(const char* name, float x, float y) const { glProgramUniform2f(h_.get(), location(name), x, y); }
    void set(const char* name, int x, int y, int z) const { glProgramUniform3i(h_.get(), location(name), x, y, z); }
    void set(const char* name, uint32_t v) const { glProgramUniform1ui(h_.get(), location(name), v); }
    void set(const char* name, const std::vector<uint32_t>& v) const
    {
        glProgramUniform1uiv(h_.get(), location(name), GLsizei(v.size()), v.data());
    }
    void set(const char* name, uint32_t x, uint32_t y, uint32_t z) const
    {
        glProgramUniform3ui(h_.get(), location(name), x, y, z);
    }
    void set(const char* name, float x, float y, float z) const
    {
        glProgramUniform3f(h_.get(), location(name), x, y, z);
    }
    void set(const char* name, float x, float y, float z, float w) const
    {
        glProgramUniform4f(h_.get(), location(name), x, y, z, w);
    }
    /// @brief Sets a mat4 uniform from 16 floats in column-major order (GLSL's).
    /// @throw svo::DeviceError as set()
    void setMatrix(const char* name, const float* columnMajor) const
    {
        glProgramUniformMatrix4fv(h_.get(), location(name), 1, GL_FALSE, columnMajor);
    }
    /// @brief Dispatches a compute program as @a groups work groups along x.
    void dispatch(uint32_t groups) const
    {
        use();
        glDispatchCompute(groups, 1, 1);
    }
    /// @brief Dispatches a compute program as @a x by @a y work groups.
    void dispatch(uint32_t x, uint32_t y) const
    {
        use();
        glDispatchCompute(x, y, 1);
    }
    /// @brief Dispatches @a groups work groups, as many rows of up to 65535
    /// along x as they need (the most one dimension takes); the shader
    /// flattens them as gl_WorkGroupID.x + gl_NumWorkGroups.x *
    /// gl_WorkGroupID.y and skips the ids of the last row past @a groups.
    /// Nothing runs for 0.
    void dispatchRows(uint64_t groups) const
    {
        if (!groups) return;
        const uint64_t x = groups < 65535 ? groups : 65535;
        dispatch(uint32_t(x), uint32_t((groups + x - 1) / x));
    }
    /// @brief Dispatches a compute program with group counts read on the GPU
    /// from @a args at byte @a offset (glDispatchComputeIndirect).
    void dispatchIndirect(const Buffer& args, uint64_t offset) const
    {
        use();
        args.bind(GL_DISPATCH_INDIRECT_BUFFER);
        glDispatchComputeIndirect(GLintptr(offset));
    }

private:
    Program() = default;
    /// Fills locations_ from the linked program.
    void findUniforms();
    GLint location(const char* name) const;
    Handle<detail::deleteProgram> h_;
    std::string files_; ///< "a.vert, a.frag", for messages
    /// Every active uniform that has a location, resolved once after linking.
    std::map<std::string, GLint, std::less<>> locations_;
};

} // namespace svo::gl
