#pragma once
/// @file objects.h
/// Small owners for GL objects. Each holds one name, deletes it on
/// destruction, moves but never copies, and exposes operations rather than the
/// name itself. All use 4.5 direct state access.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "svo/gl/gl_api.h"
#include "svo/gl/shaders.h"

namespace svo::gl {

/// Movable ownership of one GL name; Deleter frees it.
template <void (*Deleter)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint name) : name_(name) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
    Handle& operator=(Handle&& o) noexcept
    {
        if (this != &o) { reset(); name_ = std::exchange(o.name_, 0); }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    GLuint get() const { return name_; }
    void reset()
    {
        if (name_) Deleter(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

namespace detail {
inline void deleteBuffer(GLuint n) { glDeleteBuffers(1, &n); }
inline void deleteVertexArray(GLuint n) { glDeleteVertexArrays(1, &n); }
inline void deleteFramebuffer(GLuint n) { glDeleteFramebuffers(1, &n); }
inline void deleteQuery(GLuint n) { glDeleteQueries(1, &n); }
inline void deleteProgram(GLuint n) { glDeleteProgram(n); }
inline void deleteShader(GLuint n) { glDeleteShader(n); }
inline void deleteTexture(GLuint n) { glDeleteTextures(1, &n); }
} // namespace detail

/// Immutable-storage buffer (glNamedBufferStorage). Allocation failure throws.
class Buffer {
public:
    Buffer() = default;
    /// `what` names the buffer in out-of-memory errors.
    Buffer(const char* what, uint64_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
    uint64_t bytes() const { return bytes_; }
    void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, h_.get()); }
    void bind(GLenum target) const { glBindBuffer(target, h_.get()); }
    /// Small reads (counters): glGetNamedBufferSubData.
    void read(uint64_t offset, uint64_t bytes, void* out) const
    {
        glGetNamedBufferSubData(h_.get(), GLintptr(offset), GLsizeiptr(bytes), out);
    }
    /// Bulk reads: a GPU copy into a host-visible staging buffer, then a
    /// mapped memcpy, in chunks of at most 64 MiB. Some drivers serve
    /// glGetNamedBufferSubData on device memory through a slow path.
    void readBulk(uint64_t offset, uint64_t bytes, void* out) const;
    void clearUint(uint32_t value) const
    {
        glClearNamedBufferData(h_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    }
    /// Clears only the first `bytes` (a multiple of 4): scratch buffers are
    /// often larger than one call needs.
    void clearUint(uint32_t value, uint64_t bytes) const
    {
        glClearNamedBufferSubData(h_.get(), GL_R32UI, 0, GLsizeiptr(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    }
    /// Uploads into a buffer made with GL_DYNAMIC_STORAGE_BIT (the default).
    void write(uint64_t offset, uint64_t bytes, const void* data) const
    {
        if (bytes) glNamedBufferSubData(h_.get(), GLintptr(offset), GLsizeiptr(bytes), data);
    }

private:
    friend class VertexArray;
    Handle<detail::deleteBuffer> h_;
    uint64_t bytes_ = 0;
};

/// Immutable-storage 2D texture of one level, read by texelFetch and written
/// as an image (the viewer's pixels). Allocation failure throws.
class Texture2D {
public:
    Texture2D() = default;
    /// `what` names the texture in out-of-memory errors.
    Texture2D(const char* what, GLenum internalFormat, int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }
    void bindTexture(GLuint unit) const { glBindTextureUnit(unit, h_.get()); }
    GLuint get() const { return h_.get(); } ///< the GL name, e.g. to attach it to a framebuffer
    /// Binds the texture as an image (imageLoad / imageStore); `format` is the image's layout qualifier format.
    void bindImage(GLuint unit, GLenum access, GLenum format) const
    {
        glBindImageTexture(unit, h_.get(), 0, GL_FALSE, 0, access, format);
    }

private:
    Handle<detail::deleteTexture> h_;
    int width_ = 0, height_ = 0;
};

/// Immutable-storage 3D texture with a full mip chain of `levels` levels
/// (glTextureStorage3D), trilinearly filtered between levels, clamped to
/// a transparent black border (outside the volume is empty). Allocation failure throws.
class Texture3D {
public:
    Texture3D() = default;
    /// `what` names the texture in out-of-memory errors.
    Texture3D(const char* what, GLenum internalFormat, int levels, int width, int height, int depth);
    int levels() const { return levels_; }
    /// Level `level`'s size along `axis` (GL's rule: halved and floored, at least 1).
    int size(int level, int axis) const { return std::max(1, size_[axis] >> level); }
    void bindTexture(GLuint unit) const { glBindTextureUnit(unit, h_.get()); }
    /// Nearest filtering, as integer textures need to be complete.
    void nearest() const
    {
        glTextureParameteri(h_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(h_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    /// Binds one level as an image (imageLoad / imageStore); `format` is the image's layout qualifier format.
    void bindImage(GLuint unit, int level, GLenum access, GLenum format) const
    {
        glBindImageTexture(unit, h_.get(), level, GL_TRUE, 0, access, format);
    }
    /// Reads one level back as `format`/`type` (glGetTextureImage) into `bytes` bytes at `out`.
    void read(int level, GLenum format, GLenum type, uint64_t bytes, void* out) const
    {
        glGetTextureImage(h_.get(), level, format, type, GLsizei(bytes), out);
    }

private:
    Handle<detail::deleteTexture> h_;
    int levels_ = 0;
    int size_[3] = {0, 0, 0};
};

/// A vertex array with one float3 attribute and an element buffer.
class VertexArray {
public:
    VertexArray();
    void setPositions(const Buffer& vertices, GLuint location);
    void setIndices(const Buffer& indices);
    void bind() const { glBindVertexArray(h_.get()); }

private:
    Handle<detail::deleteVertexArray> h_;
};

/// A framebuffer with no attachments: rasterization without a colour target.
class EmptyFramebuffer {
public:
    EmptyFramebuffer(int width, int height);
    void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, h_.get()); }

private:
    Handle<detail::deleteFramebuffer> h_;
};

/// GPU time between begin() and end(), from a pair of GL_TIMESTAMP queries.
/// (Mesa's llvmpipe returns garbage for GL_TIME_ELAPSED; timestamps measure the
/// same interval on every driver.) The result is read later.
class TimerQuery {
public:
    TimerQuery();
    void begin() const { glQueryCounter(begin_.get(), GL_TIMESTAMP); }
    void end() const { glQueryCounter(end_.get(), GL_TIMESTAMP); }
    /// Waits for the GPU; milliseconds.
    double milliseconds() const;

private:
    Handle<detail::deleteQuery> begin_, end_;
};

/// Waits until the GPU has finished the commands issued so far, in slices of
/// 20 ms, calling `poll` between slices (it may throw to stop waiting).
void waitForGpu(const std::function<void()>& poll);

/// A program's stages with their #include lines expanded: what the driver
/// compiles, and so what a cached binary of it is keyed by.
struct ProgramSource {
    std::string name;                                        ///< "a.vert, a.frag", for messages
    std::vector<std::pair<std::string, ShaderSource>> stages; ///< file name, expanded text
};

/// The expanded stages of `files`, looked up in `extra` before the embedded
/// files. Throws svo::Error for an unknown file or an include cycle.
ProgramSource programSource(std::initializer_list<const char*> files, const ShaderFiles& extra = {});

/// A linked program from embedded shader files (see shaders.h), compiled or
/// loaded from a binary the driver gave earlier.
class Program {
public:
    /// Stage files by name, e.g. {"raster.vert", "raster.geom", "raster.frag"}.
    /// Throws svo::Error with the compiler log, its lines naming files, on failure.
    Program(std::initializer_list<const char*> files);
    /// The same, looking files up in `extra` before the embedded ones.
    Program(const ShaderFiles& extra, std::initializer_list<const char*> files);
    /// Compiles and links `source`. `retrievable` asks the driver to keep the
    /// linked binary for binary(). Throws as above.
    explicit Program(const ProgramSource& source, bool retrievable = false);

    /// A program from a binary that binary() returned, or nothing when the
    /// driver refuses it (another driver or GPU, a damaged binary, a format it
    /// no longer offers): the caller compiles instead. Throws svo::Error for a
    /// GL error left by earlier work, or one other than the refusal.
    static std::optional<Program> fromBinary(const ProgramSource& source, GLenum format,
                                             const std::vector<uint8_t>& binary);
    /// The linked binary and its format (glGetProgramBinary); empty when the
    /// driver keeps none. Throws svo::Error on a GL error.
    std::vector<uint8_t> binary(GLenum& format) const;

    /// set() throws svo::Error for a name that is not an active uniform:
    /// misspelt, or unused by the shaders and so removed by the linker.
    void use() const { glUseProgram(h_.get()); }
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
    /// A mat4 uniform from 16 floats in column-major order (GLSL's).
    void setMatrix(const char* name, const float* columnMajor) const
    {
        glProgramUniformMatrix4fv(h_.get(), location(name), 1, GL_FALSE, columnMajor);
    }
    /// Compute programs: `groups` work groups along x.
    void dispatch(uint32_t groups) const
    {
        use();
        glDispatchCompute(groups, 1, 1);
    }
    /// Compute programs: x by y work groups.
    void dispatch(uint32_t x, uint32_t y) const
    {
        use();
        glDispatchCompute(x, y, 1);
    }
    /// Compute programs: group counts read on the GPU from `args` at byte `offset`.
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

/// Runs compute `program` as `groups` workgroups (along x) that loop over
/// units [0, count): the shader takes units [uniform `first`, uniform `end`),
/// group g the units first + g, first + g + groups, and so on. Where the
/// driver silently ends an invocation's loops after `loopLimit` iterations in
/// all (ContextInfo::loopLimit; 0: no limit), the units are cut into as many
/// dispatches as keep each invocation under it, given at most
/// `iterationsPerUnit` loop iterations a unit (the loop's own included);
/// otherwise one dispatch. A storage barrier follows each dispatch.
void dispatchLooping(const Program& program, uint64_t count, uint32_t groups, uint64_t loopLimit,
                     uint64_t iterationsPerUnit, const char* first, const char* end);

/// Counts the invocations of one dispatch whose loops the driver cut short
/// (ContextInfo::loopLimit): a shader that includes loop_cut.glsl and ends
/// with countIfLoopsWereCut() adds itself to a counter this owns. Passes
/// whose work per invocation cannot be cut into dispatches (a ray march, a
/// cone, a texel's shadow rays) use it to refuse a result the driver would
/// otherwise truncate without a word. Where the driver has no limit the probe
/// is off and nothing is read back.
class LoopCutCounter {
public:
    LoopCutCounter() : buffer_("loop-cut counter", 4) {}
    /// Zeroes the count, binds it to `binding` (SVO_BIND_VIEW_LOOP_CUT) and
    /// sets the program's probe for a driver with this loop limit.
    void arm(const Program& program, GLuint binding, uint64_t loopLimit) const
    {
        limited_ = loopLimit != 0;
        buffer_.clearUint(0);
        buffer_.bindBase(GL_SHADER_STORAGE_BUFFER, binding);
        program.set("uLoopProbe", limited_ ? 2 : 0);
    }
    /// The invocations cut since arm() (waits for the dispatch); 0 on drivers without the limit.
    uint32_t count() const
    {
        uint32_t n = 0;
        if (limited_) buffer_.read(0, 4, &n);
        return n;
    }

private:
    Buffer buffer_;
    mutable bool limited_ = false;
};


} // namespace svo::gl
