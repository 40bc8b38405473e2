#pragma once
// What the Voxelizer's source files share (voxelizer.cpp, level_set.cpp): the
// call bracket for interrupters, and the transform rule of distance fields.
#include <chrono>

#include "svo/core/interrupt.h"
#include "svo/voxelizer.h"

namespace svo::detail {

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// Brackets a call with the interrupter's start() and end(), on every path
/// out, and turns it into the checkpoint svo's stages poll.
class InterruptScope {
public:
    InterruptScope(openvdb::util::NullInterrupter* interrupter, const char* what) : interrupter_(interrupter)
    {
        if (interrupter_) interrupter_->start(what);
    }
    ~InterruptScope()
    {
        if (interrupter_) interrupter_->end();
    }
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;

    Checkpoint checkpoint() const
    {
        if (!interrupter_) return {};
        auto* i = interrupter_;
        return Checkpoint([i](int percent) { return i->wasInterrupted(percent); });
    }

private:
    openvdb::util::NullInterrupter* interrupter_;
};

/// The uniform scale of a transform (world units per index unit).
/// @throw svo::Unsupported for a transform without uniform scale.
double uniformScale(const openvdb::math::Transform& xform);

} // namespace svo::detail
