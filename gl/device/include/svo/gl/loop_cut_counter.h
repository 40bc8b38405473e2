#pragma once
/// @file loop_cut_counter.h
/// Counting the invocations whose loops the driver cut short.
#include <cstdint>

#include "svo/gl/buffer.h"
#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"

namespace svo::gl {

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
