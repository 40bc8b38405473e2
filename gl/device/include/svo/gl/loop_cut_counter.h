#pragma once
/// @file loop_cut_counter.h
/// @brief svo::gl::LoopCutCounter: counting the invocations whose loops the driver cut short.
#include <cstdint>

#include "svo/gl/buffer.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"

namespace svo::gl {

/// @brief Counts the invocations of one dispatch whose loops the driver cut short
/// (ContextInfo::loopLimit): a shader that includes loop_cut.glsl and ends
/// with countIfLoopsWereCut() adds itself to a counter this owns. Passes
/// whose work per invocation cannot be cut into dispatches (a ray march, a
/// cone, a texel's shadow rays) use it to refuse a result the driver would
/// otherwise truncate without a word. Where the driver has no limit the probe
/// is off and nothing is read back.
class LoopCutCounter {
public:
    /// @brief Allocates the 4-byte counter.
    /// @throw svo::OutOfMemory, svo::DeviceError as Buffer's constructor
    LoopCutCounter() : buffer_("loop-cut counter", 4) {}
    /// @brief Zeroes the count, binds it and sets the program's probe.
    /// @param binding   the counter's storage binding (SVO_BIND_VIEW_LOOP_CUT)
    /// @param loopLimit ContextInfo::loopLimit; 0 turns the probe off
    /// @throw svo::DeviceError when @a program has no active uLoopProbe uniform
    void arm(const Program& program, GLuint binding, uint64_t loopLimit) const
    {
        limited_ = loopLimit != 0;
        buffer_.clearUint(0);
        buffer_.bindBase(GL_SHADER_STORAGE_BUFFER, binding);
        program.set("uLoopProbe", limited_ ? 2 : 0);
    }
    /// @brief The invocations cut since arm(), waiting for the dispatch.
    /// @return the count; 0 on drivers without the limit (nothing is read back)
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
