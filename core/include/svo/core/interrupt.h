#pragma once
/// @file interrupt.h
/// @brief Cancellation and progress: how a long call hears from its caller.
///
/// A Checkpoint wraps the caller's poll function (the public API adapts an
/// openvdb::util::NullInterrupter to it). Work calls the checkpoint between
/// stages and between tiles with the fraction of its part done; the poll gets
/// the whole call's percentage, and when it answers true the checkpoint throws
/// svo::Interrupted. Work split into parts hands each part a sub-range with
/// part(), so percentages stay monotonic across stages.
#include <algorithm>
#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "svo/core/error.h"

namespace svo {

/// @brief The caller's poll function, scaled to the part of a call's work at hand.
class Checkpoint {
public:
    /// @brief Gets the percentage done (0..100); returns true to cancel.
    using Poll = std::function<bool(int percent)>;

    Checkpoint() = default; ///< polls nothing, never cancels
    /// @brief Polls @a poll over the whole range [0, 1].
    explicit Checkpoint(Poll poll) : poll_(std::move(poll)) {}

    /// @brief Reports progress to the poll, if any.
    /// @param fraction how much of this part is done, clamped to [0, 1]
    /// @param where    names the step for the message
    /// @throw svo::Interrupted when the poll asks to stop
    void operator()(double fraction, const char* where = "") const
    {
        if (!poll_) return;
        const double f = from_ + (to_ - from_) * (fraction < 0 ? 0 : fraction > 1 ? 1 : fraction);
        int percent = int(f * 100.0);
        if (highest_) { // the most reported so far, from any thread
            int seen = highest_->load();
            while (seen < percent && !highest_->compare_exchange_weak(seen, percent)) {
            }
            percent = std::max(percent, seen);
        }
        if (poll_(percent))
            throw Interrupted(std::string("interrupted") + (*where ? std::string(" during ") + where : std::string()));
    }

    /// @brief This part, never reporting less than it (or its parts) reported
    /// before: for work tried again, such as a field cut into regions after
    /// its whole grid passed a GPU memory budget, whose retry starts below
    /// where the first try stopped.
    Checkpoint monotonic() const
    {
        Checkpoint c = *this;
        if (!c.highest_) c.highest_ = std::make_shared<std::atomic<int>>(0); // already: the same floor
        return c;
    }

    /// @brief The sub-range [a, b] of this part (fractions of it) as a part of its own.
    Checkpoint part(double a, double b) const
    {
        Checkpoint c = *this;
        c.from_ = from_ + (to_ - from_) * a;
        c.to_ = from_ + (to_ - from_) * b;
        return c;
    }

private:
    Poll poll_;
    double from_ = 0.0, to_ = 1.0;
    std::shared_ptr<std::atomic<int>> highest_; ///< monotonic(): shared by its parts
};

} // namespace svo
