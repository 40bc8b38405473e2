#include "svo/gl/dispatch_looping.h"

#include <algorithm>

#include "svo/gl/gl_api.h"
#include "svo/gl/program.h"

namespace svo::gl {

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
